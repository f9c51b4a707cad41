// A child part's pose turns every vertex of that part rigidly about its spine's root, end caps
// (hands, feet) included, on a real mesh, and moves nothing else: no vertex of another part
// follows it (a hand once took the toes of the other foot, and the turn tore the mesh).
#include <gtest/gtest.h>

#include "wirerig/anim/scene.h"
#include "wirerig/runtime/rig_evaluation.h"

#ifndef WIRERIG_SAMPLES_DIR
#define WIRERIG_SAMPLES_DIR "/work/main/samples"
#endif

namespace wirerig {
namespace {

TEST(ChildPose, RotatingAnArmMovesItsVerticesRigidlyAboutItsRootBeyondTheJointBridge) {
  SceneDescription description =
      LoadScene(std::string(WIRERIG_SAMPLES_DIR) + "/human/human_wave.scene.json").value();
  description.clips.clear();
  const BuiltScene scene = BuildScene(description).value();
  const RigModel& model = scene.model;
  std::size_t arm = 0;
  while (model.parts[arm].name != "arm_left") ++arm;
  std::vector<PartPose> poses(model.parts.size());
  poses[arm].rotation = Quat(Eigen::AngleAxisd(0.9, Vec3::UnitZ()));
  RigWorkspace workspace = MakeRigWorkspace(model);
  std::vector<Vec3> positions(model.vertices.size());
  EvaluateRigJob job;
  job.model = &model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  ASSERT_TRUE(job.Run().ok());
  const Vec3 root = model.parts[arm].spine_points.front();
  const Mat3 r = poses[arm].rotation.toRotationMatrix();
  std::size_t wrong = 0, caps = 0;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    // Vertices on a skin bridge (joint_bridge.h) blend across the joint instead.
    if (model.vertices[v].part != arm || model.vertices[v].joints[0].joint >= 0) continue;
    const Vec3 expected = root + r * (scene.mesh.welded_positions[v] - root);
    if ((positions[v] - expected).norm() > 1e-6) {
      ++wrong;
      caps += model.vertices[v].cap;
    }
  }
  EXPECT_EQ(wrong, 0u) << caps << " of them caps";
  // Every other part stays where it was, but for its skin on the arm's bridge.
  std::size_t others_moved = 0;
  for (std::size_t v = 0; v < positions.size(); ++v)
    if (model.vertices[v].part != arm && model.vertices[v].joints[0].joint != int(arm) &&
        model.vertices[v].joints[1].joint != int(arm))
      others_moved += (positions[v] - scene.mesh.welded_positions[v]).norm() > 1e-9;
  EXPECT_EQ(others_moved, 0u);
  // And the picture: no triangle stretched beyond the model (every edge no longer than at rest
  // plus the arm's turn).
  double longest_rest = 0.0, longest = 0.0;
  for (const Triangle& t : model.triangles)
    for (int k = 0; k < 3; ++k) {
      longest_rest = std::max(
          longest_rest,
          (scene.mesh.welded_positions[t[k]] - scene.mesh.welded_positions[t[(k + 1) % 3]]).norm());
      longest = std::max(longest, (positions[t[k]] - positions[t[(k + 1) % 3]]).norm());
    }
  EXPECT_LE(longest, longest_rest + 0.3) << longest_rest;
}

}  // namespace
}  // namespace wirerig
