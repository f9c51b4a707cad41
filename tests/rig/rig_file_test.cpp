// Rig files: save then load is exact; every malformed field is refused with its JSON pointer;
// a failed save leaves no file.
#include "wirerig/rig/rig_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

ProfileCurve Profile(double v, double radius, int points) {
  ProfileCurve p;
  p.v = v;
  p.origin = Vec3(0.1, v, -0.2);
  p.frame.tangent = Vec3(0, 1, 0);
  p.frame.normal = Vec3(1, 0, 0);
  p.frame.binormal = Vec3(0, 0, -1);
  p.closed = true;
  for (int i = 0; i < points; ++i) {
    const double a = 2.0 * 3.141592653589793 * i / points + 1e-3 * v;  // inexact doubles
    p.points.emplace_back(0.1 + radius * std::cos(a), v, -0.2 + radius * std::sin(a));
  }
  return p;
}

Rig SampleRig() {
  Rig rig;
  rig.mesh = "meshes/thing.obj";
  rig.import.up_axis = UpAxis::kZ;
  rig.import.unit_scale = 0.0254;
  rig.mesh_vertices = 5;
  rig.mesh_triangles = 3;
  for (int i = 0; i < 2; ++i) {
    RigPart part;
    part.name = i == 0 ? "torso" : "arm";
    part.parent = i == 0 ? -1 : 0;
    part.attachment = i == 0 ? 0.0 : 0.7312345678901234;
    part.central_curve = {Vec3(0, 0, 0), Vec3(0.1, 1.0 / 3.0, 0), Vec3(0, 1, 0.2)};
    part.profile_count = 3;
    part.points_per_profile = 5;
    for (int k = 1; k <= 3; ++k) {
      part.profiles.push_back(Profile(k / 4.0, 0.1 + 0.01 * k, 5));
      part.spine_points.push_back(Vec3(0.1, k / 4.0, -0.2 + 1e-17 * k));
      part.profile_wires.push_back({Material{0.1e6, 0.45, 1060.0}, StripSection(0.25, 0.005)});
    }
    part.spine_wire = {Material{1.0e6 / 3.0, 0.3, 1000.0}, TubeSection(0.11, 0.005)};
    if (i == 1) {
      part.joint.type = JointType::kHinge;
      part.joint.axis = Vec3(1.0 / 3.0, 0, 1);
      part.joint.min_degrees.x() = -5.25;
      part.joint.max_degrees.x() = 150;
      part.joint.blend_length = 0.0625;
    }
    rig.parts.push_back(part);
  }
  rig.vertex_part = {0, 0, 1, 1, 0};
  return rig;
}

void ExpectEqual(const Rig& a, const Rig& b) {
  EXPECT_EQ(RigToJson(a), RigToJson(b));  // structural, bit-exact doubles
  ASSERT_EQ(a.parts.size(), b.parts.size());
  EXPECT_EQ(a.parts[1].attachment, b.parts[1].attachment);
  EXPECT_EQ(a.parts[0].profiles[2].points[3], b.parts[0].profiles[2].points[3]);
  EXPECT_EQ(a.parts[0].spine_points[1], b.parts[0].spine_points[1]);
  EXPECT_EQ(a.parts[1].spine_wire.section.second_moment,
            b.parts[1].spine_wire.section.second_moment);
  EXPECT_EQ(a.parts[1].spine_wire.section.kind, b.parts[1].spine_wire.section.kind);
  EXPECT_EQ(a.parts[0].profile_wires[0].section.kind, SectionKind::kStrip);
  EXPECT_EQ(b.parts[0].profile_wires[0].section.kind, SectionKind::kStrip);
  EXPECT_EQ(a.vertex_part, b.vertex_part);
  EXPECT_EQ(a.import.unit_scale, b.import.unit_scale);
  EXPECT_EQ(a.import.up_axis, b.import.up_axis);
  EXPECT_EQ(b.parts[1].joint.type, JointType::kHinge);
  EXPECT_EQ(a.parts[1].joint.axis, b.parts[1].joint.axis);
  EXPECT_EQ(a.parts[1].joint.min_degrees, b.parts[1].joint.min_degrees);
  EXPECT_EQ(a.parts[1].joint.max_degrees, b.parts[1].joint.max_degrees);
  EXPECT_EQ(a.parts[1].joint.blend_length, b.parts[1].joint.blend_length);
  EXPECT_FALSE(b.parts[0].joint.blend_length.has_value());
}

TEST(RigFile, SaveThenLoadIsExact) {
  const fs::path path = fs::temp_directory_path() / "wirerig_rig_file_test.rig.json";
  const Rig rig = SampleRig();
  ASSERT_TRUE(SaveRig(rig, path).ok());
  const Result<Rig> loaded = LoadRig(path);
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  ExpectEqual(rig, loaded.value());
  // And once more: load(save(load(save(x)))) == x.
  ASSERT_TRUE(SaveRig(loaded.value(), path).ok());
  ExpectEqual(rig, LoadRig(path).value());
}

void ExpectRefused(const nlohmann::json& document, const std::string& expected) {
  const Result<Rig> rig = RigFromJson(document);
  ASSERT_FALSE(rig.ok());
  EXPECT_NE(rig.error().find(expected), std::string::npos) << rig.error();
}

TEST(RigFile, EveryMalformedFieldIsNamed) {
  const nlohmann::json good = RigToJson(SampleRig());
  ASSERT_TRUE(RigFromJson(good).ok());
  nlohmann::json d = good;
  d["format"] = "something";
  ExpectRefused(d, "/format: must be \"wirerig.rig\"");
  // A scene given as a rig is named by its format, not by its first unknown field (/clips).
  d = {{"format", "wirerig.scene"}, {"version", 1}, {"clips", nlohmann::json::array()}};
  ExpectRefused(d, "/format: must be \"wirerig.rig\"");
  d = good;
  d["version"] = 2;
  ExpectRefused(d, "/version: unsupported version");
  d = good;
  d["mesh"].erase("vertices");
  ExpectRefused(d, "/mesh/vertices: is required");
  d = good;
  d["mesh"]["up_axis"] = "w";
  ExpectRefused(d, "/mesh/up_axis: must be");
  d = good;
  d["parts"][1]["parent"] = "leg";
  ExpectRefused(d, "/parts/1/parent: 'leg' is not an earlier part");
  d = good;
  d["parts"][1]["name"] = "torso";
  ExpectRefused(d, "/parts/1/name: is used twice");
  d = good;
  d["parts"][1]["attachment"] = 1.5;
  ExpectRefused(d, "/parts/1/attachment: must lie in [0, 1]");
  d = good;
  d["parts"][0]["profiles"][1]["points"][2] = {0, "x", 0};
  ExpectRefused(d, "/parts/0/profiles/1/points/2/1: must be a number");
  d = good;
  d["parts"][0]["profiles"][1]["tangent"] = {0, 2, 0};
  ExpectRefused(d, "/parts/0/profiles/1/tangent: must be a unit vector");
  d = good;
  d["parts"][0]["profiles"][0]["wire"]["material"]["E"] = -5;
  ExpectRefused(d, "/parts/0/profiles/0/wire/material/E: must be positive");
  d = good;
  d["parts"][0]["spine_wire"]["section"]["kind"] = "hexagon";
  ExpectRefused(d, "/parts/0/spine_wire/section/kind: must be custom, strip or tube");
  d = good;
  d["parts"][0]["spine_points"].erase(0);
  ExpectRefused(d, "/parts/0/spine_points: needs one point per profile");
  d = good;
  d["vertex_part"][3] = 7;
  ExpectRefused(d, "/vertex_part/3: must be a part index");
  d = good;
  d["vertex_part"].erase(0);
  ExpectRefused(d, "/vertex_part: needs one entry per mesh vertex (5)");
  d = good;
  d["parts"][0]["colour"] = "red";
  ExpectRefused(d, "/parts/0/colour: unknown field (known fields: name, parent, ");
  d = good;
  d["parts"][0]["parnet"] = d["parts"][0]["parent"];
  ExpectRefused(d, "/parts/0/parnet: unknown field; did you mean \"parent\"? (known fields: ");
}

TEST(RigFile, LoadErrorsNameTheFile) {
  const fs::path path = fs::temp_directory_path() / "wirerig_rig_file_bad.rig.json";
  std::ofstream(path) << "{ not json";
  const Result<Rig> rig = LoadRig(path);
  ASSERT_FALSE(rig.ok());
  EXPECT_EQ(rig.error(), path.string() +
                             ": not valid JSON: line 1, column 4: syntax error while parsing "
                             "object key - invalid literal; last read: '{ no'; expected string "
                             "literal");
  EXPECT_EQ(LoadRig("/nonexistent/x.rig.json").error(), "/nonexistent/x.rig.json: no such file");
}

// A directory (reading it through a stream threw std::ios_base::failure) and a device that
// never ends are refused by name.
TEST(RigFile, LoadRefusesWhatIsNotARegularFile) {
  const fs::path dir = fs::temp_directory_path();
  Result<Rig> rig(Error{""});
  ASSERT_NO_THROW(rig = LoadRig(dir));
  ASSERT_FALSE(rig.ok());
  EXPECT_EQ(rig.error(), dir.string() + ": is a directory, not a rig file (JSON)");
  EXPECT_NE(LoadRig("/dev/zero").error().find("/dev/zero: is not a regular file"),
            std::string::npos);
}

TEST(RigFile, FailedSaveLeavesNothingBehind) {
  const fs::path dir = fs::temp_directory_path() / "wirerig_rig_file_readonly";
  fs::remove_all(dir);
  const auto saved = SaveRig(SampleRig(), dir / "missing_folder" / "x.rig.json");
  ASSERT_FALSE(saved.ok());
  EXPECT_NE(saved.error().find("x.rig.json"), std::string::npos) << saved.error();
  EXPECT_FALSE(fs::exists(dir));
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
