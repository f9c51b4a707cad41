// The rig asset (.wrig): round trip, and refusals of bad bytes naming the field.
#include "wirerig/runtime/rig_asset.h"

#include <gtest/gtest.h>
#include <algorithm>

#include <cstring>
#include <random>

#include "support/two_segment_limb.h"
#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_model_builder.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

RigAsset LimbAsset() {
  const Mesh mesh = MakeCapsule(0.08, 1.0, 24, 40, 4);
  Result<BuiltRig> rig = BuildRig(mesh, testing::TwoSegmentLimb(), "capsule");
  EXPECT_TRUE(rig.ok()) << rig.error();
  Result<BuiltRigModel> model = BuildRigModel(mesh, rig.value().rig);
  EXPECT_TRUE(model.ok()) << model.error();
  RigAsset asset;
  asset.model = std::move(model).value().model;
  asset.vertex_order = mesh.weld_map;
  return asset;
}

const RigAsset& Limb() {
  static const RigAsset asset = LimbAsset();
  return asset;
}

// Positions with the lower segment bent by 70 degrees and the upper spine loaded.
std::vector<float> Evaluate(const RigAsset& asset) {
  const RigModel& model = asset.model;
  std::vector<PartPose> poses(model.parts.size());
  const PointLoad load{0.7, Vec3(30.0, 0.0, 0.0)};
  poses[0].loads.bending_point_loads = std::span(&load, 1);
  poses[1].rotation = JointRotation(model.parts[1].joint, Vec3(70.0, 0.0, 0.0));
  RigWorkspace workspace = MakeRigWorkspace(model);
  const std::size_t outputs = asset.vertex_order.size();
  std::vector<float> positions(3 * outputs), normals(3 * outputs);
  EvaluateRigJob job;
  job.model = &model;
  job.poses = poses;
  job.workspace = &workspace;
  job.float_positions = positions;
  job.float_normals = normals;
  job.float_vertex_order = asset.vertex_order;
  const Status status = job.Run();
  EXPECT_TRUE(status.ok()) << ToString(status);
  positions.insert(positions.end(), normals.begin(), normals.end());
  return positions;
}

// Rewrites the header's checksum after the payload was edited.
void Reseal(std::vector<std::uint8_t>& bytes) {
  const std::uint32_t crc = Crc32(std::span(bytes).subspan(kRigAssetHeaderSize));
  for (int i = 0; i < 4; ++i) bytes[16 + std::size_t(i)] = std::uint8_t(crc >> (8 * i));
}

std::string Refusal(std::span<const std::uint8_t> bytes) {
  RigAsset out;
  const Status status = ParseRigAsset(bytes, &out);
  EXPECT_FALSE(status.ok());
  EXPECT_TRUE(out.model.parts.empty()) << "a refused parse must leave the output unchanged";
  return ToString(status);
}

TEST(RigAsset, Crc32MatchesTheStandardCheckValue) {
  const char* text = "123456789";  // CRC-32/ISO-HDLC check value: 0xCBF43926
  EXPECT_EQ(Crc32(std::span(reinterpret_cast<const std::uint8_t*>(text), 9)), 0xCBF43926u);
}

TEST(RigAsset, RoundTripEvaluatesBitIdentically) {
  const RigAsset& asset = Limb();
  const std::vector<std::uint8_t> bytes = SerializeRigAsset(asset);
  ASSERT_GT(bytes.size(), kRigAssetHeaderSize);
  EXPECT_EQ(std::memcmp(bytes.data(), "WRIG", 4), 0);
  RigAsset loaded;
  const Status status = ParseRigAsset(bytes, &loaded);
  ASSERT_TRUE(status.ok()) << ToString(status);
  EXPECT_EQ(loaded.vertex_order, asset.vertex_order);
  ASSERT_EQ(loaded.model.parts.size(), asset.model.parts.size());
  EXPECT_EQ(loaded.model.parts[1].name, "lower");
  const std::vector<float> expected = Evaluate(asset), got = Evaluate(loaded);
  ASSERT_EQ(got.size(), expected.size());
  EXPECT_EQ(std::memcmp(got.data(), expected.data(), got.size() * sizeof(float)), 0);
  // Serialising the loaded asset gives the same bytes.
  EXPECT_EQ(SerializeRigAsset(loaded), bytes);
  // A joint's fitted growth survives the trip.
  RigAsset fitted = asset;
  fitted.model.parts[1].joint.growth_scales = {0.375, -1.5, 2.25, 4.0};
  ASSERT_TRUE(ParseRigAsset(SerializeRigAsset(fitted), &loaded).ok());
  EXPECT_EQ(loaded.model.parts[1].joint.growth_scales, fitted.model.parts[1].joint.growth_scales);
}

TEST(RigAsset, RefusesBadHeadersNamingTheField) {
  const std::vector<std::uint8_t> good = SerializeRigAsset(Limb());
  std::vector<std::uint8_t> bytes = good;
  bytes[0] = 'X';
  EXPECT_NE(Refusal(bytes).find("magic"), std::string::npos);
  EXPECT_NE(Refusal(std::span(good).first(10)).find("magic"), std::string::npos);
  bytes = good;
  bytes[4] = std::uint8_t(kRigAssetVersion + 1);
  EXPECT_NE(Refusal(bytes).find("version"), std::string::npos);
  EXPECT_NE(Refusal(std::span(good).first(good.size() - 1)).find("size"), std::string::npos);
  bytes = good;
  bytes.push_back(0);
  EXPECT_NE(Refusal(bytes).find("size"), std::string::npos);
  bytes = good;
  bytes[good.size() / 2] ^= 0x10;
  EXPECT_NE(Refusal(bytes).find("checksum"), std::string::npos);
}

TEST(RigAsset, RefusesModelsThatCannotBeEvaluated) {
  RigAsset asset = Limb();
  asset.model.triangles[3][1] = std::uint32_t(asset.model.vertices.size());
  EXPECT_EQ(Refusal(SerializeRigAsset(asset)), "triangles[3]: name a vertex the model lacks");

  asset = Limb();
  asset.model.parts[1].parent = 1;
  EXPECT_NE(Refusal(SerializeRigAsset(asset)).find("parts[1].parent"), std::string::npos);

  asset = Limb();
  asset.model.parts[1].joint.min_degrees.x() = 10.0;
  asset.model.parts[1].joint.max_degrees.x() = -10.0;
  EXPECT_NE(Refusal(SerializeRigAsset(asset)).find("parts[1].joint"), std::string::npos);

  asset = Limb();
  asset.model.parts[1].joint.growth_scales[kGrowPlusY] = 4.5;
  EXPECT_NE(Refusal(SerializeRigAsset(asset)).find("growth_scales"), std::string::npos);

  asset = Limb();
  std::size_t paired = 0;
  while (asset.model.vertices[paired].cap) ++paired;
  asset.model.vertices[paired].pair.k1 = 100000;
  EXPECT_NE(Refusal(SerializeRigAsset(asset)).find("vertices[" + std::to_string(paired) + "].pair"),
            std::string::npos);

  // The largest profile index: profile + 1 wraps to 0 in 32 bits (found by the fuzzer).
  asset = Limb();
  asset.model.vertices[paired].profile = 0xFFFFFFFFu;
  EXPECT_EQ(Refusal(SerializeRigAsset(asset)),
            "vertices[" + std::to_string(paired) + "].profile: names a profile the part lacks");

  asset = Limb();
  asset.model.parts[0].spine_points[1].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(Refusal(SerializeRigAsset(asset)).find("parts[0].spine_points"), std::string::npos);

  asset = Limb();
  asset.vertex_order.back() = std::uint32_t(asset.model.vertices.size());
  EXPECT_NE(Refusal(SerializeRigAsset(asset)).find("vertex_order"), std::string::npos);

  // Stiffness the wire jobs cannot solve with (a review found such rigs loaded, then failed
  // every evaluation blaming "poses"): zero on a deformable spine, 1e-300 on a profile.
  asset = Limb();
  const auto part =
      std::find_if(asset.model.parts.begin(), asset.model.parts.end(),
                   [](const PartModel& p) { return p.kind == SpineKind::kDeformable; });
  ASSERT_NE(part, asset.model.parts.end());
  const std::size_t deformable = std::size_t(part - asset.model.parts.begin());
  part->spine_stiffness.axial = 0.0;
  EXPECT_EQ(Refusal(SerializeRigAsset(asset)),
            "parts[" + std::to_string(deformable) +
                "].spine_stiffness: must lie in [1e-30, 1e30] for a deformable part");
  asset = Limb();
  asset.model.parts[0].profiles.at(0).stiffness.bending = 1e-300;
  EXPECT_EQ(Refusal(SerializeRigAsset(asset)),
            "parts[0].profiles: stiffness must lie in [1e-30, 1e30]");
}

TEST(RigAsset, RefusesCountsLargerThanTheFile) {
  std::vector<std::uint8_t> bytes = SerializeRigAsset(Limb());
  // The part count is the payload's first u32: claim four billion parts.
  for (int i = 0; i < 4; ++i) bytes[kRigAssetHeaderSize + std::size_t(i)] = 0xFF;
  Reseal(bytes);
  EXPECT_NE(Refusal(bytes).find("payload"), std::string::npos);
}

// A vertex's joint influences are stored as a count and those in use; a count beyond what a
// vertex holds (kJointInfluences) is refused naming the vertex.
TEST(RigAsset, RefusesMoreJointInfluencesThanAVertexHolds) {
  RigAsset asset = Limb();
  const std::size_t last = asset.model.vertices.size() - 1;
  asset.model.vertices[last].joints = {};  // its record ends with its count, 0
  std::vector<std::uint8_t> bytes = SerializeRigAsset(asset);
  RigAsset round;
  ASSERT_TRUE(ParseRigAsset(bytes, &round).ok());
  // After the vertices: the triangles and the vertex order, each a u32 count and its elements.
  const std::size_t tail =
      4 + 12 * asset.model.triangles.size() + 4 + 4 * asset.vertex_order.size();
  std::uint8_t& count = bytes[bytes.size() - tail - 1];
  ASSERT_EQ(count, 0);
  count = std::uint8_t(kJointInfluences + 1);
  Reseal(bytes);
  EXPECT_EQ(Refusal(bytes), "vertices[" + std::to_string(last) +
                                "].joints: holds more joint influences than a vertex can");
}

// Random corruptions that keep a valid checksum (a hostile file): each is refused or parses
// into a model that evaluates without a crash (run under the sanitizers in CI).
TEST(RigAsset, CorruptPayloadsNeverCrash) {
  const std::vector<std::uint8_t> good = SerializeRigAsset(Limb());
  std::mt19937 random(12345);
  std::uniform_int_distribution<std::size_t> where(kRigAssetHeaderSize, good.size() - 1);
  std::uniform_int_distribution<int> value(0, 255), flips(1, 8);
  int parsed = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<std::uint8_t> bytes = good;
    for (int k = flips(random); k > 0; --k) bytes[where(random)] = std::uint8_t(value(random));
    Reseal(bytes);
    RigAsset asset;
    if (!ParseRigAsset(bytes, &asset).ok()) continue;
    ++parsed;
    std::vector<PartPose> poses(asset.model.parts.size());
    RigWorkspace workspace = MakeRigWorkspace(asset.model);
    std::vector<Vec3> positions(asset.model.vertices.size());
    EvaluateRigJob job;
    job.model = &asset.model;
    job.poses = poses;
    job.workspace = &workspace;
    job.positions = positions;
    (void)job.Run();
  }
  EXPECT_GT(parsed, 0) << "some corruptions (a changed real) should still parse";
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
