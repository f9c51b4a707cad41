// DescribeFromSkeleton: one part per bone of the asset's skeleton. Hand-built skeletons check
// the bones' curves (to the child continuing the chain; a leaf's from its skinned vertices),
// the parents (side branches off a branching joint), bones merged away (no vertices, no
// length), several trees, names and joints; the Assimp test model anim_test.x (ASSETS.md) checks
// a real file all the way to a built rig.
#include "wirerig/rig/skeleton_description.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/rig_builder.h"

#ifndef WIRERIG_ASSET_DIR
#error "the tests need WIRERIG_ASSET_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

Joint MakeJoint(const std::string& name, int parent, const Vec3& at,
                const Mat3& rotation = Mat3::Identity()) {
  Joint joint;
  joint.name = name;
  joint.parent = parent;
  joint.bind_global.topLeftCorner<3, 3>() = rotation;
  joint.bind_global.block<3, 1>(0, 3) = at;
  return joint;
}

// A render vertex and its influences (joint, weight).
struct SkinnedPoint {
  Vec3 position;
  std::vector<std::pair<int, double>> influences;
};

// Render vertices as given; welded vertices one per point, except that render vertex 1 is a
// second copy of render vertex 0 (a texture seam) and welds onto it.
Mesh MakeSkinnedMesh(std::vector<Joint> joints, const std::vector<SkinnedPoint>& points) {
  Mesh mesh;
  mesh.joints = std::move(joints);
  for (const SkinnedPoint& point : points) {
    mesh.positions.push_back(point.position);
    std::array<int, 4> slots{-1, -1, -1, -1};
    Vec4 weights = Vec4::Zero();
    for (std::size_t k = 0; k < point.influences.size(); ++k) {
      slots[k] = point.influences[k].first;
      weights[long(k)] = point.influences[k].second;
    }
    mesh.skin_joints.push_back(slots);
    mesh.skin_weights.push_back(weights);
  }
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (v == 1) {
      mesh.weld_map.push_back(0);
      continue;
    }
    mesh.weld_map.push_back(std::uint32_t(mesh.welded_positions.size()));
    mesh.welded_positions.push_back(mesh.positions[v]);
  }
  return mesh;
}

void ExpectCurve(const PartDescription& part, const std::vector<Vec3>& expected) {
  ASSERT_EQ(part.central_curve.size(), expected.size()) << part.name;
  for (std::size_t k = 0; k < expected.size(); ++k)
    EXPECT_NEAR((part.central_curve[k] - expected[k]).norm(), 0.0, 1e-12)
        << part.name << " point " << k << ": " << part.central_curve[k].transpose();
}

// hips -> spine -> chest, a chain of three bones; chest branches into the head (continuing the
// chain), an arm (through a wrist pivot sitting on the hand joint) and an unskinned IK pole.
enum : int { kHips, kSpine, kChest, kHead, kArm, kWristPivot, kHand, kIkPole };

Mesh BranchingSkeletonMesh() {
  std::vector<Joint> joints = {MakeJoint("hips", -1, Vec3(0, 0, 0)),
                               MakeJoint("spine", kHips, Vec3(0, 1, 0)),
                               MakeJoint("chest", kSpine, Vec3(0, 2, 0)),
                               MakeJoint("head", kChest, Vec3(0, 2.5, 0)),
                               MakeJoint("arm", kChest, Vec3(0.5, 2, 0)),
                               MakeJoint("wrist", kArm, Vec3(1.5, 2, 0)),
                               MakeJoint("hand", kWristPivot, Vec3(1.5, 2, 0)),
                               MakeJoint("ik_pole", kChest, Vec3(0, 2, -1))};
  return MakeSkinnedMesh(
      std::move(joints),
      {
          {Vec3(0.2, 0.5, 0), {{kHips, 1.0}}},                  // render 0 -> welded 0
          {Vec3(0.2, 0.5, 0), {{kSpine, 1.0}}},                 // render 1 -> welded 0 too
          {Vec3(-0.2, -0.1, 0), {{kHips, 1.0}}},                // welded 1
          {Vec3(0.2, 1.5, 0), {{kHips, 0.2}, {kSpine, 0.8}}},   // welded 2: spine
          {Vec3(0.2, 2.2, 0), {{kSpine, 0.3}, {kChest, 0.7}}},  // welded 3: chest
          {Vec3(0.1, 2.6, 0), {{kHead, 1.0}}},                  // welded 4
          {Vec3(0.0, 3.2, 0.05), {{kHead, 1.0}}},               // welded 5: the top of the head
          {Vec3(0.1, 2.4, 0), {{kHead, 1.0}}},                  // welded 6: behind the joint
          {Vec3(1.0, 2.1, 0), {{kArm, 0.6}, {kHand, 0.4}}},     // welded 7: arm
          {Vec3(1.45, 2.0, 0), {{kWristPivot, 1.0}}},           // welded 8: pivot -> arm
          {Vec3(1.7, 2.0, 0.1), {{kHand, 1.0}}},                // welded 9
          {Vec3(1.9, 2.05, 0), {{kArm, 0.1}, {kHand, 0.9}}},    // welded 10: the fingertip
          {Vec3(0.0, 0.0, 0.3), {}},                            // welded 11: no influence
      });
}

TEST(SkeletonDescription, OnePartPerBoneWithItsParentAndCurve) {
  const Mesh mesh = BranchingSkeletonMesh();
  const Result<RigDescription> result = DescribeFromSkeleton(mesh);
  ASSERT_TRUE(result.ok()) << result.error();
  const RigDescription& d = result.value();
  EXPECT_EQ(ValidateRigDescription(d), "");

  // The wrist pivot (no length: it sits on the hand joint) merges into the arm with its one
  // vertex, the IK pole (no vertices) into the chest; every other bone is a part, in skeleton
  // order.
  ASSERT_EQ(d.parts.size(), 6u);
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"hips", ""},      {"spine", "hips"}, {"chest", "spine"},
      {"head", "chest"}, {"arm", "chest"},  {"hand", "arm"}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(d.parts[i].name, expected[i].first);
    EXPECT_EQ(d.parts[i].parent, expected[i].second) << d.parts[i].name;
  }

  // Each bone runs from its joint to the child continuing its chain: chest to the head (the
  // child most aligned with the spine), not to the arm or the pole.
  ExpectCurve(d.parts[0], {Vec3(0, 0, 0), Vec3(0, 1, 0)});
  ExpectCurve(d.parts[1], {Vec3(0, 1, 0), Vec3(0, 2, 0)});
  ExpectCurve(d.parts[2], {Vec3(0, 2, 0), Vec3(0, 2.5, 0)});
  ExpectCurve(d.parts[4], {Vec3(0.5, 2, 0), Vec3(1.5, 2, 0)});  // through the pivot
  // Leaves run along the bone coming into them to their farthest skinned vertex: the head
  // 0.7 up the spine's direction, the hand 0.4 along the arm.
  ExpectCurve(d.parts[3], {Vec3(0, 2.5, 0), Vec3(0, 3.2, 0)});
  ExpectCurve(d.parts[5], {Vec3(1.5, 2, 0), Vec3(1.9, 2, 0)});

  // Ball joints about the bind X axis, or Z where X runs along the bone; no limits.
  for (const PartDescription& part : d.parts) {
    EXPECT_EQ(part.joint.type, JointType::kBall) << part.name;
    ASSERT_TRUE(part.joint.axis.has_value()) << part.name;
    const bool along_x = part.name == "arm" || part.name == "hand";
    EXPECT_NEAR((*part.joint.axis - (along_x ? Vec3::UnitZ() : Vec3::UnitX())).norm(), 0.0, 1e-12)
        << part.name;
    EXPECT_EQ(part.joint.min_degrees, Vec3::Constant(-180.0)) << part.name;
    EXPECT_EQ(part.joint.max_degrees, Vec3::Constant(180.0)) << part.name;
  }

  // Welded vertices follow their first render vertex's joint of largest weight; the pivot's
  // vertex goes to the arm it merged into; an uninfluenced vertex is left to the nearest curve.
  const std::vector<int> vertex_part = {0, 0, 1, 2, 3, 3, 3, 4, 4, 5, 5, -1};
  EXPECT_EQ(d.vertex_part, vertex_part);
}

TEST(SkeletonDescription, UnskinnedRootIsDroppedAndTheLargestTreeLeads) {
  // "Root" joins two trees and has no skin (like Testwuson's); the body holds the most
  // vertices, so it leads and the tail hangs from the body's part nearest the tail's joint.
  // Names: an empty one becomes "bone_<index>", a repeated one gets "_2".
  std::vector<Joint> joints = {
      MakeJoint("Root", -1, Vec3(0, 0, 0)), MakeJoint("tail", 0, Vec3(0, 0, -0.2)),
      MakeJoint("body", 1, Vec3(0, 0, -1)), MakeJoint("body", 0, Vec3(0, 0, 0.2)),
      MakeJoint("", 3, Vec3(0, 0, 1.2))};
  const Mesh mesh = MakeSkinnedMesh(std::move(joints), {
                                                           {Vec3(0, 0.1, -0.5), {{1, 1.0}}},
                                                           {Vec3(0, 0.1, -0.5), {{1, 1.0}}},
                                                           {Vec3(0, 0.1, -1.3), {{2, 1.0}}},
                                                           {Vec3(0, 0.2, 0.5), {{3, 1.0}}},
                                                           {Vec3(0, -0.2, 0.7), {{3, 1.0}}},
                                                           {Vec3(0, 0.1, 1.5), {{4, 1.0}}},
                                                           {Vec3(0, 0.1, 1.6), {{4, 1.0}}},
                                                       });
  const Result<RigDescription> result = DescribeFromSkeleton(mesh);
  ASSERT_TRUE(result.ok()) << result.error();
  const RigDescription& d = result.value();
  ASSERT_EQ(d.parts.size(), 4u);
  EXPECT_EQ(d.parts[0].name, "body");
  EXPECT_EQ(d.parts[0].parent, "");
  EXPECT_EQ(d.parts[1].name, "bone_4");
  EXPECT_EQ(d.parts[1].parent, "body");
  EXPECT_EQ(d.parts[2].name, "tail");
  EXPECT_EQ(d.parts[2].parent, "body");
  EXPECT_EQ(d.parts[3].name, "body_2");
  EXPECT_EQ(d.parts[3].parent, "tail");
  ExpectCurve(d.parts[0], {Vec3(0, 0, 0.2), Vec3(0, 0, 1.2)});
  ExpectCurve(d.parts[1], {Vec3(0, 0, 1.2), Vec3(0, 0, 1.6)});
  ExpectCurve(d.parts[2], {Vec3(0, 0, -0.2), Vec3(0, 0, -1)});
  ExpectCurve(d.parts[3], {Vec3(0, 0, -1), Vec3(0, 0, -1.3)});
  EXPECT_EQ(d.vertex_part, (std::vector<int>{2, 3, 0, 0, 1, 1}));
}

TEST(SkeletonDescription, AChainOfUnskinnedBonesLengthensItsParent) {
  // Bones 1 and 2 carry no skin (weights limited away, as in animation_with_skeleton.fbx): the
  // first bone's part runs on through them to bone 3, where the next part starts.
  std::vector<Joint> joints = {MakeJoint("b0", -1, Vec3(0, 0, 0)),
                               MakeJoint("b1", 0, Vec3(1, 0, 0)), MakeJoint("b2", 1, Vec3(2, 0, 0)),
                               MakeJoint("b3", 2, Vec3(3, 0, 0))};
  const Mesh mesh = MakeSkinnedMesh(std::move(joints), {{Vec3(0.5, 0.1, 0), {{0, 1.0}}},
                                                        {Vec3(0.5, 0.1, 0), {{0, 1.0}}},
                                                        {Vec3(1.5, 0.1, 0), {{0, 0.6}, {1, 0.4}}},
                                                        {Vec3(3.5, 0.1, 0), {{3, 1.0}}}});
  const Result<RigDescription> result = DescribeFromSkeleton(mesh);
  ASSERT_TRUE(result.ok()) << result.error();
  const RigDescription& d = result.value();
  ASSERT_EQ(d.parts.size(), 2u);
  EXPECT_EQ(d.parts[0].name, "b0");
  EXPECT_EQ(d.parts[1].name, "b3");
  EXPECT_EQ(d.parts[1].parent, "b0");
  ExpectCurve(d.parts[0], {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)});
  ExpectCurve(d.parts[1], {Vec3(3, 0, 0), Vec3(3.5, 0, 0)});
}

TEST(SkeletonDescription, RefusesMeshesWithoutAUsableSkeleton) {
  Mesh mesh = BranchingSkeletonMesh();
  Mesh no_joints = mesh;
  no_joints.joints.clear();
  EXPECT_EQ(DescribeFromSkeleton(no_joints).error(), "the mesh has no skeleton");
  Mesh no_skin = mesh;
  no_skin.skin_joints.clear();
  EXPECT_EQ(DescribeFromSkeleton(no_skin).error(), "the mesh's skeleton has no skin weights");
  Mesh late_parent = mesh;
  late_parent.joints[1].parent = 5;
  EXPECT_EQ(DescribeFromSkeleton(late_parent).error(),
            "joint 1 ('spine'): its parent must come before it");
  Mesh unskinned = mesh;
  for (auto& slots : unskinned.skin_joints) slots = {-1, -1, -1, -1};
  EXPECT_EQ(DescribeFromSkeleton(unskinned).error(),
            "the skeleton has no bone with both a length and skinned vertices");
}

// anim_test.x: a closed cylinder along y from -5 to 5 with four bones, of which only joint1 ->
// joint2 are linked in the file; joint3 is a root of its own and joint4 has no skin.
TEST(SkeletonDescription, AnimTestKeepsItsBonesAndRigs) {
  const fs::path path = fs::path(WIRERIG_ASSET_DIR) / "assimp/X/anim_test.x";
  ASSERT_TRUE(fs::exists(path)) << "asset missing (run scripts/setup.sh): " << path;
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  const Mesh& mesh = imported.value().mesh;
  ASSERT_EQ(mesh.joints.size(), 4u);
  const Result<RigDescription> result = DescribeFromSkeleton(mesh);
  ASSERT_TRUE(result.ok()) << result.error();
  const RigDescription& d = result.value();

  ASSERT_EQ(d.parts.size(), 3u);
  EXPECT_EQ(d.parts[0].name, "joint1");
  EXPECT_EQ(d.parts[0].parent, "");
  EXPECT_EQ(d.parts[1].name, "joint2");
  EXPECT_EQ(d.parts[1].parent, "joint1");
  EXPECT_EQ(d.parts[2].name, "joint3");
  EXPECT_EQ(d.parts[2].parent, "joint2");  // the separate root hangs from the nearest part
  auto joint_at = [&](int j) -> Vec3 { return mesh.joints[j].bind_global.block<3, 1>(0, 3); };
  ExpectCurve(d.parts[0], {joint_at(0), joint_at(1)});
  // The leaves reach their skin's far end: joint2 towards joint3, joint3 to the cap at y = 5.
  ASSERT_EQ(d.parts[1].central_curve.size(), 2u);
  EXPECT_NEAR((d.parts[1].central_curve[0] - joint_at(1)).norm(), 0.0, 1e-12);
  EXPECT_GT(d.parts[1].central_curve[1].y(), 1.0);
  EXPECT_LT(d.parts[1].central_curve[1].y(), joint_at(2).y());
  ASSERT_EQ(d.parts[2].central_curve.size(), 2u);
  EXPECT_NEAR((d.parts[2].central_curve[0] - joint_at(2)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(d.parts[2].central_curve[1].y(), 5.0, 0.1);
  ASSERT_EQ(d.vertex_part.size(), mesh.welded_positions.size());
  for (std::size_t i = 0; i < d.parts.size(); ++i)
    EXPECT_GT(std::count(d.vertex_part.begin(), d.vertex_part.end(), int(i)), 100)
        << d.parts[i].name;
  EXPECT_EQ(std::count(d.vertex_part.begin(), d.vertex_part.end(), -1), 0);

  const Result<BuiltRig> built = BuildRig(mesh, d, path.string());
  ASSERT_TRUE(built.ok()) << built.error();
  ASSERT_EQ(built.value().rig.parts.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const RigPart& part = built.value().rig.parts[i];
    EXPECT_EQ(part.parent, int(i) - 1) << part.name;
    EXPECT_EQ(part.profiles.size(), 12u) << part.name;
    EXPECT_EQ(built.value().report.parts[i].profiles.misses, 0u) << part.name;
  }
}

// Testwuson.X: 37 bones under a "Root" node without skin; every bone is a part, the legs and
// the tail keep every segment and the ears and mouth hang from the head ("Neck" here).
TEST(SkeletonDescription, TestwusonHasAPartPerBone) {
  const fs::path path = fs::path(WIRERIG_ASSET_DIR) / "assimp/X/Testwuson.X";
  ASSERT_TRUE(fs::exists(path)) << "asset missing (run scripts/setup.sh): " << path;
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  const Mesh& mesh = imported.value().mesh;
  ASSERT_EQ(mesh.joints.size(), 38u);
  const Result<RigDescription> result = DescribeFromSkeleton(mesh);
  ASSERT_TRUE(result.ok()) << result.error();
  const RigDescription& d = result.value();
  ASSERT_EQ(d.parts.size(), 37u);
  auto parent_of = [&](const std::string& name) {
    for (const PartDescription& part : d.parts)
      if (part.name == name) return part.parent;
    return std::string("(no part '" + name + "')");
  };
  EXPECT_EQ(d.parts[0].name, "Spine_Front01");  // the front half holds more skin
  EXPECT_EQ(parent_of("Spine_Back01"), "Spine_Front01");
  EXPECT_EQ(parent_of("Pelvis"), "Spine_Back03");
  EXPECT_EQ(parent_of("Tail06"), "Tail05");
  EXPECT_EQ(parent_of("HindLeg_L_01"), "Pelvis");
  EXPECT_EQ(parent_of("HindLeg_L_04"), "HindLeg_L_03");
  EXPECT_EQ(parent_of("ForeLeg_R_01"), "Spine_Front03");
  EXPECT_EQ(parent_of("ForeLeg_R_05"), "ForeLeg_R_04");
  EXPECT_EQ(parent_of("Ear_L"), "Neck");
  EXPECT_EQ(parent_of("Mouth"), "Neck");
  const double diagonal = ComputeBounds(mesh).Diagonal();
  for (const PartDescription& part : d.parts) {
    EXPECT_EQ(part.central_curve.size(), 2u) << part.name;
    EXPECT_GT((part.central_curve.back() - part.central_curve.front()).norm(), 0.02 * diagonal)
        << part.name;
    EXPECT_GT(std::count(d.vertex_part.begin(), d.vertex_part.end(), &part - d.parts.data()), 0)
        << part.name;
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
