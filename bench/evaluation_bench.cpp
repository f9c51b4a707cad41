// Per-frame cost of the wire rig against the usual baseline, and the cost of its binding.
//  * BM_WireEvaluation: EvaluateRigJob on human.zae rigged by samples/rigs/human.description.json,
//    every part turned a little and bent by a point load on its spine; positions and normals.
//  * BM_LinearBlendSkinning: the baseline, a plain 4-influence linear blend skinning of the same
//    welded vertices (positions and normals, doubles like the wire path). Joints are the rig's
//    spine samples (a chain per part, hung from the parent's sample at the attachment); each
//    vertex takes its 4 nearest joints with inverse-distance weights, all non-zero. Every
//    frame: forward kinematics from local rotations (the parts' poses at their first joints,
//    a small bend spread over the rest), skinning matrices, then the vertices.
//  * /subdivided: the same on human.zae refined to kSubdividedVertices welded vertices (a
//    midpoint 1-to-4 split of every triangle, then the longest edges split once more).
//  * /2_threads: the wire evaluation with its vertex and normal passes on a 2-thread pool
//    (EvaluateRigJob::parallel); wall time.
//  * BM_WireEvaluationFloat: the same into float engine buffers (the float evaluation; avx2:1
//    lets it use eight lanes where the CPU has AVX2, avx2:0 keeps SSE2's four);
//    BM_ReferenceLinearBlend: linear blend skinning as engines write it (float, one array per
//    attribute, 4 influences, vectorised as ozz-animation's SkinningJob; rig/reference_skinning.h),
//    one bone per part, same pose. The *_rotated_normals rows: the float evaluation with its
//    normals the rest normals turned with each vertex's frame (NormalMode::kRotated).
//  * BM_BindingPrecompute: BuildRigModel alone on the subdivided mesh. Target: under 200 ms
//    for 100k vertices. BM_MakeWorkspace: MakeRigWorkspace on it (flat binding layout).
// One thread each unless named; meshes, rigs, models and skins are built once, outside the timed
// loops.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "bench_setup.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/reference_skinning.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_description.h"
#include "wirerig/rig/rig_model_builder.h"
#include "wirerig/runtime/rig_evaluation.h"

#ifndef WIRERIG_ASSET_DIR
#error "the benchmarks need WIRERIG_ASSET_DIR (set by CMake)"
#endif
#ifndef WIRERIG_SAMPLES_DIR
#error "the benchmarks need WIRERIG_SAMPLES_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {

constexpr std::size_t kSubdividedVertices = 100'000;

using bench::Check;

// ---------------------------------------------------------------------------------------------
// Subdivision of a welded mesh.

// Splits the marked edges of a welded mesh at their midpoints, shared by the triangles on either
// side, so the result stays conforming and welded (weld map the identity). A triangle with 3
// marked edges becomes 4 (the midpoint 1-to-4 split), with 2 becomes 3 (the corner, and the rest
// cut along its shorter diagonal), with 1 becomes 2. Children follow their parent's place, so
// mesh parts stay contiguous triangle ranges; orientation is kept.
struct EdgeTable {
  std::vector<std::array<std::uint32_t, 2>> edges;        // unique, by welded vertex
  std::vector<std::array<std::uint32_t, 3>> of_triangle;  // edges (t0 t1), (t1 t2), (t2 t0)
};

EdgeTable MakeEdgeTable(const std::vector<Triangle>& triangles) {
  EdgeTable table;
  std::unordered_map<std::uint64_t, std::uint32_t> index;
  index.reserve(triangles.size() * 2);
  table.of_triangle.reserve(triangles.size());
  for (const Triangle& t : triangles) {
    std::array<std::uint32_t, 3> e{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = std::min(t[k], t[(k + 1) % 3]), b = std::max(t[k], t[(k + 1) % 3]);
      const auto [it, added] =
          index.try_emplace((std::uint64_t(a) << 32) | b, std::uint32_t(table.edges.size()));
      if (added) table.edges.push_back({a, b});
      e[k] = it->second;
    }
    table.of_triangle.push_back(e);
  }
  return table;
}

Mesh SplitEdges(const Mesh& mesh, const EdgeTable& table, const std::vector<bool>& marked) {
  const std::vector<Vec3>& p = mesh.welded_positions;
  Mesh out;
  out.positions = p;
  std::vector<std::uint32_t> midpoint(table.edges.size(), UINT32_MAX);
  for (std::size_t e = 0; e < table.edges.size(); ++e) {
    const auto [a, b] = table.edges[e];
    if (!marked[e] || a == b) continue;
    midpoint[e] = std::uint32_t(out.positions.size());
    out.positions.push_back(0.5 * (p[a] + p[b]));
  }
  const std::vector<Vec3>& q = out.positions;
  std::vector<std::uint32_t> first_child(mesh.welded_triangles.size() + 1);
  for (std::size_t f = 0; f < mesh.welded_triangles.size(); ++f) {
    first_child[f] = std::uint32_t(out.triangles.size());
    const Triangle& t = mesh.welded_triangles[f];
    std::array<std::uint32_t, 3> m{};
    int count = 0;
    for (int k = 0; k < 3; ++k) count += (m[k] = midpoint[table.of_triangle[f][k]]) != UINT32_MAX;
    // Turn the triangle so the pattern starts at corner r: edge k joins corner k to corner k+1.
    int r = 0;
    if (count == 1)
      while (m[r] == UINT32_MAX) ++r;  // the marked edge first
    if (count == 2)
      while (m[(r + 2) % 3] != UINT32_MAX) ++r;  // the unmarked edge last
    const std::uint32_t a = t[r], b = t[(r + 1) % 3], c = t[(r + 2) % 3];
    const std::uint32_t ab = m[r], bc = m[(r + 1) % 3], ca = m[(r + 2) % 3];
    switch (count) {
      case 0:
        out.triangles.push_back(t);
        break;
      case 1:
        out.triangles.push_back({a, ab, c});
        out.triangles.push_back({ab, b, c});
        break;
      case 2:
        out.triangles.push_back({ab, b, bc});
        if ((q[a] - q[bc]).squaredNorm() <= (q[ab] - q[c]).squaredNorm()) {
          out.triangles.push_back({a, ab, bc});
          out.triangles.push_back({a, bc, c});
        } else {
          out.triangles.push_back({a, ab, c});
          out.triangles.push_back({ab, bc, c});
        }
        break;
      default:
        out.triangles.push_back({a, ab, ca});
        out.triangles.push_back({ab, b, bc});
        out.triangles.push_back({ca, bc, c});
        out.triangles.push_back({ab, bc, ca});
        break;
    }
  }
  first_child.back() = std::uint32_t(out.triangles.size());
  for (const MeshPart& part : mesh.parts) {
    MeshPart copy = part;
    copy.first_triangle = first_child[part.first_triangle];
    copy.triangle_count =
        first_child[part.first_triangle + part.triangle_count] - copy.first_triangle;
    out.parts.push_back(copy);
  }
  out.materials = mesh.materials;
  out.weld_map.resize(out.positions.size());
  for (std::size_t v = 0; v < out.weld_map.size(); ++v) out.weld_map[v] = std::uint32_t(v);
  out.welded_positions = out.positions;
  out.welded_triangles = out.triangles;
  return out;
}

// Every edge split once (about 4x the vertices), then the longest edges split until the mesh
// has `target` welded vertices (each split edge adds one).
Mesh Subdivide(const Mesh& mesh, std::size_t target) {
  EdgeTable table = MakeEdgeTable(mesh.welded_triangles);
  Mesh once = SplitEdges(mesh, table, std::vector<bool>(table.edges.size(), true));
  if (once.welded_positions.size() >= target) return once;
  table = MakeEdgeTable(once.welded_triangles);
  std::vector<std::pair<double, std::uint32_t>> by_length;
  for (std::size_t e = 0; e < table.edges.size(); ++e) {
    const auto [a, b] = table.edges[e];
    if (a != b)
      by_length.push_back(
          {-(once.welded_positions[a] - once.welded_positions[b]).squaredNorm(), std::uint32_t(e)});
  }
  const std::size_t splits = std::min(by_length.size(), target - once.welded_positions.size());
  std::nth_element(by_length.begin(), by_length.begin() + long(splits), by_length.end());
  std::vector<bool> marked(table.edges.size(), false);
  for (std::size_t i = 0; i < splits; ++i) marked[by_length[i].second] = true;
  return SplitEdges(once, table, marked);
}

// ---------------------------------------------------------------------------------------------
// The baseline: 4-influence linear blend skinning.

using Mat34 = Eigen::Matrix<double, 3, 4>;  // [rotation | translation], column-major

struct LinearBlendSkin {
  // Joints, parents first. Bind pose: the identity rotation at the joint's rest position.
  std::vector<int> joint_parent;   // -1 for the root
  std::vector<Vec3> joint_rest;    // world
  std::vector<Vec3> joint_offset;  // rest position minus the parent's
  // Per welded vertex.
  std::vector<Vec3> rest_positions;
  std::vector<Vec3> rest_normals;
  std::vector<std::array<std::uint32_t, 4>> influence_joints;
  std::vector<Eigen::Vector4d> influence_weights;  // all > 0, summing to 1
};

// The per-frame input of the skin: a local rotation per joint (about the joint, in its parent's
// axes) and the root's translation.
struct SkinPose {
  std::vector<Quat> local_rotations;
  Vec3 root_translation = Vec3::Zero();
};

// Per-frame scratch, allocated once.
struct SkinWorkspace {
  std::vector<Mat3> global_rotations;
  std::vector<Vec3> global_translations;
  std::vector<Mat34> skinning;  // global * inverse bind
};

void EvaluateSkin(const LinearBlendSkin& skin, const SkinPose& pose, SkinWorkspace& w,
                  std::span<Vec3> positions, std::span<Vec3> normals) {
  // Forward kinematics and skinning matrices.
  const std::size_t joints = skin.joint_parent.size();
  for (std::size_t j = 0; j < joints; ++j) {
    const Mat3 local = pose.local_rotations[j].toRotationMatrix();
    const int parent = skin.joint_parent[j];
    if (parent < 0) {
      w.global_rotations[j] = local;
      w.global_translations[j] = skin.joint_rest[j] + pose.root_translation;
    } else {
      w.global_rotations[j] = w.global_rotations[parent] * local;
      w.global_translations[j] =
          w.global_translations[parent] + w.global_rotations[parent] * skin.joint_offset[j];
    }
    w.skinning[j].leftCols<3>() = w.global_rotations[j];
    w.skinning[j].col(3) = w.global_translations[j] - w.global_rotations[j] * skin.joint_rest[j];
  }
  // Vertices: the weighted sum of the 4 matrices, applied to the rest position and normal.
  const Mat34* s = w.skinning.data();
  const std::size_t vertices = skin.rest_positions.size();
  for (std::size_t v = 0; v < vertices; ++v) {
    const std::array<std::uint32_t, 4>& j = skin.influence_joints[v];
    const Eigen::Vector4d& k = skin.influence_weights[v];
    const Mat34 m = k[0] * s[j[0]] + k[1] * s[j[1]] + k[2] * s[j[2]] + k[3] * s[j[3]];
    positions[v] = m.leftCols<3>() * skin.rest_positions[v] + m.col(3);
    normals[v] = (m.leftCols<3>() * skin.rest_normals[v]).normalized();
  }
}

// Joints from the model's spine samples; weights from the 4 nearest joints.
LinearBlendSkin MakeSkin(const RigModel& model, const Mesh& mesh) {
  LinearBlendSkin skin;
  std::vector<std::size_t> first_joint;
  for (const PartModel& part : model.parts) {
    first_joint.push_back(skin.joint_rest.size());
    const std::size_t n = part.spine_points.size();
    for (std::size_t k = 0; k < n; ++k) {
      int parent = int(skin.joint_rest.size()) - 1;
      if (k == 0)
        parent =
            part.parent < 0
                ? -1
                : int(first_joint[std::size_t(part.parent)] +
                      std::size_t(std::lround(
                          part.attachment *
                          double(model.parts[std::size_t(part.parent)].spine_points.size() - 1))));
      skin.joint_parent.push_back(parent);
      skin.joint_rest.push_back(part.spine_points[k]);
      skin.joint_offset.push_back(
          parent < 0 ? Vec3::Zero()
                     : Vec3(part.spine_points[k] - skin.joint_rest[std::size_t(parent)]));
    }
  }
  skin.rest_positions = mesh.welded_positions;
  skin.rest_normals.assign(mesh.welded_positions.size(), Vec3::Zero());
  for (const Triangle& t : mesh.welded_triangles) {
    const Vec3& a = mesh.welded_positions[t[0]];
    const Vec3 n = (mesh.welded_positions[t[1]] - a).cross(mesh.welded_positions[t[2]] - a);
    for (std::uint32_t v : t) skin.rest_normals[v] += n;
  }
  for (Vec3& n : skin.rest_normals) {
    const double length = n.norm();
    n = length > 0.0 ? Vec3(n / length) : Vec3::UnitY();
  }
  constexpr double kSoftening = 1e-3;  // m: a vertex on a joint still shares its weight
  for (const Vec3& p : skin.rest_positions) {
    std::array<std::pair<double, std::uint32_t>, 4> best;
    best.fill({std::numeric_limits<double>::max(), 0});
    for (std::size_t j = 0; j < skin.joint_rest.size(); ++j) {
      const double d = (skin.joint_rest[j] - p).squaredNorm();
      if (d >= best[3].first) continue;
      best[3] = {d, std::uint32_t(j)};
      std::sort(best.begin(), best.end());
    }
    std::array<std::uint32_t, 4> joints{};
    Eigen::Vector4d weights;
    for (int i = 0; i < 4; ++i) {
      joints[std::size_t(i)] = best[std::size_t(i)].second;
      const double d = std::sqrt(best[std::size_t(i)].first) + kSoftening;
      weights[i] = 1.0 / (d * d);
    }
    skin.influence_joints.push_back(joints);
    skin.influence_weights.push_back(weights / weights.sum());
  }
  return skin;
}

// ---------------------------------------------------------------------------------------------
// Scenes.

struct Scene {
  Mesh mesh;
  Rig rig;
  RigModel model;
  std::vector<std::array<PointLoad, 1>> loads;  // per part: poses[i] points here
  std::vector<PartPose> poses;
  LinearBlendSkin skin;
  SkinPose skin_pose;
};

const RigDescription& HumanDescription() {
  static const RigDescription description =
      Check(LoadRigDescription(std::string(WIRERIG_SAMPLES_DIR) + "/rigs/human.description.json"),
            "human.description.json");
  return description;
}

const Mesh& HumanMesh() {
  static const Mesh mesh =
      Check(ImportMesh(std::string(WIRERIG_ASSET_DIR) + "/assimp/Collada/human.zae",
                       HumanDescription().import),
            "human.zae")
          .mesh;
  return mesh;
}

// A small rotation of every part (about an axis that differs from part to part), the root
// moved a little, and a bending point load of 0.05 EI / L^3 (the size the evaluation tests use)
// on every spine at v = 0.7, along the normal and half as much along the binormal. The skin gets
// the same rotations at each part's first joint, and its other joints share a bend of 0.15 rad per
// part.
void Pose(Scene& scene) {
  const std::size_t parts = scene.model.parts.size();
  scene.loads.resize(parts);
  scene.poses.resize(parts);
  scene.skin_pose.local_rotations.clear();
  for (std::size_t i = 0; i < parts; ++i) {
    const PartModel& part = scene.model.parts[i];
    const double x = double(i);
    const Vec3 axis = Vec3(std::sin(1.7 * x + 0.3), std::cos(1.1 * x), 0.5).normalized();
    const Quat rotation(Eigen::AngleAxisd(0.1 + 0.02 * x, axis));
    const double force = 0.05 * part.spine_stiffness.bending / std::pow(part.spine_length, 3);
    scene.loads[i] = {{{0.7, Vec3(force, 0.5 * force, 0.0)}}};
    scene.poses[i].rotation = rotation;
    scene.poses[i].loads.bending_point_loads = scene.loads[i];
    const std::size_t n = part.spine_points.size();
    const double bend = 0.15 / double(n - 1);
    for (std::size_t k = 0; k < n; ++k)
      scene.skin_pose.local_rotations.push_back(
          k == 0 ? rotation : Quat(Eigen::AngleAxisd(bend, part.spine_frames[k].binormal)));
  }
  scene.poses[0].translation = Vec3(0.02, -0.01, 0.05);
  scene.skin_pose.root_translation = scene.poses[0].translation;
}

std::unique_ptr<Scene> MakeScene(Mesh mesh, const std::string& name) {
  auto scene = std::make_unique<Scene>();
  scene->mesh = std::move(mesh);
  scene->rig = Check(BuildRig(scene->mesh, HumanDescription(), name), name.c_str()).rig;
  scene->model = Check(BuildRigModel(scene->mesh, scene->rig), name.c_str()).model;
  scene->skin = MakeSkin(scene->model, scene->mesh);
  Pose(*scene);
  return scene;
}

const Scene& Human() {
  static const std::unique_ptr<Scene> scene = MakeScene(HumanMesh(), "human.zae");
  return *scene;
}

const Scene& Subdivided() {
  static const std::unique_ptr<Scene> scene =
      MakeScene(Subdivide(HumanMesh(), kSubdividedVertices), "human.zae (subdivided)");
  return *scene;
}

// ---------------------------------------------------------------------------------------------
// Benchmarks.

void SetVertexCounters(benchmark::State& state, std::size_t vertices) {
  state.counters["vertices"] = double(vertices);
  state.counters["vertices/s"] = benchmark::Counter(double(state.iterations()) * double(vertices),
                                                    benchmark::Counter::kIsRate);
}

// One pool per thread count, made once per process (its threads are running and warm when a
// repetition starts, as in an engine that keeps its pool).
const ThreadPool& Pool(std::size_t threads) {
  static std::vector<std::unique_ptr<ThreadPool>> pools(8);
  std::unique_ptr<ThreadPool>& pool = pools.at(threads);
  if (!pool) pool = std::make_unique<ThreadPool>(threads);
  return *pool;
}

// state.range(0): threads for the vertex and normal passes (1: no pool, the default).
void BM_WireEvaluation(benchmark::State& state, const Scene& (*get)()) {
  const Scene& scene = get();
  const auto threads = static_cast<std::size_t>(state.range(0));
  const ThreadPool* pool = threads > 1 ? &Pool(threads) : nullptr;
  RigWorkspace workspace = MakeRigWorkspace(scene.model);
  std::vector<Vec3> positions(scene.model.vertices.size()), normals(positions.size());
  EvaluateRigJob job;
  job.model = &scene.model;
  job.poses = scene.poses;
  job.workspace = &workspace;
  job.positions = positions;
  job.normals = normals;
  job.parallel = pool;
  for (auto _ : state) {
    const Status status = job.Run();
    if (!status) {
      state.SkipWithError(ToString(status).c_str());
      break;
    }
    benchmark::DoNotOptimize(positions.data());
    benchmark::DoNotOptimize(normals.data());
    benchmark::ClobberMemory();
  }
  SetVertexCounters(state, positions.size());
}

// The same frame into float engine buffers (interleaved position and normal, stride 6): the
// float evaluation, four vertices at a time. state.range(0): threads, as above.
void BM_WireEvaluationFloat(benchmark::State& state, const Scene& (*get)(),
                            NormalMode normal_mode = NormalMode::kFromTriangles) {
  const Scene& scene = get();
  const auto threads = static_cast<std::size_t>(state.range(0));
  const ThreadPool* pool = threads > 1 ? &Pool(threads) : nullptr;
  RigWorkspace workspace = MakeRigWorkspace(scene.model);
  std::vector<float> buffer(6 * scene.model.vertices.size());
  EvaluateRigJob job;
  job.model = &scene.model;
  job.poses = scene.poses;
  job.workspace = &workspace;
  job.float_positions = buffer;
  job.float_position_stride = 6;
  job.float_normals = std::span<float>(buffer).subspan(3);
  job.float_normal_stride = 6;
  job.parallel = pool;
  job.allow_avx2 = state.range(1) != 0;
  job.normal_mode = normal_mode;
  for (auto _ : state) {
    const Status status = job.Run();
    if (!status) {
      state.SkipWithError(ToString(status).c_str());
      break;
    }
    benchmark::DoNotOptimize(buffer.data());
    benchmark::ClobberMemory();
  }
  SetVertexCounters(state, scene.model.vertices.size());
}

// Linear blend skinning as engines write it (ReferenceSkinningJob: float, one array per
// attribute, 4 influences, positions and rest normals skinned), one bone per part, with the
// parts' rigid motions of the same pose.
struct ReferenceScene {
  ReferenceSkin skin;
  std::vector<BoneMatrix> bones;
};
const ReferenceScene& Reference(const Scene& scene) {
  static std::unordered_map<const Scene*, std::unique_ptr<ReferenceScene>> made;
  std::unique_ptr<ReferenceScene>& out = made[&scene];
  if (!out) {
    out = std::make_unique<ReferenceScene>();
    out->skin = MakeReferenceSkin(scene.model, scene.mesh.welded_positions);
    RigWorkspace workspace = MakeRigWorkspace(scene.model);
    std::vector<Vec3> positions(scene.model.vertices.size());
    EvaluateRigJob job;
    job.model = &scene.model;
    job.poses = scene.poses;
    job.workspace = &workspace;
    job.positions = positions;
    if (!job.Run()) std::exit(1);
    out->bones.resize(scene.model.parts.size());
    BoneMatricesFromWorkspace(scene.model, workspace, out->bones);
  }
  return *out;
}

void BM_ReferenceLinearBlend(benchmark::State& state, const Scene& (*get)()) {
  const Scene& scene = get();
  const ReferenceScene& reference = Reference(scene);
  const std::size_t n = scene.model.vertices.size();
  std::vector<float> x(n), y(n), z(n), nx(n), ny(n), nz(n);
  const ReferenceSkinningJob job{
      ReferenceSkinning::kLinearBlend, &reference.skin, reference.bones, x, y, z, nx, ny, nz};
  for (auto _ : state) {
    job.Run();
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  SetVertexCounters(state, n);
}

void BM_LinearBlendSkinning(benchmark::State& state, const Scene& (*get)()) {
  const Scene& scene = get();
  const std::size_t joints = scene.skin.joint_parent.size();
  SkinWorkspace workspace{std::vector<Mat3>(joints), std::vector<Vec3>(joints),
                          std::vector<Mat34>(joints)};
  std::vector<Vec3> positions(scene.skin.rest_positions.size()), normals(positions.size());
  for (auto _ : state) {
    EvaluateSkin(scene.skin, scene.skin_pose, workspace, positions, normals);
    benchmark::DoNotOptimize(positions.data());
    benchmark::DoNotOptimize(normals.data());
    benchmark::ClobberMemory();
  }
  SetVertexCounters(state, positions.size());
  state.counters["joints"] = double(joints);
}

void BM_BindingPrecompute(benchmark::State& state, const Scene& (*get)()) {
  const Scene& scene = get();
  for (auto _ : state) {
    Result<BuiltRigModel> built = BuildRigModel(scene.mesh, scene.rig);
    if (!built) {
      state.SkipWithError(built.error().c_str());
      break;
    }
    benchmark::DoNotOptimize(built.value().model.vertices.data());
  }
  SetVertexCounters(state, scene.mesh.welded_positions.size());
}

// MakeRigWorkspace: the per-model (not per-frame) cost of laying the bindings out flat.
void BM_MakeWorkspace(benchmark::State& state, const Scene& (*get)()) {
  const Scene& scene = get();
  for (auto _ : state) {
    RigWorkspace workspace = MakeRigWorkspace(scene.model);
    benchmark::DoNotOptimize(workspace.stage32.position.x.data());
  }
  SetVertexCounters(state, scene.model.vertices.size());
}

// The fastest repetition too: on a loaded machine the minimum is the figure closest to an idle
// one (run with many repetitions).
double Minimum(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

BENCHMARK_CAPTURE(BM_WireEvaluation, human, &Human)
    ->Arg(1)
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_LinearBlendSkinning, human, &Human)
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_WireEvaluation, subdivided, &Subdivided)
    ->Arg(1)
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_LinearBlendSkinning, subdivided, &Subdivided)
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
// Two threads (the vertex and normal passes on a ThreadPool): wall time is the figure.
BENCHMARK_CAPTURE(BM_WireEvaluation, human_2_threads, &Human)
    ->Arg(2)
    ->UseRealTime()
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_WireEvaluation, subdivided_2_threads, &Subdivided)
    ->Arg(2)
    ->UseRealTime()
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_WireEvaluationFloat, human, &Human)
    ->ArgNames({"threads", "avx2"})
    ->Args({1, 1})
    ->Args({1, 0})
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ReferenceLinearBlend, human, &Human)
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_WireEvaluationFloat, subdivided, &Subdivided)
    ->ArgNames({"threads", "avx2"})
    ->Args({1, 1})
    ->Args({1, 0})
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ReferenceLinearBlend, subdivided, &Subdivided)
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_WireEvaluationFloat, subdivided_2_threads, &Subdivided)
    ->ArgNames({"threads", "avx2"})
    ->Args({2, 1})
    ->UseRealTime()
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_WireEvaluationFloat, human_rotated_normals, &Human, NormalMode::kRotated)
    ->ArgNames({"threads", "avx2"})
    ->Args({1, 1})
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_WireEvaluationFloat, subdivided_rotated_normals, &Subdivided,
                  NormalMode::kRotated)
    ->ArgNames({"threads", "avx2"})
    ->Args({1, 1})
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_BindingPrecompute, subdivided, &Subdivided)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MakeWorkspace, subdivided, &Subdivided)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
