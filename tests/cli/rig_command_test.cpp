// `wirerig rig`, run in-process: a real mesh with its description gives a rig file that loads
// back; bad meshes and descriptions end in a message naming the file, exit 1, and no file.
#include "rig_command.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "wirerig/rig/rig_file.h"

namespace wirerig::cli {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

struct CommandRun {
  int exit_code;
  std::string out, err;
};

CommandRun RunRig(const RigCommandOptions& options) {
  std::ostringstream out, err;
  const int code = RunRigCommand(options, out, err);
  return {code, out.str(), err.str()};
}

fs::path Output(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "wirerig_rig_command_test";
  fs::create_directories(dir);
  fs::remove(dir / name);
  return dir / name;
}

TEST(RigCommand, HumanWithItsDescriptionWritesARigThatLoads) {
  RigCommandOptions options;
  options.mesh = std::string(WIRERIG_ASSET_DIR) + "/assimp/Collada/human.zae";
  options.description = std::string(WIRERIG_SAMPLES_DIR) + "/rigs/human.description.json";
  options.output = Output("human.rig.json").string();
  const CommandRun run = RunRig(options);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("14444 vertices (welded from 15593), 28796 triangles"), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("rig: 20 parts from"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("quality: 100.0% of the vertices bound (14444 of 14444), 0 of 128 "
                         "profiles cross"),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("verdict: usable: "), std::string::npos) << run.out;
  const Result<Rig> rig = LoadRig(options.output);
  ASSERT_TRUE(rig.ok()) << rig.error();
  EXPECT_EQ(rig.value().parts.size(), 20u);  // with the two skinless clavicles
  EXPECT_EQ(rig.value().mesh_vertices, 14444u);
}

TEST(RigCommand, SkeletonAssetNeedsNoHandInput) {
  RigCommandOptions options;
  options.mesh = std::string(WIRERIG_ASSET_DIR) + "/assimp/X/anim_test.x";
  options.output = Output("anim_test.rig.json").string();
  const CommandRun run = RunRig(options);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("from the skeleton (4 joints)"), std::string::npos) << run.out;
  EXPECT_TRUE(LoadRig(options.output).ok());
}

// --joint-poses lists exactly the wire rig's poses that miss a target, each with its measures.
TEST(RigCommand, JointPosesListOnlyThePosesThatMissATarget) {
  RigCommandOptions options;
  options.mesh = std::string(WIRERIG_ASSET_DIR) + "/assimp/X/anim_test.x";
  options.output = Output("anim_test_poses.rig.json").string();
  options.joint_report = true;
  options.joint_poses = true;
  const CommandRun run = RunRig(options);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::size_t list = run.out.find("poses where the wire rig misses a target");
  ASSERT_NE(list, std::string::npos) << run.out;
  ASSERT_NE(run.out.find("all joints"), std::string::npos) << run.out;
  std::istringstream lines(run.out.substr(list));
  std::string line;
  std::getline(lines, line);  // the heading
  int listed = 0;
  while (std::getline(lines, line) && line.rfind("  ", 0) == 0) {
    std::istringstream fields(line);
    std::string joint, pose;
    std::size_t folds = 0;
    double stretch = 0, volume = 0, perimeter = 0;
    ASSERT_TRUE(fields >> joint >> pose >> folds >> stretch >> volume >> perimeter) << line;
    // Printed rounded: a miss may print at the bound itself.
    EXPECT_TRUE(folds > 0 || stretch >= 1.995 || std::abs(volume - 1.0) >= 0.0295 ||
                perimeter <= 0.9005)
        << line;
    ++listed;
  }
  EXPECT_GT(listed, 0) << run.out;  // this tube's end joint misses the volume target
}

void ExpectFailure(const RigCommandOptions& options, const std::string& expected) {
  const CommandRun run = RunRig(options);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(options.output));
}

TEST(RigCommandErrors, HugeClaimedMeshIsRefusedQuickly) {
  RigCommandOptions options;
  options.mesh = std::string(WIRERIG_ASSET_DIR) + "/assimp/invalid/OutOfMemory.off";
  options.output = Output("oom.rig.json").string();
  ExpectFailure(options, "OutOfMemory.off: claims 353535235358 vertices");
}

TEST(RigCommand, OpenMeshRigsFromItsWrapAndSaysSo) {
  RigCommandOptions options;
  options.mesh = std::string(WIRERIG_ASSET_DIR) + "/assimp/STL/sphereWithHole.stl";
  options.output = Output("hole.rig.json").string();
  const CommandRun run = RunRig(options);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("from the curve skeleton of an alpha wrap"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("holes closed"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("the mesh is not closed"), std::string::npos) << run.out;
  EXPECT_TRUE(LoadRig(options.output).ok());
}

TEST(RigCommand, OneBoneSkeletonGivesWayToTheSurfacesOwn) {
  RigCommandOptions options;
  options.mesh = std::string(WIRERIG_ASSET_DIR) + "/assimp/SMD/WusonSMD.smd";
  options.output = Output("wuson_smd.rig.json").string();
  const CommandRun run = RunRig(options);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("(the file's skeleton makes a single part)"), std::string::npos)
      << run.out;
  const Result<Rig> rig = LoadRig(options.output);
  ASSERT_TRUE(rig.ok()) << rig.error();
  EXPECT_GE(rig.value().parts.size(), 5u);  // torso, head, legs: not one rigid part
  options.mesh = std::string(WIRERIG_ASSET_DIR) + "/assimp/SMD/triangle.smd";
  options.output = Output("triangle_smd.rig.json").string();
  ExpectFailure(options,
                "triangle.smd: the skeleton makes a single part, and it has fewer than 4 "
                "vertices");
}

TEST(RigCommandErrors, StrictRefusesARigWithWarningsAndWritesNothing) {
  RigCommandOptions options;
  options.mesh = std::string(WIRERIG_ASSET_DIR) + "/cow.off";
  options.output = Output("strict_cow.rig.json").string();
  options.strict = true;
  const CommandRun run = RunRig(options);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("verdict: usable: "), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("cow.off: --strict: "), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("warnings (listed above); nothing written"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(options.output));
}

TEST(RigCommandErrors, FlatSheetWithoutDescriptionSaysWhy) {
  const fs::path sheet = Output("sheet.obj");
  std::ofstream(sheet) << "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0.5 0 0.5\n"
                          "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n";
  RigCommandOptions options;
  options.mesh = sheet.string();
  options.output = Output("sheet.rig.json").string();
  ExpectFailure(options,
                "sheet.obj: the mesh is not closed: 4 boundary edges (holes or open "
                "borders); it is flat (a sheet, thickness under 2% of its size): no limbs "
                "to rig");
}

TEST(RigCommandErrors, BrokenDescriptionNamesFileAndField) {
  const fs::path description = Output("broken.description.json");
  std::ofstream(description) << R"({"parts": [{"name": "a", "central_curve": [[0,0,0],[0,1,0]]},
                                           {"name": "b", "parent": "c",
                                            "central_curve": [[0,0,0],[1,0,0]]}]})";
  RigCommandOptions options;
  options.mesh = std::string(WIRERIG_ASSET_DIR) + "/cow.off";
  options.description = description.string();
  options.output = Output("broken.rig.json").string();
  ExpectFailure(
      options, description.string() +
                   ": /parts/1/parent: 'c' is not an earlier part; did you mean \"a\"? (parts: a)");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::cli
