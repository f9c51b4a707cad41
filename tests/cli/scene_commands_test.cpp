// `wirerig bake`, `render` and `demo`, run in-process on the octopus sample and on broken
// scenes: the .glb passes the Khronos validator, the PNG shows the model and changes with
// time, and every failure names the file and field, exits 1 and leaves no output file.
#include <gtest/gtest.h>

#include <cfenv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "bake_command.h"
#include "demo_command.h"
#include "render_command.h"
#include "wirerig/viewer/image.h"

#ifndef WIRERIG_SOURCE_DIR
#error "the tests need WIRERIG_SOURCE_DIR (set by CMake)"
#endif
#ifndef WIRERIG_ASSET_DIR
#error "the tests need WIRERIG_ASSET_DIR (set by CMake)"
#endif

namespace wirerig::cli {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

const std::string kOctopus =
    std::string(WIRERIG_SOURCE_DIR) + "/samples/octopus/octopus.scene.json";
const std::string kData = std::string(WIRERIG_SOURCE_DIR) + "/tests/cli/data/";

fs::path Output(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "wirerig_scene_commands_test";
  fs::create_directories(dir);
  fs::remove_all(dir / name);
  return dir / name;
}

// Runs scripts/validate_gltf.mjs; returns its first line of output and sets *code.
std::string Validate(const fs::path& file, int* code) {
  const std::string command = "node '" + std::string(WIRERIG_SOURCE_DIR) +
                              "/scripts/validate_gltf.mjs' '" + file.string() + "' 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return "cannot run node";
  std::string text;
  char buffer[512];
  while (fgets(buffer, sizeof buffer, pipe)) text += buffer;
  *code = pclose(pipe);
  return text;
}

struct CommandRun {
  int code;
  std::string out, err;
};

CommandRun Bake(BakeCommandOptions options) {
  std::ostringstream out, err;
  const int code = RunBakeCommand(options, out, err);
  return {code, out.str(), err.str()};
}

CommandRun Render(RenderCommandOptions options) {
  std::ostringstream out, err;
  const int code = RunRenderCommand(options, out, err);
  return {code, out.str(), err.str()};
}

TEST(BakeCommand, OctopusExportsAValidGlbInBothModes) {
  for (const char* mode : {"morph", "skin"}) {
    SCOPED_TRACE(mode);
    BakeCommandOptions options;
    options.scene = kOctopus;
    options.output = Output(std::string("octopus_") + mode + ".glb").string();
    options.mode = mode;
    options.fps = 10;
    const CommandRun run = Bake(options);
    ASSERT_EQ(run.code, 0) << run.err;
    EXPECT_NE(run.out.find("baked 101 keys"), std::string::npos) << run.out;
    ASSERT_TRUE(fs::exists(options.output));
    EXPECT_GT(fs::file_size(options.output), 100'000u);
    int code = -1;
    const std::string report = Validate(options.output, &code);
    EXPECT_EQ(code, 0) << report;
    EXPECT_NE(report.find(": 0 errors"), std::string::npos) << report;
  }
}

TEST(BakeCommand, FailuresNameTheFileAndFieldAndWriteNothing) {
  struct Case {
    std::string scene, clip, message;
  };
  const std::vector<Case> cases = {
      {kData + "bad_clip_part.scene.json", "",
       "bad_clip_part.scene.json: scene \"bad\": /clips/0: parts[0].part: no part of the rig is "
       "named \"tentacle\""},
      {kData + "bad_track.scene.json", "",
       "bad_track.scene.json: /clips/0/parts/0/tip_force/keys/1/1: must be an array of 3 "
       "numbers"},
      {kData + "missing.scene.json", "", "missing.scene.json: no such file"},
      {kOctopus, "dance", "octopus.scene.json: no clip is named \"dance\" (clips: swim, crawl)"},
      {kOctopus, "swimm",
       "octopus.scene.json: no clip is named \"swimm\"; did you mean \"swim\"? (clips: swim, "
       "crawl)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.scene);
    BakeCommandOptions options;
    options.scene = c.scene;
    options.clip = c.clip;
    options.output = Output("bad.glb").string();
    const CommandRun run = Bake(options);
    EXPECT_EQ(run.code, 1);
    EXPECT_NE(run.err.find(c.message), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(options.output));
  }
  BakeCommandOptions options;
  options.scene = kOctopus;
  options.output = Output("octopus.fbx").string();
  const CommandRun run = Bake(options);
  EXPECT_EQ(run.code, 1);
  EXPECT_FALSE(fs::exists(options.output));
}

// Writes `text` to the file `name` in the test's output folder.
fs::path WriteFile(const std::string& name, const std::string& text) {
  const fs::path path = Output(name);
  std::ofstream(path) << text;
  return path;
}

// A scene of human.zae on `description` with `clip` (JSON) and optional `playback` (JSON).
fs::path HumanScene(const std::string& name, const std::string& clip,
                    const std::string& description, const std::string& playback = "") {
  return WriteFile(name, R"({"format": "wirerig.scene", "version": 1, "name": "t",
    "mesh": {"file": ")" + std::string(WIRERIG_ASSET_DIR) +
                             R"(/assimp/Collada/human.zae"},
    "rig": {"description": ")" +
                             description + R"("}, "default_kind": "rigid",)" +
                             (playback.empty() ? "" : R"("playback": )" + playback + ",") +
                             R"("clips": [)" + clip + "]}");
}

// Issue 12's bad input (motion capture, joint limits, tracking gains): each refused naming the
// scene, the file at fault and its field (a BVH's line), exit 1, no .glb.
TEST(BakeCommand, BadMotionLimitsAndGainsNameTheFileAndFieldAndWriteNothing) {
  const std::string samples = std::string(WIRERIG_SOURCE_DIR) + "/samples";
  const std::string human = samples + "/rigs/human.description.json";
  const std::string bvh = std::string(WIRERIG_ASSET_DIR) + "/assimp/BVH/01_01.bvh";
  // The checked-in mapping with one CMU joint renamed to one the capture does not have.
  std::ifstream mapping_file(samples + "/mocap/human_from_cmu.mapping.json");
  std::string mapping((std::istreambuf_iterator<char>(mapping_file)), {});
  const std::string from = "\"LeftForeArm\"";
  ASSERT_NE(mapping.find(from), std::string::npos);
  mapping.replace(mapping.find(from), from.size(), "\"LeftElbowX\"");
  WriteFile("bad_bone.mapping.json", mapping);
  // A capture whose second frame has one value fewer than its channels.
  WriteFile("short.bvh", R"(HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation
  JOINT Spine
  {
    OFFSET 0 1 0
    CHANNELS 3 Zrotation Yrotation Xrotation
    End Site
    {
      OFFSET 0 1 0
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.0333333
0 0 0 0 0 0 0 0 0
0 0 0 0 0 0 0 0
)");
  // The human's description with spine_1's X limits the wrong way round.
  std::ifstream description_file(human);
  std::string description((std::istreambuf_iterator<char>(description_file)), {});
  const std::string limits = "\"x\": [-20, 35]";
  ASSERT_NE(description.find(limits), std::string::npos);
  description.replace(description.find(limits), limits.size(), "\"x\": [35, -20]");
  const std::string relative_mesh = "../../.cache/assets/assimp/Collada/human.zae";
  ASSERT_NE(description.find(relative_mesh), std::string::npos);
  description.replace(description.find(relative_mesh), relative_mesh.size(),
                      std::string(WIRERIG_ASSET_DIR) + "/assimp/Collada/human.zae");
  const fs::path bad_limit = WriteFile("bad_limit.description.json", description);
  const std::string keyed = R"({"name": "c", "duration": 1.0, "parts": [{"part": "shin_l",
      "joint_angles": {"keys": [[0, [10, 0, 0], "cubic"], [1, [20, 0, 0], "cubic"]]}}]})";
  struct Case {
    fs::path scene;
    std::string message;
  };
  const std::vector<Case> cases = {
      {HumanScene("bad_bone.scene.json",
                  R"({"name": "m", "motion": {"file": ")" + bvh +
                      R"(", "mapping": "bad_bone.mapping.json", "frames": [1, 4]}})",
                  human),
       "bad_bone.mapping.json: /joints/LeftElbowX: " + bvh + " has no joint of this name"},
      {HumanScene("short.scene.json",
                  R"({"name": "m", "motion": {"file": "short.bvh", "mapping": ")" + samples +
                      R"(/mocap/human_from_cmu.mapping.json"}})",
                  human),
       "short.bvh: line 20: frame 1 has 8 values; the hierarchy's 2 joints have 9 channels"},
      {HumanScene("bad_limit.scene.json", keyed, bad_limit.string()),
       "bad_limit.description.json: /parts/1/joint/limits/x: the lower limit 35"},
      {HumanScene("bad_gain.scene.json", keyed, human,
                  R"({"tracking": {"frequency": 1000.0, "damping_ratio": 0.7}})"),
       "bad_gain.scene.json: /playback/tracking/frequency: must be in (0, 100] Hz"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.scene.string());
    BakeCommandOptions options;
    options.scene = c.scene.string();
    options.output = Output("bad_input.glb").string();
    const CommandRun run = Bake(options);
    EXPECT_EQ(run.code, 1);
    EXPECT_NE(run.err.find(c.message), std::string::npos) << run.err;
    EXPECT_NE(run.err.find(c.scene.filename().string()), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(options.output));
  }
}

// A procedural beam scene (a cylinder, one steel part) whose clip pushes the tip with
// `force` N for `duration` s, written to `name`.
fs::path BeamScene(const std::string& name, double duration, double force) {
  const fs::path path = Output(name);
  char text[1400];
  std::snprintf(text, sizeof text, R"({
    "format": "wirerig.scene", "version": 1, "name": "beam",
    "mesh": {"procedural": "cylinder", "parameters": {"radius": 0.1, "height": 1.0}},
    "rig": {"description": {"parts": [{"name": "beam", "central_curve": [[0, 0, 0], [0, 1, 0]],
                                       "profile_count": 8, "points_per_profile": 16}]}},
    "parts": {"beam": {"kind": "deformable", "spine": {"material": "steel"}}},
    "clips": [{"name": "push", "duration": %.17g, "parts": [
      {"part": "beam", "boundary": [{"time": 0, "boundary": "cantilever_free"}],
       "tip_force": {"keys": [{"time": 0, "value": [%.17g, 0, 0]}]}}]}]})",
                duration, force);
  FILE* f = std::fopen(path.c_str(), "w");
  std::fputs(text, f);
  std::fclose(f);
  return path;
}

// A 1e5 s clip threw std::bad_alloc, and a 1,000 s one took 8 GB and 17 s before the .glb was
// refused: both are refused with their numbers before anything is baked.
TEST(BakeCommand, AClipTooLargeIsRefusedWithItsNumbersBeforeBaking) {
  const fs::path scene = BeamScene("long.scene.json", 1e5, 1.0);
  BakeCommandOptions options;
  options.scene = scene.string();
  options.fps = 1000;
  const auto start = std::chrono::steady_clock::now();
  for (const char* name : {"long.glb", "long.gltf"}) {
    options.output = Output(name).string();
    CommandRun run = Bake(options);
    EXPECT_EQ(run.code, 1);
    EXPECT_NE(run.err.find(std::string(name) + ": 100000001 keys (100000 s at 1000 fps) x "),
              std::string::npos)
        << run.err;
    EXPECT_NE(run.err.find("more than a glTF buffer may hold (4.29 GB); bake fewer keys"),
              std::string::npos)
        << run.err;
    EXPECT_FALSE(fs::exists(options.output));
  }
  // Skinned at 10 keys/s, the export (joints only, ~0.9 GB) fits, but the bake would not fit the
  // memory it may take.
  options.mode = "skin";
  options.fps = 10;
  const CommandRun run = Bake(options);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.err.find("the bake would hold 1000001 keys"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(options.output));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
}

// A morph export weighs every target at every key: keys^2 floats. A mesh of a few hundred
// vertices and a 3,000 s clip (90,001 keys, 32 GB of weights) aborted with std::bad_alloc after
// the bake, and a 1,000 s one took 44 s and 8 GB; both are refused before baking. Skinned (no
// morph targets) the same clip fits.
TEST(BakeCommand, AMorphExportWhoseWeightsOutgrowABufferIsRefusedBeforeBaking) {
  const fs::path scene = BeamScene("weights.scene.json", 3000.0, 1.0);
  BakeCommandOptions options;
  options.scene = scene.string();
  options.output = Output("weights.glb").string();
  options.mode = "morph";
  const auto start = std::chrono::steady_clock::now();
  const CommandRun run = Bake(options);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.err.find("weights.glb: 90001 keys (3000 s at 30 fps) x "), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("the export needs at least"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("or --mode skin without --residual"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(options.output));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
}

// A tip deflection of ~1e45 m (beyond float) and one of ~1e33 m (positions finite as floats,
// but the bake's float normals overflowed while render's double ones did not): `bake` refused
// them while `render` drew them and exited 0. Both now fail with the same check's message.
TEST(SceneCommands, BakeAndRenderRefuseGeometryBeyondFloatAlike) {
  for (const double tip : {1e45, 1e33}) {
    SCOPED_TRACE("tip deflection " + std::to_string(tip) + " m");
    // Steel beam, r = 0.1 m, L = 1 m: EI = 2e11 * pi r^4 / 4 = 1.57e7 N m^2; F = 3 EI d / L^3.
    const fs::path scene = BeamScene("overflow.scene.json", 1.0, 3.0 * 1.57e7 * tip);
    fedisableexcept(FE_ALL_EXCEPT);  // the float rounding overflows, by design here
    BakeCommandOptions bake;
    bake.scene = scene.string();
    bake.output = Output("overflow.glb").string();
    const CommandRun baked = Bake(bake);
    const char* kReason = "positions[";
    const char* kWhy = "not finite, or beyond 1e7 m (the deformation overflowed)";
    EXPECT_EQ(baked.code, 1);
    EXPECT_NE(baked.err.find(kReason), std::string::npos) << baked.err;
    EXPECT_NE(baked.err.find(kWhy), std::string::npos) << baked.err;
    EXPECT_FALSE(fs::exists(bake.output));
    RenderCommandOptions render;
    render.scene = scene.string();
    render.size = "64x64";
    render.output = Output("overflow.png").string();
    const CommandRun rendered = Render(render);
    feenableexcept(FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW);
    EXPECT_EQ(rendered.code, 1);
    EXPECT_NE(rendered.err.find(kReason), std::string::npos) << rendered.err;
    EXPECT_NE(rendered.err.find(kWhy), std::string::npos) << rendered.err;
    EXPECT_FALSE(fs::exists(render.output));
  }
}

// Mesa's software rasterizer raises floating-point exceptions inside its own code (context
// creation, shader compilation); the drawing tests turn the test main's traps off. The scene
// evaluation they call is covered with traps on by the anim tests.
class DrawingTest : public ::testing::Test {
 protected:
  void SetUp() override { fedisableexcept(FE_ALL_EXCEPT); }
  void TearDown() override { feenableexcept(FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW); }
};
using RenderCommand = DrawingTest;
using DemoCommand = DrawingTest;

// Mean absolute difference of two images below row `top` (the caption, which names the time,
// sits above it).
double MeanDifference(const Image& a, const Image& b, int top) {
  double sum = 0.0;
  const std::size_t first = std::size_t(top) * std::size_t(a.width) * 4;
  for (std::size_t i = first; i < a.rgba.size(); ++i)
    sum += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
  return sum / double(a.rgba.size() - first);
}

TEST_F(RenderCommand, OctopusPictureShowsTheModelAndMovesWithTime) {
  RenderCommandOptions options;
  options.scene = kOctopus;
  options.size = "320x200";
  options.wires = false;  // the skin itself, not the wires drawn over it
  options.time = 0.0;
  const fs::path first_path = Output("octopus_t0.png");
  options.output = first_path.string();
  CommandRun run = Render(options);
  ASSERT_EQ(run.code, 0) << run.err;
  options.time = 1.3;
  options.output = Output("octopus_t13.png").string();
  run = Render(options);
  ASSERT_EQ(run.code, 0) << run.err;
  const Image first = LoadPng(first_path).value();
  const Image later = LoadPng(options.output).value();
  ASSERT_EQ(first.width, 320);
  ASSERT_EQ(first.height, 200);
  // The skin is orange (red well above blue) in the lower middle of the picture, where the
  // octopus starts the swim that takes it up through the fixed camera's view (measured 505
  // pixels); the corners show the grey-blue sky or the pale ground.
  int skin = 0;
  for (int y = 100; y < 190; ++y)
    for (int x = 110; x < 210; ++x) {
      const auto p = first.At(x, y);
      skin += p[0] > p[2] + 40;
    }
  EXPECT_GT(skin, 350);
  const auto corner = first.At(2, 2);
  EXPECT_LE(std::abs(int(corner[0]) - int(corner[2])), 30);
  EXPECT_GT(MeanDifference(first, later, 30), 1.0);  // measured 4.2
  EXPECT_EQ(MeanDifference(first, first, 30), 0.0);
}

TEST_F(RenderCommand, BadSizeAndSceneFailCleanly) {
  RenderCommandOptions options;
  options.scene = kOctopus;
  options.size = "wide";
  options.output = Output("bad.png").string();
  CommandRun run = Render(options);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.err.find("--size: must be WIDTHxHEIGHT"), std::string::npos) << run.err;
  options.size = "64x64";
  options.scene = kData + "bad_clip_part.scene.json";
  run = Render(options);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.err.find("no part of the rig is named \"tentacle\""), std::string::npos);
  EXPECT_FALSE(fs::exists(options.output));
}

TEST_F(DemoCommand, WritesTheSceneTheGlbAndTheContactSheet) {
  DemoCommandOptions options;
  options.output = Output("demo").string();
  options.samples = std::string(WIRERIG_SOURCE_DIR) + "/samples";
  std::ostringstream out, err;
  ASSERT_EQ(RunDemoCommand(options, out, err), 0) << err.str();
  for (const char* name : {"octopus.scene.json", "octopus.glb", "octopus.png", "octopus_crawl.glb",
                           "octopus_crawl.png", "walk.glb", "walk.png"})
    EXPECT_TRUE(fs::exists(fs::path(options.output) / name)) << name;
  const Image sheet = LoadPng(fs::path(options.output) / "octopus.png").value();
  EXPECT_GT(sheet.width, 1000);  // 3 tiles of 640 across
  int code = -1;
  const std::string report = Validate(fs::path(options.output) / "octopus.glb", &code);
  EXPECT_EQ(code, 0) << report;
  const std::string crawl = Validate(fs::path(options.output) / "octopus_crawl.glb", &code);
  EXPECT_EQ(code, 0) << crawl;
  const std::string walk = Validate(fs::path(options.output) / "walk.glb", &code);
  EXPECT_EQ(code, 0) << walk;
}

// A samples folder without the walk: refused before the octopus is baked (it baked ~124 MB).
TEST_F(DemoCommand, ChecksItsInputsBeforeBaking) {
  DemoCommandOptions options;
  options.output = Output("demo_missing").string();
  options.samples = Output("no_samples").string();
  std::ostringstream out, err;
  EXPECT_EQ(RunDemoCommand(options, out, err), 1);
  EXPECT_EQ(err.str(), "wirerig demo: " + options.samples +
                           "/walk/walk.scene.json: no such sample scene (--samples names the "
                           "samples folder)\n");
  EXPECT_FALSE(fs::exists(fs::path(options.output) / "octopus.glb"));
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::cli
