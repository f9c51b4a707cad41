// Rig descriptions: parsing, validation rules with JSON pointers, and the checked-in ones.
#include "wirerig/rig/rig_description.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include <nlohmann/json.hpp>

#ifndef WIRERIG_SAMPLES_DIR
#error "the tests need WIRERIG_SAMPLES_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

nlohmann::json Good() {
  return nlohmann::json::parse(R"({
    "format": "wirerig.rig_description", "version": 1, "up_axis": "z", "material": "rubber",
    "defaults": {"profile_count": 6, "points_per_profile": 16},
    "parts": [
      {"name": "body", "central_curve": [[0, 0, 0], [0, 1, 0]]},
      {"name": "arm", "parent": "body", "central_curve": [[0, 0.8, 0], [0.5, 0.8, 0]],
       "profile_count": 4, "mesh_parts": ["arm_mesh"]}
    ]})");
}

// `rig --description DIR` aborted: reading a directory through a stream threw.
TEST(RigDescription, LoadRefusesADirectoryByName) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  Result<RigDescription> d(Error{""});
  ASSERT_NO_THROW(d = LoadRigDescription(dir));
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.error(), dir.string() + ": is a directory, not a rig description (JSON)");
}

TEST(RigDescription, ParsesFieldsAndDefaults) {
  const Result<RigDescription> d = ParseRigDescription(Good());
  ASSERT_TRUE(d.ok()) << d.error();
  ASSERT_EQ(d.value().parts.size(), 2u);
  EXPECT_EQ(d.value().import.up_axis, UpAxis::kZ);
  EXPECT_EQ(d.value().material.youngs_modulus, FindMaterialPreset("rubber")->youngs_modulus);
  EXPECT_EQ(d.value().parts[0].profile_count, 6);
  EXPECT_EQ(d.value().parts[0].points_per_profile, 16);
  EXPECT_EQ(d.value().parts[1].profile_count, 4);
  EXPECT_EQ(d.value().parts[1].parent, "body");
  EXPECT_EQ(d.value().parts[1].mesh_parts, std::vector<std::string>{"arm_mesh"});
  EXPECT_FALSE(d.value().clean_assignment);  // a written description keeps its assignment
  nlohmann::json merging = Good();
  merging["clean_assignment"] = true;
  const Result<RigDescription> m = ParseRigDescription(merging);
  ASSERT_TRUE(m.ok()) << m.error();
  EXPECT_TRUE(m.value().clean_assignment);
}

void ExpectRefused(const nlohmann::json& document, const std::string& expected) {
  const Result<RigDescription> d = ParseRigDescription(document);
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().find(expected), std::string::npos) << d.error();
}

// 20,000 parts ran for minutes: more than kMaxRigParts are refused as they are read.
TEST(RigDescription, RefusesMorePartsThanARigMayHave) {
  nlohmann::json d = Good();
  const nlohmann::json arm = d["parts"][1];
  while (d["parts"].size() <= kMaxRigParts) d["parts"].push_back(arm);
  ExpectRefused(d, "/parts: at most 1024 parts");
}

// Descriptions made in code (a skeleton's bones, an automatic rig) meet the same bounds as
// files: the part count, and the profile points of all parts together (16 parts of 4096
// profiles of 1024 points asked for 6 GB of JSON and 7 x 10^7 rays).
TEST(RigDescription, ValidationBoundsPartsAndProfilePointsOfDescriptionsMadeInCode) {
  Result<RigDescription> parsed = ParseRigDescription(Good());
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  RigDescription many = parsed.value();
  const PartDescription arm = many.parts[1];
  for (std::size_t i = many.parts.size(); i <= kMaxRigParts; ++i) {
    many.parts.push_back(arm);
    many.parts.back().name = "arm_" + std::to_string(i);
  }
  EXPECT_NE(ValidateRigDescription(many).find("/parts: at most 1024 parts"), std::string::npos)
      << ValidateRigDescription(many);
  RigDescription dense = parsed.value();
  for (int i = 0; i < 16; ++i) {
    dense.parts.push_back(arm);
    dense.parts.back().name = "dense_" + std::to_string(i);
    dense.parts.back().profile_count = 4096;
    dense.parts.back().points_per_profile = 1024;
  }
  EXPECT_NE(ValidateRigDescription(dense).find("profile points in all"), std::string::npos)
      << ValidateRigDescription(dense);
  dense.parts.resize(parsed.value().parts.size() + 1);  // one part at its largest: allowed
  EXPECT_EQ(ValidateRigDescription(dense), "");
}

TEST(RigDescription, EachBrokenRuleIsNamed) {
  nlohmann::json d = Good();
  d["parts"][1]["parent"] = "leg";
  ExpectRefused(d, "/parts/1/parent: 'leg' is not an earlier part (parts: body)");
  d["parts"][1]["parent"] = "bdy";  // a misspelling gets the nearest earlier part
  ExpectRefused(d, "/parts/1/parent: 'bdy' is not an earlier part; did you mean \"body\"?");
  d = Good();
  d["parts"][1]["name"] = "body";
  ExpectRefused(d, "/parts/1/name: 'body' is used twice");
  d = Good();
  d["parts"][0]["central_curve"] = {{0, 0, 0}};
  ExpectRefused(d, "/parts/0/central_curve: needs at least 2 points");
  d = Good();
  d["parts"][0]["central_curve"] = {{0, 0, 0}, {0, 0, 0}};
  ExpectRefused(d, "/parts/0/central_curve/1: repeats the previous point");
  d = Good();
  d["parts"][0]["points_per_profile"] = 2;
  ExpectRefused(d, "/parts/0/points_per_profile: must lie in [3, 1024]");
  d = Good();
  d["parts"][0]["profile_count"] = 1;
  ExpectRefused(d, "/parts/0/profile_count: must lie in [2, 4096]");
  // A bad default is named where it is written, even where every part sets its own (0 passed;
  // -1 points was blamed on /parts/0, which did not write it).
  d = Good();
  d["defaults"]["profile_count"] = 0;
  for (auto& part : d["parts"]) part["profile_count"] = 6;
  ExpectRefused(d, "/defaults/profile_count: must lie in [2, 4096]");
  d = Good();
  d["defaults"]["points_per_profile"] = -1;
  ExpectRefused(d, "/defaults/points_per_profile: must lie in [3, 1024]");
  d = Good();
  d["parts"][0]["parent"] = "arm";
  ExpectRefused(d, "/parts/0/parent: the first part is the root");
  d = Good();
  d["parts"][1].erase("parent");
  ExpectRefused(d, "/parts/1/parent: only the first part may be a root");
  d = Good();
  d["up_axis"] = "up";
  ExpectRefused(d, "/up_axis: must be \"x\", \"y\" or \"z\"");
  d = Good();
  d["unit_scale"] = 0;
  ExpectRefused(d, "/unit_scale: must be positive");
  d = Good();
  d["parts"] = nlohmann::json::array();
  ExpectRefused(d, "/parts: needs at least one part");
  d = Good();
  d["parts"][0]["central_curve"][1] = {0, 1};
  ExpectRefused(d, "/parts/0/central_curve/1: must be an array of 3 numbers");
  d = Good();
  d["material"] = {{"E", 1e6}, {"nu", 0.7}};
  ExpectRefused(d, "/material/nu: must lie in (-1, 0.5)");
  d = Good();
  d["clean_assignment"] = "yes";
  ExpectRefused(d, "/clean_assignment");
}

TEST(RigDescription, CheckedInDescriptionsLoad) {
  const Result<RigDescription> human =
      LoadRigDescription(std::string(WIRERIG_SAMPLES_DIR) + "/rigs/human.description.json");
  ASSERT_TRUE(human.ok()) << human.error();
  EXPECT_GE(human.value().parts.size(), 6u);
  EXPECT_EQ(human.value().mesh.filename(), "human.zae");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(RigDescription, JointsParseWithTypeAxisLimitsAndBlend) {
  nlohmann::json d = Good();
  d["parts"][1]["joint"] = nlohmann::json::parse(
      R"({"type": "hinge", "axis": [0, 0, 2], "limits": {"x": [-5, 150]}, "blend": 0.04})");
  const Result<RigDescription> parsed = ParseRigDescription(d);
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  const JointDescription& joint = parsed.value().parts[1].joint;
  EXPECT_EQ(joint.type, JointType::kHinge);
  EXPECT_EQ(*joint.axis, Vec3(0, 0, 2));
  EXPECT_EQ(joint.min_degrees, Vec3(-5, -180, -180));
  EXPECT_EQ(joint.max_degrees, Vec3(150, 180, 180));
  EXPECT_EQ(*joint.blend_length, 0.04);
  EXPECT_EQ(parsed.value().parts[0].joint.type, JointType::kBall);       // the default
  EXPECT_FALSE(parsed.value().parts[0].joint.blend_length.has_value());  // automatic
}

TEST(RigDescription, BrokenJointsAndCyclesAreNamed) {
  nlohmann::json d = Good();
  d["parts"][1]["joint"] = {{"limits", {{"y", {30, -30}}}}};
  ExpectRefused(d, "/parts/1/joint/limits/y: the lower limit 30 is above the upper limit -30");
  // Another kind of file given as a description is named by its format, not its fields.
  d = {{"format", "wirerig.scene"}, {"version", 1}, {"camera", {{"yaw", 0}}}};
  ExpectRefused(d, "/format: must be \"wirerig.rig_description\"");
  d = Good();
  d["parts"][1]["joint"] = {{"type", "hinge"}, {"axis", {0, 0, 0}}};
  ExpectRefused(d, "/parts/1/joint/axis: must be finite and of non-zero length");
  d = Good();
  d["parts"][1]["joint"] = {{"type", "hinge"}};
  ExpectRefused(d, "/parts/1/joint/axis: a hinge needs its axis");
  d = Good();
  d["parts"][1]["joint"] = {{"type", "saddle"}};
  ExpectRefused(d, "/parts/1/joint/type: must be \"ball\", \"hinge\" or \"fixed\"");
  d = Good();
  d["parts"][1]["joint"] = {{"blend", -0.1}};
  ExpectRefused(d, "/parts/1/joint/blend: must be finite and >= 0 (m)");
  d = Good();
  d["parts"][1]["joint"] = {{"limits", {{"x", {10}}}}};
  ExpectRefused(d, "/parts/1/joint/limits/x: must be [min, max] in degrees");
  // A chain that loops: body -> arm -> hand -> arm.
  d = Good();
  d["parts"].push_back(
      {{"name", "hand"}, {"parent", "arm"}, {"central_curve", {{0.5, 0.8, 0}, {0.7, 0.8, 0}}}});
  d["parts"][1]["parent"] = "hand";
  ExpectRefused(d, "/parts/1/parent: the chain has a cycle: arm -> hand -> arm");
}

TEST(RigDescription, TheHumanIsABoneChainWithClaviclesAndHingedElbowsAndKnees) {
  const Result<RigDescription> human =
      LoadRigDescription(std::string(WIRERIG_SAMPLES_DIR) + "/rigs/human.description.json");
  ASSERT_TRUE(human.ok()) << human.error();
  std::map<std::string, const PartDescription*> parts;
  for (const PartDescription& p : human.value().parts) parts[p.name] = &p;
  ASSERT_EQ(parts.size(), 20u);
  for (const char* hinge : {"forearm_l", "forearm_r", "shin_l", "shin_r"}) {
    ASSERT_TRUE(parts.contains(hinge)) << hinge;
    EXPECT_EQ(parts[hinge]->joint.type, JointType::kHinge) << hinge;
  }
  EXPECT_EQ(parts["hand_l"]->parent, "forearm_l");
  EXPECT_EQ(parts["forearm_l"]->parent, "upper_arm_l");
  EXPECT_EQ(parts["upper_arm_l"]->parent, "clavicle_l");
  EXPECT_EQ(parts["upper_arm_r"]->parent, "clavicle_r");
  for (const char* clavicle : {"clavicle_l", "clavicle_r"}) {
    ASSERT_TRUE(parts.contains(clavicle)) << clavicle;
    EXPECT_FALSE(parts[clavicle]->skin) << clavicle;
    EXPECT_EQ(parts[clavicle]->parent, "chest") << clavicle;
  }
  EXPECT_EQ(parts["foot_r"]->parent, "shin_r");
  EXPECT_EQ(parts["shin_r"]->parent, "thigh_r");
  EXPECT_EQ(parts["thigh_r"]->parent, "pelvis");
  EXPECT_EQ(parts["head"]->parent, "neck");
  EXPECT_EQ(parts["neck"]->parent, "chest");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
