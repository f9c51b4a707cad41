// The real `wirerig` executable: one exit-code policy for every command (0 success, 1 bad
// input or failure, 2 usage error, stated in --help), and inputs that used to abort
// (SIGABRT from an escaping std::ios_base::failure) or hang (a FIFO, /dev/zero) end with a
// message naming the file and exit code 1.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include "wirerig_process.h"

#ifndef WIRERIG_ASSET_DIR
#error "the tests need WIRERIG_ASSET_DIR (set by CMake)"
#endif
#ifndef WIRERIG_SOURCE_DIR
#error "the tests need WIRERIG_SOURCE_DIR (set by CMake)"
#endif

namespace wirerig::cli {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;
using testing::ProcessResult;
using testing::RunWirerig;

const std::string kOctopus =
    std::string(WIRERIG_SOURCE_DIR) + "/samples/octopus/octopus.scene.json";

fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "wirerig_main_test";
  fs::create_directories(dir);
  fs::remove_all(dir / name);
  return dir / name;
}

// Exited (no signal, no timeout) with `code`, standard error holding `text`.
void ExpectExit(const ProcessResult& run, int code, const std::string& text) {
  EXPECT_FALSE(run.timed_out);
  EXPECT_EQ(run.signal, 0) << run.err;
  EXPECT_EQ(run.exit_code, code) << run.err;
  EXPECT_NE(run.err.find(text), std::string::npos) << run.err;
}

// A steel beam (r = 0.1 m, L = 1 m: EI = 1.57e7 N m^2, a cantilever) pushed at its tip by
// `force` N along +x for its 1 s clip, written as `name`.
std::string Contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

fs::path PushedBeamScene(const std::string& name, double force) {
  const fs::path scene = Scratch(name);
  char text[1000];
  std::snprintf(text, sizeof text, R"({"format": "wirerig.scene", "version": 1, "name": "pushed",
    "mesh": {"procedural": "cylinder", "parameters": {"radius": 0.1, "height": 1.0}},
    "rig": {"description": {"parts": [{"name": "beam", "central_curve": [[0, 0, 0], [0, 1, 0]],
                                       "profile_count": 8, "points_per_profile": 16}]}},
    "parts": {"beam": {"kind": "deformable", "spine": {"material": "steel"}}},
    "clips": [{"name": "push", "duration": 1, "parts": [
      {"part": "beam", "boundary": [{"time": 0, "boundary": "cantilever_free"}],
       "tip_force": {"keys": [{"time": 0, "value": [%.17g, 0, 0]}]}}]}]})",
                force);
  std::ofstream(scene) << text;
  return scene;
}

TEST(WirerigExitCodes, HelpStatesThePolicyAndExitsZero) {
  const ProcessResult run = RunWirerig({"--help"});
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("Exit codes (every command): 0 success; 1 bad input or failure"),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("2 usage error"), std::string::npos) << run.out;
  EXPECT_EQ(RunWirerig({"--version"}).exit_code, 0);
}

TEST(WirerigExitCodes, UsageErrorsExitTwo) {
  ExpectExit(RunWirerig({}), 2, "subcommand");  // was 106
  ExpectExit(RunWirerig({"frobnicate"}), 2, "wirerig: unknown command \"frobnicate\" (commands: ");
  ExpectExit(RunWirerig({"bakee", kOctopus}), 2,
             "unknown command \"bakee\"; did you mean \"bake\"?");
  ExpectExit(RunWirerig({"wire"}), 2, "input");  // missing argument
  ExpectExit(RunWirerig({"bake", kOctopus, "-o", "x.glb", "--fps", "abc"}), 2, "--fps");  // 105
  ExpectExit(RunWirerig({"wire", "x.json", "--format", "xml"}), 2, "--format");
  // Options that do not apply to the chosen mode are refused, not ignored.
  ExpectExit(RunWirerig({"bake", kOctopus, "-o", "x.glb", "--mode", "morph", "--max-joints", "8"}),
             2, "--max-joints: applies to --mode skin only");
  ExpectExit(
      RunWirerig({"bake", kOctopus, "-o", "x.glb", "--mode", "morph", "--key-tolerance", "1e-4"}),
      2, "--key-tolerance: applies to --mode skin only");
  ExpectExit(RunWirerig({"bake", kOctopus, "-o", "x.glb", "--key-tolerance", "-1"}), 2,
             "--key-tolerance");
  ExpectExit(RunWirerig({"bake", kOctopus, "-o", "x.glb", "--mode", "morph", "--compress"}), 2,
             "--compress: applies to --mode skin only");
  ExpectExit(RunWirerig({"bake", kOctopus, "-o", "x.glb", "--keep-vertex-order"}), 2,
             "--keep-vertex-order: applies to --compress only");
  ExpectExit(RunWirerig({"bake", kOctopus, "-o", "x.glb", "--mode", "morph", "--influences", "8"}),
             2, "--influences: applies to --mode skin only");
  ExpectExit(RunWirerig({"bake", kOctopus, "-o", "x.glb", "--influences", "6"}), 2, "--influences");
  ExpectExit(RunWirerig({"bake", kOctopus, "-o", "x.glb", "--mode", "morph", "--no-flesh-joints"}),
             2, "--no-flesh-joints: applies to --mode skin only");
  ExpectExit(RunWirerig({"bake", kOctopus, "-o", "x.glb", "--mode", "skin", "--quantize",
                         "--max-correctives", "0"}),
             2, "--quantize: quantizes morph targets: this skin has none");
  ExpectExit(RunWirerig({"bake", kOctopus, "-o", "x.glb", "--mode", "skin", "--residual",
                         "--max-correctives", "4"}),
             2, "--residual: carries a target per key: it replaces the corrective shapes");
  // rig and build likewise refuse what does not apply.
  const std::string mesh = std::string(WIRERIG_ASSET_DIR) + "/cow.off";
  ExpectExit(RunWirerig({"rig", mesh, "-o", "x.rig.json", "--joint-poses"}), 2,
             "--joint-poses: lists the poses of --joint-report: give both");
  for (const char* option : {"--ignore-skeleton", "--wrap-alpha"}) {
    std::vector<std::string> args = {"rig", mesh, "-d", "d.json", "-o", "x.rig.json", option};
    if (std::string(option) == "--wrap-alpha") args.push_back("0.05");
    ExpectExit(RunWirerig(args), 2, std::string(option) + ": applies without a description only");
  }
  ExpectExit(RunWirerig({"build", kOctopus, "-o", "x.wrig", "--fps", "60"}), 2,
             "--fps: samples the clips: applies with --clips only");
#ifdef WIRERIG_HAS_VIEWER  // render and view exist only with the viewer
  // An image size out of range is a usage error like any other bad value (it exited 1).
  for (const char* size : {"0x0", "wide", "16x9000"}) {
    ExpectExit(
        RunWirerig({"render", kOctopus, "-o", "x.png", "--size", size}), 2,
        std::string("--size: must be WIDTHxHEIGHT, each in [16, 8192], e.g. 1280x720 (got \"") +
            size + "\")");
    ExpectExit(RunWirerig({"view", kOctopus, "--size", size}), 2, "--size");
  }
  // A contact sheet beyond what a PNG is written with (4 x 16 tiles of 4096: 16394 x 65570
  // pixels) is refused before anything is drawn; it crashed in the PNG encoder after 81 s.
  const fs::path sheet = Scratch("huge_sheet.png");
  ExpectExit(RunWirerig({"render", kOctopus, "-o", sheet.string(), "--size", "4096x4096", "--sheet",
                         "64"}),
             2, "--size 4096x4096 with --sheet 64: the sheet would be 16394x65570 pixels");
  EXPECT_FALSE(fs::exists(sheet));
#endif
}

#ifdef WIRERIG_HAS_VIEWER
// A folder given as the scene to view printed three lines (the reason, "the application failed
// to initialise", "the viewer stopped with an error"): now the reason, once.
TEST(WirerigExitCodes, ViewSaysWhatFailedOnce) {
  const fs::path folder = Scratch("a_folder");
  fs::create_directories(folder);
  const ProcessResult run = RunWirerig({"view", folder.string(), "--no-window", "--frames", "1"});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.err,
            "wirerig view: " + folder.string() + ": is a directory, not a scene file (JSON)\n");
}
#endif

// Output that cannot be written is a failure: `wire` into a full device exited 0.
TEST(WirerigExitCodes, AnUnwritableStandardOutputExitsOne) {
  const std::string problem =
      std::string(WIRERIG_SOURCE_DIR) + "/samples/worked_wire/steel_cantilever.json";
  testing::WirerigProcess process({"wire", problem}, "/dev/full");
  const ProcessResult run = process.Wait();
  ExpectExit(run, 1, "wirerig: cannot write standard output");
}

#ifdef WIRERIG_HAS_VIEWER
// Headless, nothing can close the view; frames beyond the bound were a bad-input exit.
TEST(WirerigExitCodes, ViewNeedsAFrameCountHeadlessAndStatesItsBound) {
  ExpectExit(RunWirerig({"view", kOctopus, "--no-window"}), 2,
             "--no-window: needs --frames N (N >= 1)");
  ExpectExit(RunWirerig({"view", kOctopus, "--no-window", "--frames", "1000000001"}), 2,
             "--frames: must be in [0, 1e+09]");
}

// A scene whose evaluation overflows: render and bake refused it, view drew its rest pose and
// exited 0. It now fails the same way, naming the scene, the time and the vertex.
TEST(WirerigExitCodes, ViewFailsOnGeometryRenderAndBakeRefuse) {
  const fs::path scene = PushedBeamScene("overflow.scene.json", 1e40);
  const ProcessResult run = RunWirerig({"view", scene.string(), "--no-window", "--frames", "2"});
  ExpectExit(run, 1, "wirerig view: " + scene.string() + ": t = ");
  EXPECT_NE(run.err.find("not finite, or beyond 1e7 m (the deformation overflowed)"),
            std::string::npos)
      << run.err;
}

// A long clip with wire dynamics: its checkpoint cache was sized for the whole clip (a 1e5 s
// octopus took over 12 GB and 2 minutes before drawing t = 0). The cache is bounded now.
TEST(WirerigExitCodes, ALongDynamicClipDrawsItsFirstFrameAtOnce) {
  std::ifstream in(std::string(WIRERIG_SOURCE_DIR) + "/samples/octopus/octopus.scene.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "\"duration\": 10.0";
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, from.size(), "\"duration\": 100000.0");
  const fs::path scene = Scratch("long_octopus.scene.json");
  std::ofstream(scene) << text;
  const auto start = std::chrono::steady_clock::now();
  const ProcessResult run =
      RunWirerig({"render", scene.string(), "-o", Scratch("long.png").string(), "--size", "64x64"});
  ExpectExit(run, 0, "");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
}

// A broken catalog says where it breaks, like every other JSON file.
TEST(WirerigExitCodes, ABrokenCatalogGivesLineAndColumn) {
  const fs::path dir = Scratch("catalog_dir");
  fs::create_directories(dir);
  std::ofstream(dir / "catalog.json") << "[\n  {\"name\": }\n]\n";
  ExpectExit(RunWirerig({"samples", "--dir", dir.string()}), 1,
             (dir / "catalog.json").string() + ": not valid JSON: line 2, column ");
}

// Where the gallery page goes is checked before any picture is drawn (it drew for 34 s).
TEST(WirerigOutputs, GalleryChecksItsPageFirst) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path page = Scratch("absent_folder") / "g.md";
  ExpectExit(
      RunWirerig({"gallery", "--page", page.string()}), 1,
      page.string() + ": the folder " + Scratch("absent_folder").string() + " does not exist");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}
#endif

// A deflection far beyond the part's length: bake and render warned, build --clips and view
// did not.
TEST(WirerigExitCodes, BuildAndViewWarnOfDeflectionsBeyondLinearTheory) {
  // F = 3 EI 10 m / L^3 bends the tip by ~10 m, ten times the length.
  const fs::path scene = PushedBeamScene("bent.scene.json", 4.7e8);
  const ProcessResult built =
      RunWirerig({"build", scene.string(), "-o", Scratch("bent.wrig").string(), "--clips"});
  EXPECT_EQ(built.exit_code, 0) << built.err;
  EXPECT_NE(built.out.find("warning: clip \"push\": part \"beam\": its deflection reached"),
            std::string::npos)
      << built.out;
#ifdef WIRERIG_HAS_VIEWER
  const ProcessResult viewed = RunWirerig({"view", scene.string(), "--no-window", "--frames", "2"});
  EXPECT_EQ(viewed.exit_code, 0) << viewed.err;
  EXPECT_NE(viewed.err.find("wirerig view: warning: " + scene.string() +
                            ": part \"beam\": its deflection reached"),
            std::string::npos)
      << viewed.err;
#endif
}

// The pushed beam's scene with two clips named `first` and `second`, written as `name`.
fs::path TwoClipBeamScene(const std::string& name, const std::string& first,
                          const std::string& second) {
  const std::string clip = R"(", "duration": 1, "parts": [
      {"part": "beam", "boundary": [{"time": 0, "boundary": "cantilever_free"}],
       "tip_force": {"keys": [{"time": 0, "value": [1000, 0, 0]}]}}]})";
  const fs::path scene = Scratch(name);
  std::ofstream(scene) << R"({"format": "wirerig.scene", "version": 1, "name": "pushed",
    "mesh": {"procedural": "cylinder", "parameters": {"radius": 0.1, "height": 1.0}},
    "rig": {"description": {"parts": [{"name": "beam", "central_curve": [[0, 0, 0], [0, 1, 0]],
                                       "profile_count": 8, "points_per_profile": 16}]}},
    "parts": {"beam": {"kind": "deformable", "spine": {"material": "steel"}}},
    "clips": [{"name": ")" + first +
                              clip + R"(, {"name": ")" + second + clip + "]}";
  return scene;
}

// Quantized residual targets: the printed error is the stored file's bound, not the floats'.
TEST(WirerigBake, QuantizedResidualsReportTheStoredBound) {
  const fs::path scene = PushedBeamScene("residual.scene.json", 1e5);
  const ProcessResult run = RunWirerig(
      {"bake", scene.string(), "-o", Scratch("residual.glb").string(), "--residual", "--quantize"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("as floats; 31 of them stored as shorts, within 2.6e-05 m of the bake"),
            std::string::npos)
      << run.out;
}

// build --clips writes the rig and every clip or nothing: two clips whose names make the same
// file name, or a clip whose file name is too long, are refused before anything is written.
TEST(WirerigExitCodes, BuildClipsWritesAllOrNothing) {
  const fs::path folder = Scratch("build_clips");  // a folder of its own, emptied
  fs::create_directories(folder);
  const fs::path output = folder / "clips.wrig";
  auto written = [&] {
    std::size_t count = 0;
    for (const auto& entry : fs::directory_iterator(folder))
      count += entry.path().filename().string().rfind("clips.", 0) == 0;
    return count;
  };
  const fs::path same = TwoClipBeamScene("same_file.scene.json", "a/b", "a_b");
  ExpectExit(RunWirerig({"build", same.string(), "-o", output.string(), "--clips"}), 1,
             "clips \"a/b\" and \"a_b\" would both be written to " +
                 (folder / "clips.a_b.wclip").string());
  EXPECT_EQ(written(), 0u);
  const fs::path long_name =
      TwoClipBeamScene("long_name.scene.json", "short", std::string(300, 'x'));
  ExpectExit(RunWirerig({"build", long_name.string(), "-o", output.string(), "--clips"}), 1,
             "the file name is too long");
  EXPECT_EQ(written(), 0u);
  // Distinct names: the rig and both clips.
  const fs::path distinct = TwoClipBeamScene("distinct.scene.json", "a", "b");
  const ProcessResult run =
      RunWirerig({"build", distinct.string(), "-o", output.string(), "--clips"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::exists(folder / "clips.a.wclip"));
  EXPECT_TRUE(fs::exists(folder / "clips.b.wclip"));
  EXPECT_EQ(written(), 3u);
}

TEST(WirerigExitCodes, BadInputExitsOne) {
  ExpectExit(RunWirerig({"wire", Scratch("missing.json").string()}), 1,
             "missing.json: no such file");
}

// One byte of Assimp's binary X test cube changed: Assimp 5.2.5 segfaults reading it. The
// import runs in a child process, so wirerig itself reports it and exits 1.
TEST(WirerigImporterCrash, RigAndBakeExitOneNamingTheFile) {
  const fs::path source = fs::path(WIRERIG_ASSET_DIR) / "assimp/X/test_cube_binary.x";
  if (!fs::exists(source)) FAIL() << "asset missing: " << source << " (run scripts/setup.sh)";
  std::ifstream in(source, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 2816u);
  bytes[2609] = static_cast<char>(0xb2);
  const fs::path mesh = Scratch("corrupted.x");
  std::ofstream(mesh, std::ios::binary) << bytes;
  const std::string crashed = mesh.string() + ": the importer crashed on this file";
  ExpectExit(RunWirerig({"rig", mesh.string(), "-o", Scratch("c.rig.json").string()}), 1, crashed);

  const fs::path scene = Scratch("corrupted.scene.json");
  std::ofstream(scene) << R"({"format": "wirerig.scene", "version": 1, "name": "corrupted",
    "mesh": {"file": "corrupted.x"}, "rig": {"from": "automatic"}})";
  ExpectExit(RunWirerig({"bake", scene.string(), "-o", Scratch("c.glb").string()}), 1, crashed);
  EXPECT_FALSE(fs::exists(Scratch("c.glb")));
}

// Outputs are checked before any work: the scene named here does not even exist, and the
// output is what is refused.
TEST(WirerigOutputs, RefusedBeforeAnyWork) {
  const std::string missing_scene = Scratch("missing.scene.json").string();
  ExpectExit(RunWirerig({"bake", missing_scene, "-o", "m.fbx"}), 1,
             "m.fbx: the output must be a .glb or .gltf file (not .fbx)");
#ifdef WIRERIG_HAS_VIEWER  // render exists only with the viewer
  ExpectExit(RunWirerig({"render", missing_scene, "-o", "x.jpg"}), 1,
             "x.jpg: the output must be a .png file (not .jpg)");
#endif
  ExpectExit(RunWirerig({"build", missing_scene, "-o", "x.glb"}), 1,
             "x.glb: the output must be a .wrig file (not .glb)");
  ExpectExit(RunWirerig({"rig", "mesh.obj", "-o", "x.rig"}), 1,
             "x.rig: the output must be a .json file (not .rig)");
  const fs::path deep = Scratch("absent") / "deeper" / "x.glb";
  ExpectExit(RunWirerig({"bake", missing_scene, "-o", deep.string()}), 1,
             deep.string() + ": the folder " + Scratch("absent").string() + " does not exist");
}

// No command writes over a file it reads: a bake over the scene's mesh (a .gltf), a rig over
// its description, a wire solution over its problem. The inputs stay as they were.
TEST(WirerigOutputs, NoCommandWritesOverItsInput) {
  const fs::path folder = Scratch("own_inputs");
  fs::create_directories(folder);
  const fs::path box = fs::path(WIRERIG_ASSET_DIR) / "assimp/glTF2/BoxTextured-glTF";
  if (!fs::exists(box)) FAIL() << "asset missing: " << box << " (run scripts/setup.sh)";
  for (const char* name : {"BoxTextured.gltf", "BoxTextured0.bin", "CesiumLogoFlat.png"})
    fs::copy_file(box / name, folder / name, fs::copy_options::overwrite_existing);
  const fs::path mesh = folder / "BoxTextured.gltf";
  const auto size = fs::file_size(mesh);
  const fs::path scene = folder / "box.scene.json";
  std::ofstream(scene) << R"({"format": "wirerig.scene", "version": 1, "name": "box",
    "mesh": {"file": "BoxTextured.gltf"}, "rig": {"from": "automatic"}})";
  ExpectExit(RunWirerig({"bake", scene.string(), "-o", mesh.string()}), 1,
             mesh.string() + ": is the scene's mesh (" + mesh.string() +
                 "), which this command reads; write elsewhere");
  EXPECT_EQ(fs::file_size(mesh), size);
  const fs::path description = folder / "box.description.json";
  std::ofstream(description) << R"({"format": "wirerig.rig_description", "version": 1,
    "parts": [{"name": "box", "central_curve": [[0, -0.4, 0], [0, 0.4, 0]]}]})";
  ExpectExit(
      RunWirerig({"rig", mesh.string(), "-d", description.string(), "-o", description.string()}), 1,
      "is the rig description");
  EXPECT_NE(Contents(description).find("wirerig.rig_description"), std::string::npos);
  const fs::path problem = Scratch("own_problem.json");
  std::ofstream(problem) << "{}";
  ExpectExit(RunWirerig({"wire", problem.string(), "-o", problem.string()}), 1,
             "is the wire problem");
  EXPECT_EQ(Contents(problem), "{}");
}

// A mesh whose file name and object name are Latin-1 (not UTF-8) rigs and bakes: the JSON and
// glTF writers take UTF-8 only, and such names aborted `wirerig rig` after all its work.
TEST(WirerigOutputs, NamesThatAreNotUtf8AreWrittenWithReplacementCharacters) {
  const fs::path folder = Scratch("latin1");
  fs::create_directories(folder);
  const fs::path mesh = folder / std::string("caf\xe9.obj");
  {
    std::ofstream obj(mesh, std::ios::binary);
    obj << "o caf\xe9_part\n";
    constexpr int kSides = 12, kRings = 8;
    for (int r = 0; r <= kRings; ++r)
      for (int k = 0; k < kSides; ++k) {
        const double a = 2.0 * 3.14159265358979 * k / kSides;
        obj << "v " << 0.1 * std::cos(a) << " " << double(r) / kRings << " " << 0.1 * std::sin(a)
            << "\n";
      }
    obj << "v 0 0 0\nv 0 1 0\n";
    const int bottom = (kRings + 1) * kSides + 1, top = bottom + 1;  // 1-based
    for (int r = 0; r < kRings; ++r)
      for (int k = 0; k < kSides; ++k) {
        const int a = r * kSides + k + 1, b = r * kSides + (k + 1) % kSides + 1;
        obj << "f " << a << " " << a + kSides << " " << b << "\nf " << b << " " << a + kSides << " "
            << b + kSides << "\n";
      }
    for (int k = 0; k < kSides; ++k)
      obj << "f " << bottom << " " << k + 1 << " " << (k + 1) % kSides + 1 << "\nf " << top << " "
          << kRings * kSides + (k + 1) % kSides + 1 << " " << kRings * kSides + k + 1 << "\n";
  }
  const fs::path rig = folder / "latin1.rig.json";
  const ProcessResult rigged = RunWirerig({"rig", mesh.string(), "-o", rig.string()});
  ASSERT_EQ(rigged.exit_code, 0) << rigged.err;
  EXPECT_NE(Contents(rig).find("caf\xef\xbf\xbd.obj"), std::string::npos);
  const fs::path scene = folder / "latin1.scene.json";
  std::ofstream(scene)
      << "{\"format\": \"wirerig.scene\", \"version\": 1, \"name\": \"latin1\", "
         "\"mesh\": {\"file\": \"caf\xc3\xa9.obj\"}, \"rig\": {\"file\": "
         "\"latin1.rig.json\"}, \"clips\": [{\"name\": \"still\", \"duration\": 1, "
         "\"parts\": []}]}";
  // The scene (UTF-8, as JSON is) cannot name the Latin-1 file: the mesh is read by the rig's
  // own path, so copy it under its UTF-8 name.
  fs::copy_file(mesh, folder / "caf\xc3\xa9.obj", fs::copy_options::overwrite_existing);
  const fs::path glb = folder / "latin1.glb";
  const ProcessResult baked = RunWirerig({"bake", scene.string(), "-o", glb.string()});
  EXPECT_EQ(baked.exit_code, 0) << baked.err;
}

// A rigid body whose keyed force is far too large for its mass: the bake stops naming the part,
// not the integrator's step ("dt").
TEST(WirerigBake, AnOverloadedRigidBodyIsNamedByPart) {
  const fs::path scene = Scratch("overloaded.scene.json");
  std::ofstream(scene) << R"({"format": "wirerig.scene", "version": 1, "name": "arm",
    "mesh": {"procedural": "cylinder", "parameters": {"radius": 0.1, "height": 1.0}},
    "rig": {"description": {"parts": [{"name": "base", "central_curve": [[0, 0, 0], [0, 0.5, 0]],
                                       "profile_count": 8, "points_per_profile": 16}]}},
    "default_kind": "rigid",
    "clips": [{"name": "push", "duration": 1, "parts": [
      {"part": "base", "rigid_forces": [{"at": [0, 0, 0], "force": [1e6, 0, 0]}]}]}]})";
  ExpectExit(RunWirerig({"bake", scene.string(), "-o", Scratch("overloaded.glb").string()}), 1,
             "part \"base\" (rigid body): its step cannot go on");
  EXPECT_FALSE(fs::exists(Scratch("overloaded.glb")));
}

// Out-of-range option values state their bound readably (usage errors: exit 2).
TEST(WirerigOutputs, OptionBoundsAreReadable) {
  ExpectExit(RunWirerig({"bake", kOctopus, "-o", "x.glb", "--fps", "0"}), 2,
             "--fps: must be in [1, 1000] (got 0)");
  ExpectExit(RunWirerig({"rig", "m.obj", "-o", "x.json", "--skin-thickness", "-1"}), 2,
             "--skin-thickness: must be > 0 (got -1)");
  // The importer's range, as a usage error (it was exit 1, from the importer, after "> 0").
  ExpectExit(RunWirerig({"rig", "m.obj", "-o", "x.json", "--unit-scale", "1e300"}), 2,
             "--unit-scale: must be in [1e-12, 1e+12] (got 1e300)");
  // A thickness whose sections overflow: refused, naming it, and nothing written (it wrote a
  // rig whose I was null, which no scene could load).
  const fs::path thick = Scratch("thick.rig.json");
  ExpectExit(RunWirerig({"rig", std::string(WIRERIG_ASSET_DIR) + "/cow.off", "-o", thick.string(),
                         "--skin-thickness", "1e300"}),
             1, "skin thickness 1e+300 m: its wire sections: h: gives with b a section");
  EXPECT_FALSE(fs::exists(thick));
#ifdef WIRERIG_HAS_VIEWER
  ExpectExit(RunWirerig({"render", kOctopus, "-o", "x.png", "-t", "-2"}), 2,
             "--time: must be >= 0 (got -2)");
#endif
}

TEST(WirerigDirectoryInput, WireExitsOneNamingTheDirectory) {
  const fs::path dir = Scratch("dir.json");
  fs::create_directories(dir);
  ExpectExit(RunWirerig({"wire", dir.string()}), 1, dir.string() + ": is a directory");
}

TEST(WirerigDirectoryInput, RigDescriptionExitsOneNamingTheDirectory) {
  const fs::path dir = Scratch("description");
  fs::create_directories(dir);
  ExpectExit(RunWirerig({"rig", "mesh.obj", "--description", dir.string(), "-o",
                         Scratch("out.rig.json").string()}),
             1, dir.string() + ": is a directory");
}

TEST(WirerigDirectoryInput, SceneRigFileExitsOneNamingTheDirectory) {
  const fs::path scene = Scratch("dot_rig.scene.json");
  FILE* f = std::fopen(scene.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs(R"({"format": "wirerig.scene", "version": 1, "name": "dot",
    "mesh": {"procedural": "cylinder", "parameters": {"radius": 0.1, "height": 1.0}},
    "rig": {"file": "."}, "clips": []})",
             f);
  std::fclose(f);
  ExpectExit(RunWirerig({"bake", scene.string(), "-o", Scratch("dot.glb").string()}), 1,
             "is a directory, not a rig file");
}

TEST(WirerigSpecialFiles, WireOnAFifoExitsOneWithoutBlocking) {
  const fs::path fifo = Scratch("pipe.json");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  ExpectExit(RunWirerig({"wire", fifo.string()}, std::chrono::seconds(20)), 1,
             "pipe.json: is not a regular file");
  fs::remove(fifo);
}

TEST(WirerigSpecialFiles, BakeAndRenderOfDevZeroExitOne) {
  ExpectExit(RunWirerig({"bake", "/dev/zero", "-o", Scratch("zero.glb").string()},
                        std::chrono::seconds(20)),
             1, "/dev/zero: is not a regular file");
  EXPECT_FALSE(fs::exists(Scratch("zero.glb")));
#ifdef WIRERIG_HAS_VIEWER
  ExpectExit(RunWirerig({"render", "/dev/zero", "-o", Scratch("zero.png").string()},
                        std::chrono::seconds(20)),
             1, "/dev/zero: is not a regular file");
#endif
}

#ifdef WIRERIG_HAS_VIEWER
// `view` imports a scene's mesh in a child process as `bake` and `render` do: a file that
// crashes Assimp (one byte of its binary X test cube changed) ends the child, and the viewer
// exits 1 naming the file.
TEST(WirerigImportIsolation, ViewOfAMeshThatCrashesAssimpExitsOne) {
  const fs::path source = fs::path(WIRERIG_ASSET_DIR) / "assimp/X/test_cube_binary.x";
  std::ifstream in(source, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 2816u) << source;
  bytes[2609] = static_cast<char>(0xb2);
  const fs::path mesh = Scratch("corrupted.x");
  std::ofstream(mesh, std::ios::binary) << bytes;
  const fs::path scene = Scratch("corrupted.scene.json");
  std::ofstream(scene) << R"({"format": "wirerig.scene", "version": 1, "name": "corrupted",
    "mesh": {"file": ")"
                       << mesh.string() << R"("}, "rig": {"from": "automatic"}, "clips": []})";
  ExpectExit(RunWirerig({"view", scene.string(), "--no-window", "--frames", "1"},
                        std::chrono::seconds(120)),
             1, mesh.string() + ": the importer crashed on this file (");
}
#endif

// The import child's limits are options of every command that imports.
TEST(WirerigImportIsolation, LimitsAreOptions) {
  const std::string cow = std::string(WIRERIG_ASSET_DIR) + "/cow.off";
  const fs::path rig = Scratch("cow.rig.json");
  // Out of memory in the child: a bad_alloc ("out of memory"), or under a sanitizer, whose
  // allocator aborts instead, a crash; either way exit 1 naming the file.
  const ProcessResult run = RunWirerig({"rig", cow, "-o", rig.string(), "--import-memory", "1"});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_EQ(run.signal, 0) << run.err;
  EXPECT_TRUE(run.err.find("cow.off: cannot import: out of memory (limit 1 MiB") !=
                  std::string::npos ||
              run.err.find("cow.off: the importer crashed on this file") != std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(rig));
  ExpectExit(RunWirerig({"bake", kOctopus, "-o", "x.glb", "--import-seconds", "0"}), 2,
             "--import-seconds: must be in [0.001, 1e+06] (got 0)");
  ExpectExit(RunWirerig({"build", kOctopus, "-o", "x.wrig", "--import-memory", "-1"}), 2,
             "--import-memory");
}

// Entries of `dir` whose name holds ".tmp".
int TemporaryEntries(const fs::path& dir) {
  int n = 0;
  std::error_code error;
  for (fs::directory_iterator it(dir, error), end; !error && it != end; it.increment(error))
    n += it->path().filename().string().find(".tmp") != std::string::npos;
  return n;
}

// A bake killed while writing left OUT.glb.tmpPID beside the target: SIGTERM now removes it
// and still ends the process by SIGTERM.
TEST(WirerigSignals, ABakeKilledWhileWritingLeavesNoTemporaryFile) {
  const fs::path dir = Scratch("killed");
  fs::create_directories(dir);
  const fs::path out = dir / "candle.glb";
  // The candle computes little and, as morph targets, writes much (86 MB at 480 fps), so the
  // write is a wide window even under sanitizers.
  const std::string candle = std::string(WIRERIG_SOURCE_DIR) + "/samples/candle/candle.scene.json";
  testing::WirerigProcess bake(
      {"bake", candle, "-o", out.string(), "--fps", "480", "--mode", "morph"});
  // Waits for the temporary file to appear, then kills the bake.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (TemporaryEntries(dir) == 0 && std::chrono::steady_clock::now() < deadline &&
         ::kill(bake.pid(), 0) == 0 && !fs::exists(out))
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  ASSERT_EQ(TemporaryEntries(dir), 1) << "the bake never wrote its temporary file";
  bake.Signal(SIGTERM);
  const ProcessResult run = bake.Wait();
  EXPECT_EQ(run.signal, SIGTERM) << run.err;
  EXPECT_EQ(TemporaryEntries(dir), 0);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::cli
