// A child part's joint rotation turns every vertex of that part and of the parts hanging from it
// rigidly about its spine's root, end caps (hands) included, on a real mesh (the human bone
// chain), and moves nothing else: no vertex of another part follows it (a hand once took the
// toes of the other foot, and the turn tore the mesh).
#include <gtest/gtest.h>

#include <algorithm>

#include "wirerig/anim/scene.h"
#include "wirerig/runtime/joint.h"
#include "wirerig/runtime/rig_evaluation.h"

#ifndef WIRERIG_SAMPLES_DIR
#error "the tests need WIRERIG_SAMPLES_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

std::size_t FindPart(const RigModel& model, const std::string& name) {
  std::size_t p = 0;
  while (p < model.parts.size() && model.parts[p].name != name) ++p;
  EXPECT_LT(p, model.parts.size()) << "no part " << name;
  return p;
}

TEST(ChildPose, RotatingAnUpperArmMovesItsArmRigidlyAboutItsRootBeyondTheJointBridge) {
  SceneDescription description =
      LoadScene(std::string(WIRERIG_SAMPLES_DIR) + "/human/human_wave.scene.json").value();
  description.clips.clear();
  const BuiltScene scene = BuildScene(description).value();
  const RigModel& model = scene.model;
  const std::size_t arm = FindPart(model, "upper_arm_l");
  const std::size_t forearm = FindPart(model, "forearm_l");
  const std::size_t hand = FindPart(model, "hand_l");
  ASSERT_EQ(model.parts[forearm].parent, int(arm));
  ASSERT_EQ(model.parts[hand].parent, int(forearm));
  const auto in_arm = [&](std::size_t p) { return p == arm || p == forearm || p == hand; };

  // The arm raised sideways and forwards by its shoulder joint, inside the joint's limits.
  const Vec3 angles(-20.0, 40.0, 0.0);
  ASSERT_EQ(ClampJointAngles(model.parts[arm].joint, angles), angles);
  std::vector<PartPose> poses(model.parts.size());
  poses[arm].rotation = JointRotation(model.parts[arm].joint, angles);
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
  std::size_t wrong = 0, caps = 0, checked = 0;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    // Vertices on the shoulder's skin bridge (joint_bridge.h) blend across it instead. The
    // elbow and the wrist are not bent, so their bridges turn rigidly with the arm.
    if (!in_arm(model.vertices[v].part) || model.vertices[v].OnJoint(int(arm))) continue;
    ++checked;
    const Vec3 expected = root + r * (scene.mesh.welded_positions[v] - root);
    if ((positions[v] - expected).norm() > 1e-6) {
      ++wrong;
      caps += model.vertices[v].cap;
    }
  }
  EXPECT_GT(checked, 1000u);
  EXPECT_EQ(wrong, 0u) << caps << " of them caps";
  // The hand went somewhere: its tip moved by well over 10 cm.
  const std::size_t tip = workspace.spine_points[hand].size() - 1;
  EXPECT_GT((workspace.spine_points[hand][tip] - model.parts[hand].spine_points[tip]).norm(), 0.1);

  // Every other part stays where it was, but for its skin on the shoulder's bridge.
  std::size_t others_moved = 0, others = 0;
  for (std::size_t v = 0; v < positions.size(); ++v)
    if (!in_arm(model.vertices[v].part) && !model.vertices[v].OnJoint(int(arm))) {
      ++others;
      others_moved += (positions[v] - scene.mesh.welded_positions[v]).norm() > 1e-9;
    }
  EXPECT_GT(others, 5000u);
  EXPECT_EQ(others_moved, 0u);

  // And the picture: no edge stretched absurdly. The shoulder's skin still folds where the upper
  // arm's armpit meets the side of the ribs (README, status; measured: an edge grows by 7 cm
  // here), but none by 15 cm (a vertex left behind on the wrong part stretches one by half a
  // metre).
  double worst = 0.0;
  for (const Triangle& t : model.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      const double rest = (scene.mesh.welded_positions[a] - scene.mesh.welded_positions[b]).norm();
      worst = std::max(worst, (positions[a] - positions[b]).norm() - rest);
    }
  EXPECT_LT(worst, 0.15);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
