// Skinless bones (a clavicle: a joint and a rigid bone, no skin; rig_description.h) on a
// procedural limb: a capsule as "upper", a 10 cm skinless "bone" and "lower". Turning the bone
// moves the lower segment rigidly by exactly the bone's rotation about its start and leaves the
// upper segment's skin away from the joint where it was, the skin between whole; descriptions
// of bad skinless parts are refused naming the field; the rig file and the .wrig keep the bone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/evaluate_rig.h"
#include "support/two_segment_limb.h"
#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_description.h"
#include "wirerig/rig/rig_file.h"
#include "wirerig/rig/rig_model_builder.h"
#include "wirerig/rig/skin_quality.h"
#include "wirerig/runtime/rig_asset.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

struct BoneLimb {
  Mesh mesh;
  Rig rig;
  RigModel model;
};

const BoneLimb& Limb() {
  static const BoneLimb limb = [] {
    BoneLimb out;
    out.mesh = MakeCapsule(0.08, 1.0, 48, 80, 8);
    Result<BuiltRig> rig = BuildRig(out.mesh, testing::SkinlessBoneLimb(), "capsule");
    EXPECT_TRUE(rig.ok()) << rig.error();
    out.rig = rig.value().rig;
    RigModelOptions options;
    options.spine_kind = SpineKind::kRigid;
    Result<BuiltRigModel> model = BuildRigModel(out.mesh, out.rig, options);
    EXPECT_TRUE(model.ok()) << model.error();
    out.model = std::move(model).value().model;
    return out;
  }();
  return limb;
}

std::vector<Vec3> Evaluate(const RigModel& model, std::span<const PartPose> poses) {
  return testing::EvaluatePose(model, poses);
}

TEST(SkinlessBone, BuildsARigidBoneWithAJointAndNoSkin) {
  const BoneLimb& limb = Limb();
  ASSERT_EQ(limb.model.parts.size(), 3u);
  const PartModel& bone = limb.model.parts[1];
  EXPECT_TRUE(IsSkinless(bone));
  EXPECT_EQ(bone.kind, SpineKind::kRigid);
  EXPECT_NEAR(bone.spine_length, 0.1, 1e-9);
  EXPECT_GT(bone.mass.mass, 0.0);  // a rod, for the articulated dynamics
  EXPECT_GT(bone.joint.blend_length, 0.0);
  EXPECT_EQ(SkinParent(limb.model, 2), 0);
  EXPECT_NEAR(limb.model.parts[2].attachment, 1.0, 1e-9);  // from the bone's end
  for (const VertexAttachment& a : limb.model.vertices) EXPECT_NE(a.part, 1u);
  for (int v : limb.rig.vertex_part) EXPECT_NE(v, 1);
  EXPECT_TRUE(ValidateRigModel(limb.model).ok());
}

TEST(SkinlessBone, TurningItMovesTheChildRigidlyAndLeavesTheParentsFarSkin) {
  const BoneLimb& limb = Limb();
  const std::span<const Vec3> rest = limb.mesh.welded_positions;
  std::vector<PartPose> poses(limb.model.parts.size());
  const std::vector<Vec3> unposed = Evaluate(limb.model, poses);
  for (std::size_t v = 0; v < rest.size(); ++v) ASSERT_LT((unposed[v] - rest[v]).norm(), 1e-9);

  const Vec3 degrees(25.0, 10.0, 0.0);
  poses[1].rotation = JointRotation(limb.model.parts[1].joint, degrees);
  const Mat3 r = poses[1].rotation.toRotationMatrix();
  const Vec3 start(0, 0.55, 0);
  const std::vector<Vec3> posed = Evaluate(limb.model, poses);
  // The bone moves the upper segment's skin within 2 bone lengths, along the surface, of the
  // lower segment's skin (the bone has none: its stretch of the capsule goes to both sides).
  double lower_top = 0.0;
  for (std::size_t v = 0; v < rest.size(); ++v)
    if (limb.model.vertices[v].part == 2) lower_top = std::max(lower_top, rest[v].y());
  EXPECT_GT(lower_top, 0.44);
  EXPECT_LT(lower_top, 0.56);
  const double reach = lower_top + 2.0 * 0.1;
  std::size_t rigid = 0, still = 0, between_moved = 0;
  for (std::size_t v = 0; v < rest.size(); ++v) {
    const Vec3& p = rest[v];
    if (p.y() < 0.15) {  // beyond the lower joint's skin spread: the child alone
      EXPECT_LT((posed[v] - (start + r * (p - start))).norm(), 1e-9) << v;
      ++rigid;
    } else if (p.y() > reach + 0.01) {  // beyond the bone's spread over the parent
      EXPECT_LT((posed[v] - p).norm(), 1e-12) << v;
      ++still;
    } else if (p.y() > 0.6 && (posed[v] - p).norm() > 1e-4) {
      ++between_moved;  // the parent's skin near the joint follows the bone part of the way
    }
  }
  EXPECT_GT(rigid, 100u);
  EXPECT_GT(still, 100u);
  EXPECT_GT(between_moved, 50u);
  const SkinQuality quality =
      MeasureSkin(MakeSkinQualityReference(rest, limb.model.triangles), posed);
  EXPECT_EQ(quality.folded_edges, 0u);
  EXPECT_LT(quality.worst_stretch, 2.0);
}

TEST(SkinlessBone, RigFileAndRigAssetKeepIt) {
  const BoneLimb& limb = Limb();
  const nlohmann::json text = RigToJson(limb.rig);
  EXPECT_EQ(text["parts"][1]["skin"], false);
  EXPECT_FALSE(text["parts"][1].contains("profiles"));
  const Result<Rig> read = RigFromJson(text);
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_FALSE(read.value().parts[1].skin);
  EXPECT_TRUE(read.value().parts[1].profiles.empty());
  EXPECT_EQ(RigToJson(read.value()), text);

  nlohmann::json with_profiles = text;
  with_profiles["parts"][1]["profile_count"] = 3;
  const Result<Rig> refused = RigFromJson(with_profiles);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().find("/parts/1/profile_count"), std::string::npos) << refused.error();
  nlohmann::json long_bone = text;
  long_bone["parts"][1]["spine_points"].push_back({0.0, 0.4, 0.0});
  const Result<Rig> refused_bone = RigFromJson(long_bone);
  ASSERT_FALSE(refused_bone.ok());
  EXPECT_NE(refused_bone.error().find("/parts/1/spine_points"), std::string::npos);

  RigAsset asset;
  asset.model = limb.model;
  asset.vertex_order = limb.mesh.weld_map;
  RigAsset loaded;
  ASSERT_TRUE(ParseRigAsset(SerializeRigAsset(asset), &loaded).ok());
  ASSERT_TRUE(IsSkinless(loaded.model.parts[1]));
  std::vector<PartPose> poses(asset.model.parts.size());
  poses[1].rotation = JointRotation(asset.model.parts[1].joint, Vec3(20.0, 0.0, 5.0));
  poses[2].rotation = JointRotation(asset.model.parts[2].joint, Vec3(40.0, 0.0, 0.0));
  EXPECT_EQ(Evaluate(asset.model, poses), Evaluate(loaded.model, poses));

  // A model whose skinless part is a leaf, or deformable, is refused naming it.
  RigAsset leaf = asset;
  leaf.model.parts[2].parent = 0;
  EXPECT_NE(ToString(ParseRigAsset(SerializeRigAsset(leaf), &loaded)).find("parts[1].profiles"),
            std::string::npos);
}

nlohmann::json BoneDescription() {
  return nlohmann::json::parse(R"({
    "parts": [
      {"name": "chest", "central_curve": [[0, 0, 0], [0, 1, 0]]},
      {"name": "clavicle", "parent": "chest", "skin": false,
       "central_curve": [[0, 0.9, 0], [0.2, 0.85, 0]]},
      {"name": "arm", "parent": "clavicle", "central_curve": [[0.2, 0.85, 0], [0.6, 0.5, 0]]}
    ]})");
}

void ExpectRefused(const nlohmann::json& document, const std::string& expected) {
  const Result<RigDescription> d = ParseRigDescription(document);
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().find(expected), std::string::npos) << d.error();
}

TEST(SkinlessBone, DescriptionsOfBadSkinlessPartsAreRefusedNamingTheField) {
  const Result<RigDescription> good = ParseRigDescription(BoneDescription());
  ASSERT_TRUE(good.ok()) << good.error();
  EXPECT_FALSE(good.value().parts[1].skin);
  EXPECT_EQ(good.value().parts[1].profile_count, 0);
  EXPECT_TRUE(good.value().parts[2].skin);

  nlohmann::json d = BoneDescription();
  d["parts"][1]["profile_count"] = 4;
  ExpectRefused(d, "/parts/1/profile_count: a skinless part");
  d = BoneDescription();
  d["parts"][1]["mesh_parts"] = {"collar"};
  ExpectRefused(d, "/parts/1/mesh_parts: a skinless part");
  d = BoneDescription();
  d["parts"][1]["central_curve"].push_back({0.3, 0.8, 0});
  ExpectRefused(d, "/parts/1/central_curve: a skinless part's bone is 2 points");
  d = BoneDescription();
  d["parts"].erase(2);  // a skinless leaf
  ExpectRefused(d, "/parts/1/skin: a skinless part needs a child");
  d = BoneDescription();
  d["parts"][0]["skin"] = false;
  d["parts"][0]["central_curve"] = {{0, 0, 0}, {0, 1, 0}};
  ExpectRefused(d, "/parts/0/skin: the root part must have skin");
  d = BoneDescription();
  d["parts"][1]["skin"] = "no";
  ExpectRefused(d, "/parts/1/skin");

  RigDescription weighted = good.value();
  weighted.vertex_part = {0, 1, 2};
  EXPECT_NE(ValidateRigDescription(weighted).find("/vertex_part: gives vertices to skinless part "
                                                  "'clavicle'"),
            std::string::npos);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
