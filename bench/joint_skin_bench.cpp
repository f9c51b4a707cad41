// Time per frame of the wire rig's skin against the skinning engines ship, on the same rig,
// bones, blend region and pose (the quality side of the comparison is `wirerig rig
// --joint-report`; see docs/benchmarks.md):
//  * BM_WireRigSkin: EvaluateRigJob on human.zae's bone-chain rig (18 rigid parts, skin bridges
//    at every joint), positions and normals (doubles), one thread; BM_WireRigSkinFloat: the
//    same into float buffers (normals:0: positions only).
//  * BM_LinearBlend, BM_DualQuaternion, BM_CentresOfRotation: ReferenceSkinningJob (float, one
//    array per attribute, 4 influences, positions and normals; linear blend vectorised as
//    ozz-animation's SkinningJob is) with the bone matrices of the same pose.
// The pose bends every joint: elbows and knees 60 degrees, shoulders and hips 45 about their
// second and first axes, the spine, neck and head 15, wrists and ankles 20.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "bench_setup.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/reference_skinning.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_model_builder.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {
namespace {

using bench::Check;

struct Scene {
  Mesh mesh;
  RigModel model;
  std::vector<PartPose> poses;
  ReferenceSkin skin;
  std::vector<BoneMatrix> bones;
};

Vec3 BusyAngles(const std::string& name) {
  if (name.starts_with("forearm") || name.starts_with("shin")) return {60, 0, 0};
  if (name.starts_with("upper_arm")) return {0, 45, 0};
  if (name.starts_with("thigh")) return {-45, 0, 0};
  if (name.starts_with("hand") || name.starts_with("foot")) return {20, 0, 0};
  return {15, 0, 0};
}

const Scene& Human() {
  static const Scene scene = [] {
    Scene s;
    const RigDescription description =
        Check(LoadRigDescription(std::string(WIRERIG_SAMPLES_DIR) + "/rigs/human.description.json"),
              "human.description.json");
    s.mesh = Check(ImportMesh(description.mesh.string(), description.import), "human.zae").mesh;
    const Rig rig = Check(BuildRig(s.mesh, description, "human.zae"), "rig").rig;
    RigModelOptions options;
    options.spine_kind = SpineKind::kRigid;
    s.model = Check(BuildRigModel(s.mesh, rig, options), "model").model;
    s.poses.resize(s.model.parts.size());
    for (std::size_t i = 1; i < s.model.parts.size(); ++i)
      s.poses[i].rotation =
          JointRotation(s.model.parts[i].joint, BusyAngles(s.model.parts[i].name));
    s.skin = MakeReferenceSkin(s.model, s.mesh.welded_positions);
    RigWorkspace workspace = MakeRigWorkspace(s.model);
    std::vector<Vec3> positions(s.model.vertices.size());
    EvaluateRigJob job;
    job.model = &s.model;
    job.poses = s.poses;
    job.workspace = &workspace;
    job.positions = positions;
    if (!job.Run()) std::exit(1);
    s.bones.resize(s.model.parts.size());
    BoneMatricesFromWorkspace(s.model, workspace, s.bones);
    return s;
  }();
  return scene;
}

void BM_WireRigSkin(benchmark::State& state) {
  const Scene& s = Human();
  RigWorkspace workspace = MakeRigWorkspace(s.model);
  std::vector<Vec3> positions(s.model.vertices.size()), normals(positions.size());
  EvaluateRigJob job;
  job.model = &s.model;
  job.poses = s.poses;
  job.workspace = &workspace;
  job.positions = positions;
  job.normals = normals;
  for (auto _ : state) {
    if (!job.Run()) state.SkipWithError("evaluation failed");
    benchmark::DoNotOptimize(positions.data());
    benchmark::ClobberMemory();
  }
  state.counters["vertices"] = double(positions.size());
  state.counters["bridged"] = double(workspace.plan->layout.joint_vertices.size());
}
BENCHMARK(BM_WireRigSkin)->Unit(benchmark::kMicrosecond);

// The same frame into float engine buffers (the float evaluation, four vertices at a time);
// normals:0 writes positions only (what the normals cost is the difference).
void BM_WireRigSkinFloat(benchmark::State& state) {
  const Scene& s = Human();
  RigWorkspace workspace = MakeRigWorkspace(s.model);
  std::vector<float> positions(3 * s.model.vertices.size()), normals(positions.size());
  EvaluateRigJob job;
  job.model = &s.model;
  job.poses = s.poses;
  job.workspace = &workspace;
  job.float_positions = positions;
  if (state.range(0) == 1) job.float_normals = normals;
  for (auto _ : state) {
    if (!job.Run()) state.SkipWithError("evaluation failed");
    benchmark::DoNotOptimize(positions.data());
    benchmark::ClobberMemory();
  }
  state.counters["vertices"] = double(s.model.vertices.size());
  state.counters["bridged"] = double(workspace.plan->layout.joint_vertices.size());
}
BENCHMARK(BM_WireRigSkinFloat)->ArgName("normals")->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond);

void RunReference(benchmark::State& state, ReferenceSkinning method) {
  const Scene& s = Human();
  const std::size_t n = s.model.vertices.size();
  std::vector<float> x(n), y(n), z(n), nx(n), ny(n), nz(n);
  const ReferenceSkinningJob job{method, &s.skin, s.bones, x, y, z, nx, ny, nz};
  for (auto _ : state) {
    job.Run();
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  state.counters["vertices"] = double(n);
}
void BM_LinearBlend(benchmark::State& state) {
  RunReference(state, ReferenceSkinning::kLinearBlend);
}
void BM_DualQuaternion(benchmark::State& state) {
  RunReference(state, ReferenceSkinning::kDualQuaternion);
}
void BM_CentresOfRotation(benchmark::State& state) {
  RunReference(state, ReferenceSkinning::kCentreOfRotation);
}
BENCHMARK(BM_LinearBlend)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DualQuaternion)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CentresOfRotation)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
