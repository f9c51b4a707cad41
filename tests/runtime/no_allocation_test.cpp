// Proves that the jobs' Run() never allocates: global operator new is replaced by one that
// counts, and the count must not change across Run().
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_model_builder.h"
#include "wirerig/runtime/axial_job.h"
#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/clip_asset.h"
#include "wirerig/runtime/curve.h"
#include "wirerig/runtime/rig_asset.h"
#include "wirerig/runtime/rig_evaluation.h"
#include "wirerig/runtime/rigid_body.h"
#include "wirerig/wirerig.h"

#include "support/counting_allocator.h"
#include "support/two_segment_limb.h"

using wirerig::testing::g_allocations;

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(NoAllocation, CountingAllocatorSeesAllocations) {
  EXPECT_GE(testing::CountedAllocationsOfAHeapVector(), 2);
}

TEST(NoAllocation, BendingRunInBothModesWithAllOutputs) {
  std::vector<PointLoad> p = {{0.2, Vec3(0, -1, 0)}, {0.7, Vec3(1, 0, 0)}};
  std::vector<LineLoad> q = {{0.1, 0.5, Vec3(0, 0, 2)}};
  std::vector<LinearLineLoad> r = {{0.3, 0.9, Vec3(0, 0, 2), Vec3(1, -1, 0)}};
  std::vector<double> v(257);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = double(i) / double(v.size() - 1);
  std::vector<Vec3> x(v.size()), slope(v.size()), curvature(v.size());
  for (BendingMode mode : {BendingMode::kExact, BendingMode::kSeries}) {
    BendingJob job;
    job.boundary = BoundaryCondition::kCantileverFree;
    job.mode = mode;
    job.series_terms = 300;  // more than one stack block of terms
    job.length = 1.5;
    job.bending_stiffness = 3.0;
    job.tip_force = Vec3(0, 1, 0);
    job.point_loads = p;
    job.line_loads = q;
    job.linear_line_loads = r;
    job.samples = v;
    job.displacement = x;
    job.slope = slope;
    job.curvature = curvature;
    const long before = g_allocations;
    const Status status = job.Run();
    const long after = g_allocations;
    ASSERT_TRUE(status.ok());
    EXPECT_EQ(after, before) << ToString(mode);
  }
}

// Point loads only: the piecewise-cubic path (up to 16 loads) and, past it, the general one.
TEST(NoAllocation, BendingRunWithPointLoadsOnly) {
  std::vector<PointLoad> p;
  for (int j = 0; j < 17; ++j) p.push_back({(j * 7 % 17) / 16.0, Vec3(1, -2, 0.5 * j)});
  std::vector<double> v(257);
  for (std::size_t i = 0; i < v.size(); ++i) v[(i * 5) % v.size()] = double(i) / 256.0;
  std::vector<Vec3> x(v.size()), slope(v.size()), curvature(v.size());
  for (BoundaryCondition bc :
       {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped,
        BoundaryCondition::kCantileverFree, BoundaryCondition::kCantileverGuided}) {
    for (std::size_t loads : {std::size_t{3}, std::size_t{16}, std::size_t{17}}) {
      BendingJob job;
      job.boundary = bc;
      job.length = 1.5;
      job.bending_stiffness = 3.0;
      job.point_loads = std::span<const PointLoad>(p).first(loads);
      job.samples = v;
      job.displacement = x;
      job.slope = slope;
      job.curvature = curvature;
      const long before = g_allocations;
      const Status status = job.Run();
      const long after = g_allocations;
      ASSERT_TRUE(status.ok());
      EXPECT_EQ(after, before) << ToString(bc) << " with " << loads << " loads";
    }
  }
}

TEST(NoAllocation, AxialRunWithNormalForce) {
  std::vector<AxialPointLoad> p = {{0.2, -1.0}, {0.9, 2.0}};
  std::vector<AxialLineLoad> q = {{0.3, 0.6, 1.0}};
  std::vector<double> v = {0.0, 0.25, 0.5, 0.75, 1.0};
  std::vector<double> x(v.size()), n(v.size());
  AxialJob job;
  job.length = 1.0;
  job.axial_stiffness = 10.0;
  job.fixed_at = 0.5;
  job.point_loads = p;
  job.line_loads = q;
  job.samples = v;
  job.displacement = x;
  job.normal_force = n;
  const long before = g_allocations;
  const Status status = job.Run();
  const long after = g_allocations;
  ASSERT_TRUE(status.ok());
  EXPECT_EQ(after, before);
}

TEST(NoAllocation, CurveQueries) {
  std::vector<Vec3> points;
  for (int i = 0; i < 12; ++i) points.emplace_back(std::cos(i * 0.5), std::sin(i * 0.5), 0.1 * i);
  Curve curve;
  ASSERT_TRUE(Curve::Build(points, false, CurveInterpolation::kCubic, &curve).ok());
  std::vector<Vec3> resampled(40);
  const long before = g_allocations;
  Vec3 sum = Vec3::Zero();
  for (int i = 0; i <= 100; ++i) {
    const double v = i / 100.0;
    sum += curve.Position(v) + curve.Tangent(v) + curve.FrameAt(v).normal;
  }
  curve.Resample(resampled);
  const long after = g_allocations;
  EXPECT_TRUE(sum.allFinite());
  EXPECT_EQ(after, before);
}

TEST(NoAllocation, RigEvaluationWithLoadsAndNormals) {
  // A deformable one-part rig on a procedural capsule, with a pose, spine loads and normals.
  RigDescription description;
  description.parts.push_back({"body", {Vec3(0, 0.05, 0), Vec3(0, 0.95, 0)}, 8, 16, "", {}, {}});
  const Mesh mesh = MakeCapsule(0.2, 1.0, 32, 16, 6);
  const Result<BuiltRig> rig = BuildRig(mesh, description, "capsule");
  ASSERT_TRUE(rig.ok()) << rig.error();
  const Result<BuiltRigModel> model = BuildRigModel(mesh, rig.value().rig);
  ASSERT_TRUE(model.ok()) << model.error();
  RigWorkspace workspace = MakeRigWorkspace(model.value().model);
  std::vector<Vec3> positions(model.value().model.vertices.size()), normals(positions.size());
  std::vector<PointLoad> loads = {{0.7, Vec3(1e-4, 0, 0)}};
  std::vector<AxialPointLoad> axial = {{1.0, 1e-3}};
  std::vector<PartPose> poses(1);
  poses[0].rotation = Quat(Eigen::AngleAxisd(0.2, Vec3::UnitX()));
  poses[0].loads.bending_point_loads = loads;
  poses[0].loads.axial_point_loads = axial;
  EvaluateRigJob job;
  job.model = &model.value().model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  job.normals = normals;
  const long before = g_allocations;
  const Status status = job.Run();
  const long after = g_allocations;
  ASSERT_TRUE(status.ok()) << ToString(status);
  EXPECT_EQ(after, before);
}

TEST(NoAllocation, RigEvaluationOnAThreadPool) {
  // As above, with the vertex and normal passes shared out over a pool made beforehand.
  RigDescription description;
  description.parts.push_back({"body", {Vec3(0, 0.05, 0), Vec3(0, 0.95, 0)}, 8, 16, "", {}, {}});
  const Mesh mesh = MakeCapsule(0.2, 1.0, 96, 48, 6);
  const Result<BuiltRig> rig = BuildRig(mesh, description, "capsule");
  ASSERT_TRUE(rig.ok()) << rig.error();
  const Result<BuiltRigModel> model = BuildRigModel(mesh, rig.value().rig);
  ASSERT_TRUE(model.ok()) << model.error();
  RigWorkspace workspace = MakeRigWorkspace(model.value().model);
  std::vector<Vec3> positions(model.value().model.vertices.size()), normals(positions.size());
  std::vector<PointLoad> loads = {{0.7, Vec3(1e-4, 0, 0)}};
  std::vector<PartPose> poses(1);
  poses[0].loads.bending_point_loads = loads;
  const ThreadPool pool(2);
  EvaluateRigJob job;
  job.model = &model.value().model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  job.normals = normals;
  job.parallel = &pool;
  ASSERT_TRUE(job.Run().ok());  // the workers have started and run once
  const long before = g_allocations;
  for (int frame = 0; frame < 10; ++frame) {  // normals from the triangles, then rotated
    job.normal_mode = frame % 2 == 0 ? NormalMode::kFromTriangles : NormalMode::kRotated;
    ASSERT_TRUE(job.Run().ok());
  }
  const long after = g_allocations;
  EXPECT_EQ(after, before);
}

TEST(NoAllocation, JointedRigIntoFloatBuffers) {
  // Two rigid segments of a capsule with a skin bridge at their joint, bent, evaluated into an
  // interleaved float buffer: the float stage, the bridge pass and the normals (from the
  // triangles, then rotated).
  const Mesh mesh = MakeCapsule(0.08, 1.0, 48, 80, 8);
  const Result<BuiltRig> rig = BuildRig(mesh, testing::TwoSegmentLimb(), "capsule");
  ASSERT_TRUE(rig.ok()) << rig.error();
  RigModelOptions options;
  options.spine_kind = SpineKind::kRigid;
  const Result<BuiltRigModel> model = BuildRigModel(mesh, rig.value().rig, options);
  ASSERT_TRUE(model.ok()) << model.error();
  RigWorkspace workspace = MakeRigWorkspace(model.value().model);
  ASSERT_FALSE(workspace.plan->layout.joint_vertices.empty());
  std::vector<float> buffer(6 * model.value().model.vertices.size());
  std::vector<PartPose> poses(2);
  poses[1].rotation = Quat(Eigen::AngleAxisd(1.2, Vec3::UnitX()));
  EvaluateRigJob job;
  job.model = &model.value().model;
  job.poses = poses;
  job.workspace = &workspace;
  job.float_positions = buffer;
  job.float_position_stride = 6;
  job.float_normals = std::span<float>(buffer).subspan(3);
  job.float_normal_stride = 6;
  for (const NormalMode mode : {NormalMode::kFromTriangles, NormalMode::kRotated}) {
    job.normal_mode = mode;
    const long before = g_allocations;
    const Status status = job.Run();
    const long after = g_allocations;
    ASSERT_TRUE(status.ok()) << ToString(status);
    EXPECT_EQ(after, before);
  }
}

// An engine's frame through the C API: a context from a loaded .wrig, a joint bent and a spine
// load set beforehand; evaluating into an interleaved buffer in the source order allocates
// nothing.
TEST(NoAllocation, CApiEvaluation) {
  const Mesh mesh = MakeCapsule(0.08, 1.0, 32, 48, 4);
  const Result<BuiltRig> rig = BuildRig(mesh, testing::TwoSegmentLimb(), "capsule");
  ASSERT_TRUE(rig.ok()) << rig.error();
  Result<BuiltRigModel> model = BuildRigModel(mesh, rig.value().rig);
  ASSERT_TRUE(model.ok()) << model.error();
  RigAsset asset{std::move(model).value().model, mesh.weld_map};
  const std::vector<std::uint8_t> bytes = SerializeRigAsset(asset);
  wr_rig* loaded = nullptr;
  ASSERT_EQ(wr_rig_load_memory(bytes.data(), bytes.size(), &loaded), WR_OK) << wr_last_error();
  wr_context* context = nullptr;
  ASSERT_EQ(wr_context_create(loaded, &context), WR_OK) << wr_last_error();
  ASSERT_EQ(wr_context_set_joint_angles(context, 1, 70.0f, 10.0f, 0.0f), WR_OK);
  const float at[1] = {0.6f}, force[3] = {20.0f, 0.0f, 0.0f};
  ASSERT_EQ(wr_context_set_point_loads(context, 0, at, force, 1), WR_OK);
  const std::size_t outputs = wr_rig_vertex_count(loaded, WR_ORDER_SOURCE);
  std::vector<float> buffer(6 * outputs);
  const long before = g_allocations;
  const wr_status status = wr_context_evaluate(context, WR_ORDER_SOURCE, buffer.data(), 6,
                                               buffer.data() + 3, 6, buffer.size());
  const long after = g_allocations;
  ASSERT_EQ(status, WR_OK) << wr_last_error();
  EXPECT_EQ(after, before);

  // A clip of two frames (the joint turning, a spine load growing), set once; then each frame
  // moves its time and evaluates without allocating.
  SampledClip clip;
  clip.name = "bend";
  clip.duration = 1.0;
  clip.frame_rate = 1.0;
  clip.loop = ClipLoop::kLoop;
  clip.part_count = 2;
  clip.parts.resize(4);
  clip.parts[3].rotation = Quat(Eigen::AngleAxisd(1.0, Vec3::UnitX()));
  clip.point_loads = {{0.5, Vec3(5, 0, 0)}, {0.5, Vec3(25, 0, 0)}};
  clip.parts[0].point_loads = {0, 1};
  clip.parts[2].point_loads = {1, 1};
  clip.profile_keys_of_frame.resize(2);
  const std::vector<std::uint8_t> clip_bytes = SerializeClipAsset(clip);
  wr_clip* played = nullptr;
  ASSERT_EQ(wr_clip_load_memory(clip_bytes.data(), clip_bytes.size(), &played), WR_OK)
      << wr_last_error();
  ASSERT_EQ(wr_context_set_clip(context, played, 0.1), WR_OK) << wr_last_error();
  const long clip_before = g_allocations;
  for (double t : {0.25, 0.5, 1.75}) {
    ASSERT_EQ(wr_context_set_clip(context, played, t), WR_OK);
    ASSERT_EQ(wr_context_evaluate(context, WR_ORDER_SOURCE, buffer.data(), 6, buffer.data() + 3, 6,
                                  buffer.size()),
              WR_OK)
        << wr_last_error();
  }
  EXPECT_EQ(g_allocations, clip_before);
  wr_clip_free(played);
  wr_context_free(context);
  wr_rig_free(loaded);
}

TEST(NoAllocation, RigidBodyStepsWithBothIntegrators) {
  for (RigidIntegrator integrator : {RigidIntegrator::kRk4, RigidIntegrator::kMomentum}) {
    RigidBodyState state;
    state.angular_velocity = Vec3(0.1, 1.0, 0.1);
    RigidBodyStepJob step;
    step.integrator = integrator;
    step.mass = 2.0;
    step.principal_moments = Vec3(1, 2, 3);
    step.dt = 0.01;
    step.at_start.force = step.at_middle.force = step.at_end.force = Vec3(0, -19.6, 0);
    step.state = &state;
    const long before = g_allocations;
    for (int i = 0; i < 100; ++i) ASSERT_TRUE(step.Run().ok());
    const long after = g_allocations;
    EXPECT_EQ(after, before);
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
