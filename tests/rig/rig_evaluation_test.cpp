// Per-frame evaluation of rigs built from real and procedural meshes: zero load reproduces the
// mesh, rigid motions move it rigidly, parent motion reaches the children and never the
// reverse, a spine load bends the part by the closed form.
#include "wirerig/runtime/rig_evaluation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <thread>

#include "support/busy_pose.h"
#include "support/two_segment_limb.h"
#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_model_builder.h"
#include "wirerig/runtime/parallel.h"
#include "wirerig/runtime/spine_interpolation.h"

#ifndef WIRERIG_ASSET_DIR
#error "the tests need WIRERIG_ASSET_DIR (set by CMake)"
#endif
#ifndef WIRERIG_SAMPLES_DIR
#error "the tests need WIRERIG_SAMPLES_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

struct Scene {
  Mesh mesh;
  Rig rig;
  RigModel model;
  double diagonal = 0.0;
};

Scene Build(Mesh mesh, const RigDescription& description, SpineKind kind) {
  Scene scene;
  scene.mesh = std::move(mesh);
  scene.diagonal = ComputeBounds(scene.mesh).Diagonal();
  Result<BuiltRig> built = BuildRig(scene.mesh, description, "test");
  EXPECT_TRUE(built.ok()) << built.error();
  scene.rig = built.value().rig;
  RigModelOptions options;
  options.spine_kind = kind;
  Result<BuiltRigModel> model = BuildRigModel(scene.mesh, scene.rig, options);
  EXPECT_TRUE(model.ok()) << model.error();
  scene.model = std::move(model).value().model;
  return scene;
}

const Scene& Human() {
  static const Scene scene = [] {
    Result<ImportedMesh> mesh =
        ImportMesh(std::string(WIRERIG_ASSET_DIR) + "/assimp/Collada/human.zae");
    Result<RigDescription> description =
        LoadRigDescription(std::string(WIRERIG_SAMPLES_DIR) + "/rigs/human.description.json");
    return Build(std::move(mesh).value().mesh, description.value(), SpineKind::kDeformable);
  }();
  return scene;
}

std::vector<Vec3> Evaluate(const Scene& scene, const std::vector<PartPose>& poses,
                           std::vector<Vec3>* normals = nullptr) {
  RigWorkspace workspace = MakeRigWorkspace(scene.model);
  std::vector<Vec3> positions(scene.model.vertices.size());
  EvaluateRigJob job;
  job.model = &scene.model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  if (normals) {
    normals->resize(positions.size());
    job.normals = *normals;
  }
  const Status status = job.Run();
  EXPECT_TRUE(status.ok()) << ToString(status);
  return positions;
}

int PartIndex(const Scene& scene, const std::string& name) {
  for (std::size_t i = 0; i < scene.model.parts.size(); ++i)
    if (scene.model.parts[i].name == name) return int(i);
  return -1;
}

// Two threads' workspaces from one shared plan evaluate a jointed, loaded pose bit for bit as a
// workspace with a plan of its own; a plan made for another model is refused.
TEST(RigEvaluation, WorkspacesShareOnePlan) {
  const Scene& human = Human();
  std::vector<PartPose> poses(human.model.parts.size());
  poses[std::size_t(PartIndex(human, "forearm_l"))].rotation = JointRotation(
      human.model.parts[std::size_t(PartIndex(human, "forearm_l"))].joint, Vec3(80, 0, 0));
  const PointLoad load{0.8, Vec3(0, 40, 0)};
  poses[0].loads.bending_point_loads = std::span(&load, 1);
  const std::vector<Vec3> own = Evaluate(human, poses);
  const std::shared_ptr<const RigEvaluationPlan> plan = MakeRigEvaluationPlan(human.model);
  std::array<std::vector<Vec3>, 2> shared;
  std::array<std::thread, 2> threads;
  for (std::size_t t = 0; t < 2; ++t)
    threads[t] = std::thread([&, t] {
      RigWorkspace workspace = MakeRigWorkspace(human.model, plan);
      shared[t].resize(human.model.vertices.size());
      EvaluateRigJob job;
      job.model = &human.model;
      job.poses = poses;
      job.workspace = &workspace;
      job.positions = shared[t];
      EXPECT_TRUE(job.Run().ok());
    });
  for (std::thread& thread : threads) thread.join();
  for (const std::vector<Vec3>& positions : shared) {
    ASSERT_EQ(positions.size(), own.size());
    EXPECT_EQ(std::memcmp(positions.data(), own.data(), own.size() * sizeof(Vec3)), 0);
  }
  EXPECT_EQ(plan.use_count(), 1) << "the workspaces released their share";

  const Scene limb =
      Build(MakeCapsule(0.08, 1.0, 16, 24, 4), testing::TwoSegmentLimb(), SpineKind::kRigid);
  RigWorkspace mismatched = MakeRigWorkspace(human.model, MakeRigEvaluationPlan(limb.model));
  std::vector<Vec3> positions(human.model.vertices.size());
  EvaluateRigJob job;
  job.model = &human.model;
  job.poses = poses;
  job.workspace = &mismatched;
  job.positions = positions;
  EXPECT_EQ(ToString(job.Validate()), "workspace: was made for another model");
}

TEST(RigEvaluation, ZeroLoadReproducesTheMesh) {
  const Scene& human = Human();
  const std::vector<Vec3> positions =
      Evaluate(human, std::vector<PartPose>(human.model.parts.size()));
  double worst = 0.0;
  for (std::size_t v = 0; v < positions.size(); ++v)
    worst = std::max(worst, (positions[v] - human.mesh.welded_positions[v]).norm());
  EXPECT_LE(worst, 1e-6 * human.diagonal);
}

TEST(RigEvaluation, RigidMotionOfTheRootMovesTheMeshRigidly) {
  const Scene& human = Human();
  std::vector<PartPose> poses(human.model.parts.size());
  poses[0].rotation = Quat(Eigen::AngleAxisd(0.7, Vec3(0.3, 1.0, -0.2).normalized()));
  poses[0].translation = Vec3(0.4, -0.1, 2.0);
  const std::vector<Vec3> positions = Evaluate(human, poses);
  const Vec3 root = human.model.parts[0].spine_points.front();
  const Mat3 r = poses[0].rotation.toRotationMatrix();
  double worst = 0.0;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const Vec3 expected = root + r * (human.mesh.welded_positions[v] - root) + poses[0].translation;
    worst = std::max(worst, (positions[v] - expected).norm());
  }
  EXPECT_LE(worst, 1e-5 * human.diagonal);
}

TEST(RigEvaluation, ChildMotionNeverMovesItsParent) {
  const Scene& human = Human();
  const int arm = PartIndex(human, "upper_arm_l");
  ASSERT_GE(arm, 0);
  std::vector<PartPose> poses(human.model.parts.size());
  poses[arm].rotation = Quat(Eigen::AngleAxisd(0.6, Vec3::UnitZ()));
  const std::vector<Vec3> rest = Evaluate(human, std::vector<PartPose>(human.model.parts.size()));
  const std::vector<Vec3> moved = Evaluate(human, poses);
  // The arm and the parts hanging from it move; the parent's skin moves only where it lies on
  // the joint's skin bridge (joint_bridge.h); every other part stays.
  std::vector<bool> from_arm(human.model.parts.size(), false);
  for (std::size_t i = 0; i < from_arm.size(); ++i) {
    const int parent = human.model.parts[i].parent;
    from_arm[i] = int(i) == arm || (parent >= 0 && from_arm[std::size_t(parent)]);
  }
  std::size_t arm_moved = 0, parent_bridged = 0;
  for (std::size_t v = 0; v < moved.size(); ++v) {
    const VertexAttachment& a = human.model.vertices[v];
    const bool on_arm_bridge = a.OnJoint(arm);
    if (from_arm[a.part])
      arm_moved += (moved[v] - rest[v]).norm() > 1e-3;
    else if (on_arm_bridge)
      ++parent_bridged;
    else
      EXPECT_EQ(moved[v], rest[v]) << "vertex " << v << " of part " << a.part;
  }
  EXPECT_GT(arm_moved, 100u);
  EXPECT_GT(parent_bridged, 0u);
}

TEST(RigEvaluation, ParentMotionReachesItsChildren) {
  const Scene& human = Human();
  const int arm = PartIndex(human, "upper_arm_l"), torso = PartIndex(human, "pelvis");
  ASSERT_GE(arm, 0);
  ASSERT_EQ(torso, 0);
  std::vector<PartPose> poses(human.model.parts.size());
  poses[torso].rotation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitX()));
  const std::vector<Vec3> moved = Evaluate(human, poses);
  const Vec3 root = human.model.parts[torso].spine_points.front();
  const Mat3 r = poses[torso].rotation.toRotationMatrix();
  // The pelvis is the root: everything, the arm included, turns with it.
  std::size_t arm_vertices = 0;
  for (std::size_t v = 0; v < moved.size(); ++v) {
    if (int(human.model.vertices[v].part) != arm) continue;
    ++arm_vertices;
    const Vec3 expected = root + r * (human.mesh.welded_positions[v] - root);
    EXPECT_LE((moved[v] - expected).norm(), 1e-5 * human.diagonal);
  }
  EXPECT_GT(arm_vertices, 100u);
}

TEST(RigEvaluation, CantileverSpineBendsByTheClosedForm) {
  // A capsule rigged along its axis; a tip force on its cantilever spine along the local
  // normal: the spine's tip moves by F L^3 / 3EI (L and EI those of the model's spine).
  RigDescription description;
  description.parts.push_back({"body", {Vec3(0, 0, 0), Vec3(0, 1, 0)}, 10, 24, "", {}, {}});
  const Scene scene = Build(MakeCapsule(0.1, 1.0, 48, 20, 8), description, SpineKind::kDeformable);
  const PartModel& part = scene.model.parts[0];
  std::vector<PartPose> poses(1);
  const double force = 2e-3 * part.spine_stiffness.bending / std::pow(part.spine_length, 3);
  poses[0].loads.tip_force = Vec3(force, 0, 0);
  RigWorkspace workspace = MakeRigWorkspace(scene.model);
  std::vector<Vec3> positions(scene.model.vertices.size());
  EvaluateRigJob job;
  job.model = &scene.model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  ASSERT_TRUE(job.Run().ok());
  const double expected =
      force * std::pow(part.spine_length, 3) / (3.0 * part.spine_stiffness.bending);
  const Vec3 tip_move = workspace.spine_points[0].back() - part.spine_points.back();
  EXPECT_NEAR(tip_move.dot(part.spine_frames.back().normal), expected, 1e-9);
  EXPECT_NEAR(tip_move.dot(part.spine_frames.back().binormal), 0.0, 1e-12);
  // Vertices near the top follow the spine; the bottom cap stays (clamped root).
  std::size_t top_moved = 0;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const Vec3& rest = scene.mesh.welded_positions[v];
    const double moved = (positions[v] - rest).norm();
    if (rest.y() < 0.0) {
      EXPECT_LT(moved, 1e-12);
    }
    if (rest.y() > 0.9) top_moved += moved > 0.5 * expected;
  }
  EXPECT_GT(top_moved, 20u);
}

// Extra bending (what modal dynamics adds) moves the mesh exactly as a load of that shape: the
// textbook cantilever under a tip force F, X(v) = F L^3 v^2 (3 - v) / 6EI and dX/ds =
// F L^2 v (2 - v) / 2EI, given as extra bending, matches the tip force itself.
TEST(RigEvaluation, ExtraBendingMovesTheMeshAsTheLoadOfThatShape) {
  RigDescription description;
  description.parts.push_back({"body", {Vec3(0, 0, 0), Vec3(0, 1, 0)}, 10, 24, "", {}, {}});
  const Scene scene = Build(MakeCapsule(0.1, 1.0, 48, 20, 8), description, SpineKind::kDeformable);
  const PartModel& part = scene.model.parts[0];
  const double ei = part.spine_stiffness.bending, length = part.spine_length;
  const Vec3 force = Vec3(3e-3, -1e-3, 0) * ei / std::pow(length, 3);
  const std::size_t n = part.spine_points.size();
  std::vector<Vec3> displacement(n), slope(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double v = double(k) / double(n - 1);
    displacement[k] = force * std::pow(length, 3) * v * v * (3.0 - v) / (6.0 * ei);
    slope[k] = force * length * length * v * (2.0 - v) / (2.0 * ei);
  }
  RigWorkspace workspace = MakeRigWorkspace(scene.model);
  std::vector<Vec3> positions(scene.model.vertices.size());
  auto run = [&](const PartPose& pose) {
    std::vector<PartPose> poses = {pose};
    EvaluateRigJob job;
    job.model = &scene.model;
    job.poses = poses;
    job.workspace = &workspace;
    job.positions = positions;
    return job.Run();
  };
  auto evaluate = [&](const PartPose& pose) {
    EXPECT_TRUE(run(pose).ok());
    return positions;
  };
  PartPose loaded, extra;
  loaded.loads.tip_force = force;
  extra.loads.extra_displacement = displacement;
  extra.loads.extra_slope = slope;
  const std::vector<Vec3> expected = evaluate(loaded), got = evaluate(extra);
  double worst = 0.0, moved = 0.0;
  for (std::size_t v = 0; v < got.size(); ++v) {
    worst = std::max(worst, (got[v] - expected[v]).norm());
    moved = std::max(moved, (got[v] - scene.mesh.welded_positions[v]).norm());
  }
  EXPECT_GT(moved, 5e-4 * length);  // the tip moves by |F| L^3 / 3EI, about 1e-3 L
  EXPECT_LT(worst, 1e-12);
  // The wrong count is refused by name.
  extra.loads.extra_slope = std::span<const Vec3>(slope.data(), n - 1);
  const Status status = run(extra);
  EXPECT_FALSE(status.ok());
  EXPECT_EQ(status.field, "poses");
}

TEST(RigEvaluation, BendingAnArmAndBulgingTheChestKeepTheMeshSound) {
  const Scene& human = Human();
  const int arm = PartIndex(human, "upper_arm_l"), torso = PartIndex(human, "chest");
  ASSERT_GE(arm, 0);
  ASSERT_GE(torso, 0);
  std::vector<PartPose> poses(human.model.parts.size());
  const PartModel& arm_part = human.model.parts[arm];
  const double force = 0.05 * arm_part.spine_stiffness.bending / std::pow(arm_part.spine_length, 3);
  const std::array<PointLoad, 1> load{{{0.8, Vec3(force, 0, 0)}}};
  poses[arm].loads.bending_point_loads = load;
  // The chest's profiles, their front halves pushed outwards (along +z, which
  // the rays of each profile start towards: the rest normal), 1 cm at most.
  std::vector<ProfileLoads> bulges;
  const PartModel& torso_part = human.model.parts[torso];
  std::vector<std::array<LineLoad, 1>> pushes;
  pushes.reserve(torso_part.profiles.size());
  for (std::uint32_t p = 1; p + 1 < torso_part.profiles.size(); ++p) {
    const ProfileModel& profile = torso_part.profiles[p];
    const double stretch = 0.4;  // of the loop
    double length = 0.0;
    const std::size_t m = profile.local_points.size();
    for (std::size_t q = 1; q <= m; ++q)
      length += (profile.local_points[q % m] - profile.local_points[q - 1]).norm();
    length *= stretch;
    // Uniform q on a clamped stretch: peak q L^4 / 384 EI = 1 cm.
    const double q_load = 0.01 * 384.0 * profile.stiffness.bending / std::pow(length, 4);
    pushes.push_back({{{0.0, 1.0, Vec3(q_load, 0, 0)}}});
    bulges.push_back({std::uint32_t(torso),
                      p,
                      0.0,
                      stretch,
                      BoundaryCondition::kClamped,
                      {},
                      pushes.back(),
                      {}});
  }
  RigWorkspace workspace = MakeRigWorkspace(human.model);
  std::vector<Vec3> positions(human.model.vertices.size()), normals(positions.size());
  EvaluateRigJob job;
  job.model = &human.model;
  job.poses = poses;
  job.profile_loads = bulges;
  job.workspace = &workspace;
  job.positions = positions;
  job.normals = normals;
  ASSERT_TRUE(job.Run().ok());
  std::vector<Vec3> rest_normals;
  const std::vector<Vec3> rest =
      Evaluate(human, std::vector<PartPose>(human.model.parts.size()), &rest_normals);
  std::size_t flipped = 0, chest_moved = 0;
  double largest = 0.0;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    ASSERT_TRUE(std::isfinite(positions[v].x()) && std::isfinite(positions[v].y()) &&
                std::isfinite(positions[v].z()));
    flipped += normals[v].dot(rest_normals[v]) < 0.0;
    if (int(human.model.vertices[v].part) == torso) {
      const double moved = (positions[v] - rest[v]).norm();
      chest_moved += moved > 1e-3;
      largest = std::max(largest, moved);
    }
  }
  // The mesh keeps its triangles (topology is never touched, so no new boundary edges): what
  // can go wrong is folding, which flips normals. Report and bound it.
  EXPECT_LT(flipped, positions.size() / 100) << flipped << " vertex normals flipped";
  EXPECT_GT(chest_moved, 20u);
  EXPECT_LT(largest, 0.011);  // nothing moves further than the bulge's 1 cm peak (+ rounding)
}

TEST(RigEvaluation, InvalidJobsAreRefused) {
  const Scene& human = Human();
  RigWorkspace workspace = MakeRigWorkspace(human.model);
  std::vector<Vec3> positions(human.model.vertices.size());
  std::vector<PartPose> poses(human.model.parts.size());
  EvaluateRigJob job;
  job.model = &human.model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  ASSERT_TRUE(job.Validate().ok());
  job.poses = std::span<const PartPose>(poses).first(1);
  EXPECT_EQ(job.Validate().field, "poses");
  job.poses = poses;
  poses[1].rotation.coeffs() << 0, 0, 0, 2;
  EXPECT_EQ(job.Validate().field, "poses");
  poses[1].rotation = Quat::Identity();
  job.positions = std::span<Vec3>(positions).first(10);
  EXPECT_EQ(job.Validate().field, "positions");
  job.positions = positions;
  job.workspace = nullptr;
  EXPECT_EQ(job.Validate().field, "workspace");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

// Six times the volume the welded triangles enclose.
double Volume6(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles) {
  double volume = 0.0;
  for (const Triangle& t : triangles)
    volume += positions[t[0]].dot(positions[t[1]].cross(positions[t[2]]));
  return volume;
}

const Scene& Capsule() {
  static const Scene scene = [] {
    RigDescription description;
    description.parts.push_back({"body", {Vec3(0, 0, 0), Vec3(0, 1, 0)}, 10, 32, "", {}, {}});
    return Build(MakeCapsule(0.1, 1.0, 64, 40, 8), description, SpineKind::kDeformable);
  }();
  return scene;
}

TEST(RigEvaluation, VolumePreservationKeepsAStretchedPartsVolume) {
  const Scene& capsule = Capsule();
  const PartModel& part = capsule.model.parts[0];
  // A 20% axial strain along the whole spine: an end force of 0.2 EA, fixed at the root.
  const std::array<AxialPointLoad, 1> pull{{{1.0, 0.2 * part.spine_stiffness.axial}}};
  std::vector<PartPose> poses(1);
  poses[0].loads.axial_point_loads = pull;
  const double rest = Volume6(capsule.mesh.welded_positions, capsule.mesh.welded_triangles);
  RigWorkspace workspace = MakeRigWorkspace(capsule.model);
  std::vector<Vec3> positions(capsule.model.vertices.size());
  EvaluateRigJob job;
  job.model = &capsule.model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  ASSERT_TRUE(job.Run().ok());
  const double stretched = Volume6(positions, capsule.mesh.welded_triangles);
  job.preserve_volume = true;
  ASSERT_TRUE(job.Run().ok());
  const double preserved = Volume6(positions, capsule.mesh.welded_triangles);
  EXPECT_GT(stretched / rest - 1.0, 0.1);  // plain stretching adds volume
  EXPECT_LT(std::abs(preserved / rest - 1.0), 0.01);
  // The spine still stretched: the tip moved by the closed form F L / EA = 0.2 L.
  EXPECT_NEAR((workspace.spine_points[0].back() - part.spine_points.back()).norm(),
              0.2 * part.spine_length, 1e-9);
}

TEST(RigEvaluation, AProfileLoadMovesOnlyTheVerticesNextToItsProfile) {
  const Scene& capsule = Capsule();
  const PartModel& part = capsule.model.parts[0];
  const std::uint32_t loaded = 5;
  const ProfileModel& profile = part.profiles[loaded];
  // A clamped stretch over a quarter of the loop, pushed outwards (along the normal) at its middle.
  const double force = 1e-4 * profile.stiffness.bending;
  const std::array<PointLoad, 1> push{{{0.5, Vec3(force, 0, 0)}}};
  const std::array<ProfileLoads, 1> loads{
      {{0, loaded, 0.0, 0.25, BoundaryCondition::kClamped, push, {}, {}}}};
  std::vector<PartPose> poses(1);
  const std::vector<Vec3> rest = Evaluate(capsule, poses);
  RigWorkspace workspace = MakeRigWorkspace(capsule.model);
  std::vector<Vec3> positions(capsule.model.vertices.size());
  EvaluateRigJob job;
  job.model = &capsule.model;
  job.poses = poses;
  job.profile_loads = loads;
  job.workspace = &workspace;
  job.positions = positions;
  ASSERT_TRUE(job.Run().ok());
  std::size_t moved_near = 0;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const VertexAttachment& a = capsule.model.vertices[v];
    const bool next_to = !a.cap && (a.profile == loaded || a.profile + 1 == loaded);
    const double moved = (positions[v] - rest[v]).norm();
    if (next_to) {
      moved_near += moved > 1e-9;
    } else {
      EXPECT_EQ(positions[v], rest[v]) << "vertex " << v;
    }
  }
  EXPECT_GT(moved_near, 10u);
  // The loaded profile's points follow the closed form: the stretch's middle point moves by
  // F L^3 / 192 EI along the normal, L the stretch's rest arc length.
  const std::size_t m = profile.local_points.size();
  double length = 0.0;
  for (std::size_t q = 1; q <= m / 4; ++q)
    length += (profile.local_points[q] - profile.local_points[q - 1]).norm();
  const double expected = force * length * length * length / (192.0 * profile.stiffness.bending);
  Vec3 origin;
  const Frame frame = InterpolateSpine(workspace.spine_points[0], workspace.spine_frames[0],
                                       profile.spine_v, &origin);
  const Vec3 moved = workspace.profile_points[0][loaded][m / 8] -
                     (origin + frame.normal * profile.local_points[m / 8].x() +
                      frame.binormal * profile.local_points[m / 8].y() +
                      frame.tangent * profile.local_points[m / 8].z());
  EXPECT_NEAR(moved.dot(frame.normal), expected, 1e-9 * expected + 1e-15);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

std::vector<PartWarnings> WarningsFor(const Scene& scene, double tip_force) {
  std::vector<PartPose> poses(scene.model.parts.size());
  poses[0].loads.tip_force = Vec3(tip_force, 0, 0);
  RigWorkspace workspace = MakeRigWorkspace(scene.model);
  std::vector<Vec3> positions(scene.model.vertices.size());
  std::vector<PartWarnings> warnings(scene.model.parts.size());
  EvaluateRigJob job;
  job.model = &scene.model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  job.warnings = warnings;
  EXPECT_TRUE(job.Run().ok());
  return warnings;
}

TEST(RigEvaluationWarnings, SmallLoadsWarnAboutNothing) {
  const Scene& capsule = Capsule();
  const PartModel& part = capsule.model.parts[0];
  const double small = 0.01 * part.spine_stiffness.bending / std::pow(part.spine_length, 2);
  const PartWarnings w = WarningsFor(capsule, small)[0];
  EXPECT_FALSE(w.any());
  // Tip slope of a cantilever: F L^2 / 2EI.
  EXPECT_NEAR(w.max_slope, std::atan(0.005), 1e-9);
}

TEST(RigEvaluationWarnings, LargeLoadsLeaveTheLinearRangeAndFoldTheSkin) {
  const Scene& capsule = Capsule();
  const PartModel& part = capsule.model.parts[0];
  // Curvature at the clamp F L / EI = 60 / L: far tighter than the 0.1 m radius allows, and
  // the second profile tilts by atan(F s (L - s/2) / EI) ~ 1.4 rad: it crosses the first.
  const double large = 60.0 * part.spine_stiffness.bending / std::pow(part.spine_length, 2);
  const PartWarnings w = WarningsFor(capsule, large)[0];
  EXPECT_TRUE(w.beyond_small_deflection);
  EXPECT_NEAR(w.max_deflection_ratio,
              large * std::pow(part.spine_length, 2) / (3.0 * part.spine_stiffness.bending), 1e-9);
  EXPECT_GT(w.tight_bends, 0u);
  EXPECT_GT(w.crossing_profiles, 0u);
}

TEST(RigEvaluation, ConcurrentEvaluationsOfOneModelAgreeWithSequentialOnes) {
  const Scene& human = Human();
  std::vector<PartPose> a(human.model.parts.size()), b(human.model.parts.size());
  a[2].rotation = Quat(Eigen::AngleAxisd(0.4, Vec3::UnitZ()));
  b[0].translation = Vec3(0.1, 0.2, 0.3);
  const std::vector<Vec3> expected_a = Evaluate(human, a), expected_b = Evaluate(human, b);
  std::vector<Vec3> got_a, got_b;
  std::thread first([&] {
    for (int i = 0; i < 20; ++i) got_a = Evaluate(human, a);
  });
  std::thread second([&] {
    for (int i = 0; i < 20; ++i) got_b = Evaluate(human, b);
  });
  first.join();
  second.join();
  EXPECT_EQ(got_a, expected_a);
  EXPECT_EQ(got_b, expected_b);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using testing::BusyPose;

BusyPose MakeBusyPose(const Scene& scene) { return testing::MakeBusyPose(scene.model); }

struct Evaluated {
  std::vector<Vec3> positions, normals;
  RigWorkspace workspace;
};

Evaluated EvaluateBusy(const Scene& scene, const BusyPose& pose, const ParallelFor* parallel) {
  Evaluated out;
  out.workspace = MakeRigWorkspace(scene.model);
  out.positions.resize(scene.model.vertices.size());
  out.normals.resize(scene.model.vertices.size());
  EvaluateRigJob job;
  job.model = &scene.model;
  job.poses = pose.poses;
  job.profile_loads = pose.profile_loads;
  job.workspace = &out.workspace;
  job.positions = out.positions;
  job.normals = out.normals;
  job.preserve_volume = true;
  job.parallel = parallel;
  const Status status = job.Run();
  EXPECT_TRUE(status.ok()) << ToString(status);
  return out;
}

TEST(RigEvaluation, FlatVertexPassAgreesWithApplyPairBindingAndTriangleOrderNormals) {
  const Scene& human = Human();
  const Evaluated got = EvaluateBusy(human, MakeBusyPose(human), nullptr);
  const RigWorkspace& w = got.workspace;
  // Reference: every vertex by ApplyPairBinding (or its cap frame) on the evaluated wires.
  double worst = 0.0;
  std::size_t pairs = 0, caps = 0, on_bridges = 0, others = 0, below = 0;
  for (std::size_t v = 0; v < got.positions.size(); ++v) {
    const VertexAttachment& a = human.model.vertices[v];
    const PartModel& part = human.model.parts[a.part];
    Vec3 expected;
    if (a.cap) {
      Vec3 origin;
      const Frame frame = InterpolateSpine(w.spine_points[a.part], w.spine_frames[a.part],
                                           part.profiles[a.profile].spine_v, &origin);
      Mat3 axes = FrameAxes(frame);
      const double scale = w.profile_scale[a.part][a.profile];
      axes.col(0) *= scale;
      axes.col(1) *= scale;
      axes.col(2) /= scale * scale;
      expected = origin + axes * a.cap_local;
      ++caps;
    } else {
      expected = ApplyPairBinding(
          a.pair, {w.profile_points[a.part][a.profile], part.profiles[a.profile].closed},
          {w.profile_points[a.part][a.profile + 1], part.profiles[a.profile + 1].closed},
          w.profile_origins[a.part][a.profile], w.profile_origins[a.part][a.profile + 1]);
      ++pairs;
    }
    // Near a joint: towards the bridge's image of the point undone into rest space by its own
    // spine sample's frame.
    Vec3 bridged = Vec3::Zero();
    for (const JointInfluence& j : a.joints) {
      if (j.joint < 0) continue;
      // (the sample's stretch 1 + strain along it and, volume kept, scale 1 / sqrt(1 + strain)
      // across it undone too)
      const double stretch = 1.0 + w.strain[a.part][j.sample], shrink = std::sqrt(stretch);
      const Mat3 undo = FrameAxes(part.spine_frames[j.sample]) *
                        Vec3(shrink, shrink, 1.0 / stretch).asDiagonal() *
                        FrameAxes(w.spine_frames[a.part][j.sample]).transpose();
      const Vec3 rest =
          part.spine_points[j.sample] + undo * (expected - w.spine_points[a.part][j.sample]);
      // The bridge's image minus the rigid motion of the vertex's side of the joint: its own
      // position on the child, the child's rigid motion below the child, else the parent's.
      const BridgeSamples& bridge = w.bridges[std::size_t(j.joint)];
      bool below_child = false;
      for (int p = human.model.parts[a.part].parent; p >= 0; p = human.model.parts[p].parent)
        below_child = below_child || p == j.joint;
      const Vec3 base = j.joint == int(a.part) ? expected
                        : below_child ? Vec3(bridge.child_turn * rest + bridge.child_offset)
                                      : Vec3(bridge.parent_turn * rest + bridge.parent_offset);
      bridged += j.weight * (ApplyJointBridge(bridge, j.u, j.bridge, rest, j.section) - base);
      ++on_bridges;
      others += int(a.part) != j.joint && int(a.part) != human.model.parts[j.joint].parent;
      below += below_child;
    }
    expected += bridged;
    worst = std::max(worst, (got.positions[v] - expected).norm());
  }
  EXPECT_GT(pairs, 1000u);
  EXPECT_GT(caps, 10u);
  EXPECT_GT(on_bridges, 100u);
  EXPECT_GT(others, 10u);  // the shoulders' and hips' skin spreads over the torso
  EXPECT_GT(below, 10u);   // the chest's over the arms' skin beside it
  EXPECT_LT(worst, 1e-12 * human.diagonal);
  // Normals: accumulated over the triangles in order, then normalised, exactly.
  std::vector<Vec3> sum(got.positions.size(), Vec3::Zero());
  for (const Triangle& t : human.model.triangles) {
    const Vec3 n = (got.positions[t[1]] - got.positions[t[0]])
                       .cross(got.positions[t[2]] - got.positions[t[0]]);
    for (std::uint32_t index : t) sum[index] += n;
  }
  for (std::size_t v = 0; v < sum.size(); ++v) {
    const double length = sum[v].norm();
    const Vec3 expected = length > 0.0 ? Vec3(sum[v] * (1.0 / length)) : Vec3::UnitY();
    EXPECT_EQ(got.normals[v], expected) << "vertex " << v;
  }
}

TEST(RigEvaluation, ParallelEvaluationIsBitIdenticalToSequential) {
  const Scene& human = Human();
  const BusyPose pose = MakeBusyPose(human);
  const Evaluated sequential = EvaluateBusy(human, pose, nullptr);
  for (std::size_t threads : {1u, 2u, 3u}) {
    const ThreadPool pool(threads);
    EXPECT_EQ(pool.concurrency(), threads);
    for (int repeat = 0; repeat < 3; ++repeat) {
      const Evaluated parallel = EvaluateBusy(human, pose, &pool);
      EXPECT_EQ(parallel.positions, sequential.positions) << threads << " threads";
      EXPECT_EQ(parallel.normals, sequential.normals) << threads << " threads";
    }
  }
}

// The float evaluation (engine buffers, four vertices at a time) computes what the double one
// does, whose vertices the test above checks against ApplyPairBinding and ApplyJointBridge:
// the same positions and normals to float precision, into an interleaved buffer (position and
// normal of a vertex side by side, stride 6), bit-identical on any number of threads.
std::vector<float> EvaluateBusyFloat(const Scene& scene, const BusyPose& pose,
                                     const ParallelFor* parallel, bool allow_avx2 = true) {
  return testing::EvaluateBusyInterleaved(scene.model, pose, parallel, allow_avx2);
}

// Eight lanes (AVX2, where this CPU has it) and four (SSE2) do the same IEEE operations per
// vertex: the same bits, on one thread and on several.
TEST(RigEvaluation, WidePacksGiveTheBaselinesBits) {
  const Scene& human = Human();
  const BusyPose pose = MakeBusyPose(human);
  const std::vector<float> baseline = EvaluateBusyFloat(human, pose, nullptr, false);
  EXPECT_EQ(EvaluateBusyFloat(human, pose, nullptr, true), baseline);
  const ThreadPool pool(3);
  EXPECT_EQ(EvaluateBusyFloat(human, pose, &pool, true), baseline);
  EXPECT_EQ(EvaluateBusyFloat(human, pose, &pool, false), baseline);
}

TEST(RigEvaluation, FloatEngineBuffersHoldTheDoubleEvaluationToFloatPrecision) {
  const Scene& human = Human();
  const BusyPose pose = MakeBusyPose(human);
  const Evaluated exact = EvaluateBusy(human, pose, nullptr);
  const std::vector<float> buffer = EvaluateBusyFloat(human, pose, nullptr);
  double worst_position = 0.0, worst_normal = 0.0, sum_normal = 0.0;
  for (std::size_t v = 0; v < exact.positions.size(); ++v) {
    const Vec3 p(buffer[6 * v], buffer[6 * v + 1], buffer[6 * v + 2]);
    const Vec3 n(buffer[6 * v + 3], buffer[6 * v + 4], buffer[6 * v + 5]);
    worst_position = std::max(worst_position, (p - exact.positions[v]).norm());
    EXPECT_NEAR(n.norm(), 1.0, 1e-6) << "vertex " << v;
    const double angle = std::acos(std::clamp(n.dot(exact.normals[v]), -1.0, 1.0));
    worst_normal = std::max(worst_normal, angle);
    sum_normal += angle;
  }
  // float carries 24 bits: positions to a few units of 6e-8 of the body's size; a normal from
  // edges of a few mm whose ends are that far off turns by ~1e-4 rad (a wrong triangle or sum
  // would turn it by far more than 0.3 degrees).
  EXPECT_LT(worst_position, 1e-6 * human.diagonal);
  EXPECT_LT(worst_normal, 5e-3);  // rad
  EXPECT_LT(sum_normal / double(exact.positions.size()), 5e-4);
  for (std::size_t threads : {2u, 3u}) {
    const ThreadPool pool(threads);
    EXPECT_EQ(EvaluateBusyFloat(human, pose, &pool), buffer) << threads << " threads";
  }
}

// Into the source asset's vertex order (the mesh's unwelded vertices, through its weld map):
// each output vertex holds exactly what the welded order holds for its welded vertex.
TEST(RigEvaluation, FloatBuffersInTheSourceAssetsVertexOrder) {
  const Scene& human = Human();
  const BusyPose pose = MakeBusyPose(human);
  const std::vector<float> welded = EvaluateBusyFloat(human, pose, nullptr);
  const std::vector<std::uint32_t>& order = human.mesh.weld_map;
  ASSERT_GT(order.size(), human.model.vertices.size());  // seams split some vertices
  RigWorkspace workspace = MakeRigWorkspace(human.model);
  std::vector<float> positions(3 * order.size()), normals(3 * order.size());
  EvaluateRigJob job;
  job.model = &human.model;
  job.poses = pose.poses;
  job.profile_loads = pose.profile_loads;
  job.workspace = &workspace;
  job.float_positions = positions;
  job.float_normals = normals;
  job.float_vertex_order = order;
  job.preserve_volume = true;
  ASSERT_TRUE(job.Run().ok());
  for (std::size_t i = 0; i < order.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(positions[3 * i + c], welded[6 * order[i] + c]) << "vertex " << i;
      ASSERT_EQ(normals[3 * i + c], welded[6 * order[i] + 3 + c]) << "vertex " << i;
    }
  std::vector<std::uint32_t> bad = order;
  bad.back() = std::uint32_t(human.model.vertices.size());
  job.float_vertex_order = bad;
  EXPECT_EQ(job.Run().field, "float_vertex_order");
}

TEST(RigEvaluation, FloatOutputsAreCheckedBeforeAnythingIsWritten) {
  const Scene& human = Human();
  const std::size_t n = human.model.vertices.size();
  RigWorkspace workspace = MakeRigWorkspace(human.model);
  std::vector<PartPose> poses(human.model.parts.size());
  std::vector<Vec3> positions(n, Vec3::Constant(5.0));
  std::vector<float> buffer(6 * n, 5.0f);
  auto job = [&] {
    EvaluateRigJob j;
    j.model = &human.model;
    j.poses = poses;
    j.workspace = &workspace;
    return j;
  };
  auto expect_invalid = [&](const EvaluateRigJob& j, const std::string& field) {
    const Status status = j.Run();
    EXPECT_FALSE(status.ok());
    EXPECT_EQ(status.field, field) << ToString(status);
    EXPECT_TRUE(std::all_of(buffer.begin(), buffer.end(), [](float x) { return x == 5.0f; }));
    EXPECT_TRUE(std::all_of(positions.begin(), positions.end(),
                            [](const Vec3& p) { return p == Vec3::Constant(5.0); }));
  };
  EvaluateRigJob both = job();
  both.positions = positions;
  both.float_positions = buffer;
  expect_invalid(both, "positions");
  expect_invalid(job(), "positions");  // neither
  EvaluateRigJob narrow = job();
  narrow.float_positions = buffer;
  narrow.float_position_stride = 2;
  expect_invalid(narrow, "float_positions");
  EvaluateRigJob short_buffer = job();
  short_buffer.float_positions = std::span<float>(buffer).first(3 * n - 1);
  expect_invalid(short_buffer, "float_positions");
  EvaluateRigJob short_normals = job();
  short_normals.float_positions = buffer;
  short_normals.float_normals = std::span<float>(buffer).subspan(3);
  short_normals.float_normal_stride = 6;  // the last vertex's normal would run past the end
  short_normals.float_normals = short_normals.float_normals.first(6 * (n - 1) + 2);
  expect_invalid(short_normals, "float_normals");
  // A stride whose (n - 1) * stride + 3 wraps to a small number passed, then the stage wrote
  // far outside the buffer: s * (n - 1) = 1 modulo 2^64 for odd n - 1 (an engine programmer's
  // crafted stride, through the C API).
  const std::uint64_t m = n - 1;
  ASSERT_EQ(m % 2, 1u) << "an odd n - 1 has an inverse modulo 2^64";
  std::uint64_t inverse = m;  // Newton's iteration for the inverse of m modulo 2^64
  for (int i = 0; i < 6; ++i) inverse *= 2 - m * inverse;
  ASSERT_EQ(inverse * m, 1u);
  EvaluateRigJob wrapping = job();
  wrapping.float_positions = buffer;
  wrapping.float_position_stride = inverse;
  expect_invalid(wrapping, "float_positions");
  EvaluateRigJob wrapping_normals = job();
  wrapping_normals.float_positions = buffer;
  wrapping_normals.float_normals = buffer;
  wrapping_normals.float_normal_stride = inverse;
  expect_invalid(wrapping_normals, "float_normals");
  EvaluateRigJob huge = job();
  huge.float_positions = buffer;
  huge.float_position_stride = std::numeric_limits<std::size_t>::max();
  expect_invalid(huge, "float_positions");
  EvaluateRigJob mixed = job();
  mixed.positions = positions;
  mixed.float_normals = buffer;
  expect_invalid(mixed, "float_normals");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
