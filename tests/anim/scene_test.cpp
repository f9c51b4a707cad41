// Scene files: every field's error names its JSON pointer; save then load gives the same
// document; BuildScene makes procedural and inline-described scenes ready to play, and names
// what is wrong when it cannot.
#include "wirerig/anim/scene.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "wirerig/procedural/shapes.h"

#ifndef WIRERIG_SAMPLES_DIR
#error "the tests need WIRERIG_SAMPLES_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using nlohmann::json;
namespace fs = std::filesystem;

json CylinderScene() {
  return json::parse(R"({
    "format": "wirerig.scene", "version": 1, "name": "beam",
    "mesh": {"procedural": "cylinder", "parameters": {"radius": 0.1, "height": 1.0}},
    "rig": {"description": {"parts": [{"name": "beam", "central_curve": [[0, 0, 0], [0, 1, 0]],
                                       "profile_count": 8, "points_per_profile": 16}]}},
    "parts": {"beam": {"kind": "deformable", "spine": {"material": "steel"}}},
    "playback": {"rigid_step": 0.005, "integrator": "momentum", "gravity": [0, -9.81, 0],
                 "profile_wires": {"modes": 4, "damping_ratio": 0.2, "frequency": 2.5}},
    "clips": [{"name": "push", "duration": 2, "loop": "ping_pong", "parts": [
      {"part": "beam", "boundary": [{"time": 0, "boundary": "cantilever_free"},
                                    {"time": 1, "boundary": "cantilever_guided"}],
       "point_loads": [{"at": 1, "magnitude": {"keys": [[0, 0], [2, 5, "cubic"]]},
                        "direction": [1, 0, 0], "axes": "world"}],
       "tip_force": {"interpolation": "step", "keys": [{"time": 0, "value": [0, 0, 1]}]},
       "rotation": [0, 0.1, 0]}],
      "profiles": [{"part": "beam", "profiles": [2, 3], "from": 0.1, "to": 0.4,
                    "boundary": "clamped",
                    "line_loads": [{"force_per_length": [0.5, 0, 0]}]}]}],
    "camera": {"target": [0, 0.5, 0], "yaw": 0.3, "pitch": 0.2, "distance": 3, "fov": 0.7}
  })");
}

std::string ParseError(const json& document) {
  Result<SceneDescription> scene = ParseScene(document, ".");
  return scene.ok() ? "ok" : scene.error();
}

TEST(Scene, ParsesEveryField) {
  Result<SceneDescription> parsed = ParseScene(CylinderScene(), "/scenes");
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  const SceneDescription& scene = parsed.value();
  EXPECT_EQ(scene.name, "beam");
  EXPECT_EQ(scene.folder, fs::path("/scenes"));
  EXPECT_EQ(scene.mesh.procedural, "cylinder");
  EXPECT_EQ(scene.mesh.parameters.at("radius"), 0.1);
  EXPECT_EQ(scene.rig.kind, RigSourceKind::kDescription);
  ASSERT_EQ(scene.rig.description.parts.size(), 1u);
  EXPECT_EQ(scene.parts.at("beam").kind, SpineKind::kDeformable);
  EXPECT_EQ(scene.parts.at("beam").spine_material->youngs_modulus,
            FindMaterialPreset("steel")->youngs_modulus);
  EXPECT_EQ(scene.playback.integrator, RigidIntegrator::kMomentum);
  EXPECT_EQ(scene.playback.gravity, Vec3(0, -9.81, 0));
  EXPECT_EQ(scene.playback.profile_wires.modes, 4);
  EXPECT_EQ(scene.playback.profile_wires.damping_ratio, 0.2);
  EXPECT_EQ(scene.playback.profile_wires.frequency, 2.5);
  EXPECT_EQ(scene.playback.wires.modes, 0);  // spines stay static unless asked
  ASSERT_EQ(scene.clips.size(), 1u);
  const RawClip& clip = scene.clips[0];
  EXPECT_EQ(clip.loop, LoopMode::kPingPong);
  ASSERT_EQ(clip.parts.size(), 1u);
  EXPECT_EQ(clip.parts[0].channels.boundary.size(), 2u);
  EXPECT_EQ(clip.parts[0].channels.point_loads[0].axes, LoadAxes::kWorld);
  EXPECT_EQ(clip.parts[0].channels.point_loads[0].magnitude.keys[1].interpolation,
            Interpolation::kCubic);
  EXPECT_EQ(clip.parts[0].channels.tip_force.keys[0].interpolation, Interpolation::kStep);
  EXPECT_EQ(clip.profiles[0].channels.profiles, (std::vector<std::uint32_t>{2, 3}));
  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_EQ(scene.camera->distance, 3.0);
}

TEST(Scene, ErrorsNameTheFieldByJsonPointer) {
  json d = CylinderScene();
  d["format"] = "wirerig.rig";
  EXPECT_EQ(ParseError(d), "/format: must be \"wirerig.scene\"");
  d = CylinderScene();
  d["version"] = 2;
  EXPECT_EQ(ParseError(d), "/version: must be 1 (this wirerig reads scene format version 1)");
  d = CylinderScene();
  d["mesh"]["parameters"]["radious"] = 1;
  EXPECT_EQ(ParseError(d),
            "/mesh/parameters/radious: unknown parameter of cylinder; did you mean \"radius\"? "
            "(parameters: radius, height, radial_segments, height_segments)");
  d = CylinderScene();
  d["mesh"]["file"] = "x.obj";
  EXPECT_EQ(ParseError(d), "/mesh: needs exactly one of \"file\" and \"procedural\"");
  d = CylinderScene();
  d["clips"][0]["parts"][0]["point_loads"][0]["axes"] = "screen";
  EXPECT_EQ(ParseError(d), "/clips/0/parts/0/point_loads/0/axes: must be \"local\" or \"world\"");
  d = CylinderScene();
  d["clips"][0]["parts"][0]["point_loads"][0]["magnitude"]["keys"][1][0] = 3;
  EXPECT_EQ(ParseError(d),
            "/clips/0: parts[0].point_loads[0].magnitude.keys[1].time: must lie within the "
            "clip, [0, duration]");
  d = CylinderScene();
  d["clips"][0]["parts"][0]["boundary"][1]["boundary"] = "glued";
  EXPECT_EQ(ParseError(d).rfind("/clips/0/parts/0/boundary/1/boundary: must be", 0), 0u);
  d = CylinderScene();
  d["clips"][0]["parts"][0]["rotation"] = {0, 1};
  EXPECT_EQ(ParseError(d).rfind("/clips/0/parts/0/rotation", 0), 0u) << ParseError(d);
  d = CylinderScene();
  d["clips"].push_back(d["clips"][0]);
  EXPECT_EQ(ParseError(d), "/clips/1/name: another clip has this name");
  d = CylinderScene();
  d["playback"]["rigid_step"] = 0;
  EXPECT_EQ(ParseError(d), "/playback/rigid_step: must be in (0, 1] s");
  d = CylinderScene();
  d["playback"]["profile_wires"]["frequency"] = 0;
  EXPECT_EQ(ParseError(d), "/playback/profile_wires/frequency: must be in (0, 1000] Hz");
  d = CylinderScene();
  d["playback"]["profile_wires"]["stiffness"] = 1;
  EXPECT_EQ(ParseError(d).rfind("/playback/profile_wires/stiffness: unknown field", 0), 0u)
      << ParseError(d);
  d = CylinderScene();
  d["camera"]["pitch"] = 2;
  EXPECT_EQ(ParseError(d), "/camera/pitch: must lie within (-pi/2, pi/2)");
  d = CylinderScene();
  d["camera"]["distance"] = 1e6;  // positive, yet refused: the message gives the bound
  EXPECT_EQ(ParseError(d),
            "/camera/distance: must be 0 (frame the model) or positive, below 1e6 m");
  d = CylinderScene();
  d["parts"]["beam"]["kind"] = "floppy";
  EXPECT_EQ(ParseError(d), "/parts/beam/kind: must be \"rigid\" or \"deformable\"");
  d = CylinderScene();
  d["colour"] = "red";
  EXPECT_EQ(ParseError(d),
            "/colour: unknown field (known fields: format, version, name, mesh, rig, "
            "skin_thickness, default_kind, parts, playback, clips, camera)");
  d = CylinderScene();
  d["clips"][0]["durration"] = d["clips"][0]["duration"];
  d["clips"][0].erase("duration");
  EXPECT_EQ(
      ParseError(d).rfind("/clips/0/durration: unknown field; did you mean \"duration\"? (", 0), 0u)
      << ParseError(d);
}

TEST(Scene, SaveThenLoadGivesTheSameDocument) {
  json document = CylinderScene();
  document["camera"]["follow"] = "beam";
  document["camera"]["ground"] = -0.25;
  const SceneDescription scene = ParseScene(document, ".").value();
  EXPECT_EQ(scene.camera->follow, "beam");
  EXPECT_EQ(scene.camera->ground, -0.25);
  const fs::path path = fs::temp_directory_path() / "wirerig_scene_test" / "beam.scene.json";
  fs::create_directories(path.parent_path());
  ASSERT_TRUE(SaveScene(scene, path).ok());
  Result<SceneDescription> loaded = LoadScene(path);
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  EXPECT_EQ(SceneToJson(loaded.value()), SceneToJson(scene));
  EXPECT_EQ(loaded.value().folder, path.parent_path());
}

TEST(Scene, LoadNamesTheFile) {
  const fs::path path = fs::temp_directory_path() / "wirerig_scene_test" / "broken.scene.json";
  fs::create_directories(path.parent_path());
  std::ofstream(path) << "{\"format\": ";
  EXPECT_EQ(LoadScene(path).error(),
            path.string() +
                ": not valid JSON: line 1, column 12: syntax error while parsing value - "
                "unexpected end of input; expected '[', '{', or a literal");
  std::ofstream(path)
      << "{\n  \"format\": \"wirerig.scene\",\n  \"version\": 1\n  \"name\": \"x\"\n}\n";
  EXPECT_EQ(
      LoadScene(path).error().rfind(path.string() + ": not valid JSON: line 4, column 8: ", 0), 0u)
      << LoadScene(path).error();
  EXPECT_EQ(LoadScene(path.string() + ".missing").error(),
            path.string() + ".missing: no such file");
}

// `bake /dev/zero` read forever; a FIFO blocked: neither is opened for reading.
TEST(Scene, LoadRefusesWhatIsNotARegularFile) {
  const std::string zero = LoadScene("/dev/zero").error();
  EXPECT_EQ(zero.rfind("/dev/zero: is not a regular file", 0), 0u) << zero;
  const fs::path dir = fs::temp_directory_path() / "wirerig_scene_test";
  fs::create_directories(dir);
  EXPECT_EQ(LoadScene(dir).error(), dir.string() + ": is a directory, not a scene file (JSON)");
  const fs::path fifo = dir / "pipe.scene.json";
  fs::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string piped = LoadScene(fifo).error();
  fs::remove(fifo);
  EXPECT_NE(piped.find("pipe.scene.json: is not a regular file"), std::string::npos) << piped;
}

// A scene whose rig file is "." (its own folder) aborted the build with an escaping exception.
TEST(Scene, BuildRefusesARigFileThatIsADirectory) {
  json d = CylinderScene();
  d["rig"] = {{"file", "."}};
  const fs::path folder = fs::temp_directory_path();
  Result<SceneDescription> scene = ParseScene(d, folder);
  ASSERT_TRUE(scene.ok()) << scene.error();
  Result<BuiltScene> built(Error{""});
  ASSERT_NO_THROW(built = BuildScene(scene.value()));
  ASSERT_FALSE(built.ok());
  EXPECT_NE(built.error().find("is a directory, not a rig file (JSON)"), std::string::npos)
      << built.error();
}

TEST(Scene, BuildsAProceduralSceneReadyToPlay) {
  Result<BuiltScene> built = BuildScene(ParseScene(CylinderScene(), ".").value());
  ASSERT_TRUE(built.ok()) << built.error();
  const BuiltScene& scene = built.value();
  ASSERT_EQ(scene.model.parts.size(), 1u);
  EXPECT_EQ(scene.model.vertices.size(), scene.mesh.welded_positions.size());
  // The steel spine from the scene's part settings, not the description's soft tissue.
  EXPECT_EQ(scene.rig.parts[0].spine_wire.material.youngs_modulus,
            FindMaterialPreset("steel")->youngs_modulus);
  ASSERT_NE(scene.FindClip(""), nullptr);
  EXPECT_EQ(scene.FindClip("push")->name, "push");
  EXPECT_EQ(scene.FindClip("swim"), nullptr);
  EXPECT_EQ(scene.clips[0].profiles.size(), 1u);
}

// A closed cylinder of radius 0.1 m from y = 0 to 1 as an OFF file (the cylinder scene's beam).
fs::path WriteBeamMesh(const fs::path& path) {
  const Mesh mesh = MakeCylinder(0.1, 1.0, 16, 8);
  std::ofstream out(path);
  out << "OFF\n" << mesh.positions.size() << " " << mesh.triangles.size() << " 0\n";
  for (const Vec3& p : mesh.positions) out << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const Triangle& t : mesh.triangles)
    out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  return path;
}

// Editing a built scene's wire settings and clips (what the viewer's apply and undo do) keeps
// its mesh and rig: the mesh file is gone by then and the edit still succeeds, and the result is
// what a fresh build of the edited description gives; changing the mesh or rig source builds
// anew; a bad edit leaves the scene as it was.
TEST(Scene, EditInPlaceKeepsTheMeshAndRigAndMatchesAFreshBuild) {
  const fs::path folder = fs::path(::testing::TempDir()) / "wirerig_scene_edit";
  fs::create_directories(folder);
  const fs::path mesh_file = WriteBeamMesh(folder / "beam.off");
  json d = CylinderScene();
  d["mesh"] = {{"file", "beam.off"}};
  const SceneDescription original = ParseScene(d, folder).value();
  d["parts"]["beam"]["spine"]["material"] = "aluminium";
  d["clips"][0]["duration"] = 3;
  const SceneDescription edited = ParseScene(d, folder).value();
  Result<BuiltScene> built = BuildScene(original), reference = BuildScene(edited);
  ASSERT_TRUE(built.ok() && reference.ok()) << built.error();
  fs::remove(mesh_file);
  ASSERT_FALSE(BuildScene(edited).ok());  // a build would need the file

  BuiltScene& scene = built.value();
  Result<bool> in_place = EditScene(&scene, edited);
  ASSERT_TRUE(in_place.ok()) << in_place.error();
  EXPECT_TRUE(in_place.value());
  const PartModel& part = scene.model.parts[0];
  const PartModel& expected = reference.value().model.parts[0];
  const Material& aluminium = *FindMaterialPreset("aluminium");
  EXPECT_EQ(scene.rig.parts[0].spine_wire.material.youngs_modulus, aluminium.youngs_modulus);
  EXPECT_DOUBLE_EQ(part.spine_stiffness.bending,
                   aluminium.youngs_modulus * scene.rig.parts[0].spine_wire.section.second_moment);
  EXPECT_EQ(part.spine_stiffness.bending, expected.spine_stiffness.bending);
  EXPECT_EQ(part.spine_stiffness.axial, expected.spine_stiffness.axial);
  EXPECT_EQ(part.mass.mass, expected.mass.mass);
  EXPECT_EQ(part.profiles[3].stiffness.bending, expected.profiles[3].stiffness.bending);
  EXPECT_EQ(scene.clips[0].duration, 3.0);
  EXPECT_EQ(scene.model.vertices.size(), reference.value().model.vertices.size());

  // Undo: the description before the edit gives back the rig's steel, not the aluminium.
  ASSERT_TRUE(EditScene(&scene, original).ok());
  EXPECT_EQ(scene.rig.parts[0].spine_wire.material.youngs_modulus,
            FindMaterialPreset("steel")->youngs_modulus);
  EXPECT_EQ(scene.clips[0].duration, 2.0);

  // A bad edit names the field and changes nothing.
  SceneDescription bad = original;
  bad.parts["arm"] = PartSettings{};
  Result<bool> refused = EditScene(&scene, bad);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error(),
            "scene \"beam\": /parts/arm: the rig has no part of this name (parts: beam)");
  EXPECT_FALSE(scene.description.parts.contains("arm"));
  EXPECT_EQ(scene.mesh.welded_positions.size(), reference.value().mesh.welded_positions.size());

  // Another mesh source is built anew (and needs its file).
  SceneDescription thicker = original;
  thicker.skin_thickness = 0.01;
  Result<bool> rebuilt = EditScene(&scene, thicker);
  ASSERT_FALSE(rebuilt.ok());
  EXPECT_NE(rebuilt.error().find("beam.off"), std::string::npos) << rebuilt.error();
  WriteBeamMesh(mesh_file);
  rebuilt = EditScene(&scene, thicker);
  ASSERT_TRUE(rebuilt.ok()) << rebuilt.error();
  EXPECT_FALSE(rebuilt.value());
  EXPECT_EQ(scene.description.skin_thickness, 0.01);
}

std::string BuildError(const json& document) {
  Result<SceneDescription> scene = ParseScene(document, ".");
  if (!scene) return "parse: " + scene.error();
  Result<BuiltScene> built = BuildScene(scene.value());
  return built.ok() ? "ok" : built.error();
}

TEST(Scene, BuildNamesWhatIsWrong) {
  json d = CylinderScene();
  d["mesh"]["parameters"]["radius"] = -1;
  EXPECT_EQ(BuildError(d),
            "scene \"beam\": /mesh/parameters/radius: must be a positive length (m)");
  d = CylinderScene();
  d["parts"]["arm"] = json::object();
  EXPECT_EQ(BuildError(d),
            "scene \"beam\": /parts/arm: the rig has no part of this name (parts: beam)");
  d = CylinderScene();
  d["camera"]["follow"] = "arm";
  EXPECT_EQ(BuildError(d),
            "scene \"beam\": /camera/follow: the rig has no part named \"arm\" (parts: beam)");
  d["camera"]["follow"] = "beam";
  EXPECT_EQ(BuildError(d), "ok");
  d["camera"]["ground"] = 1e300;
  EXPECT_EQ(ParseError(d), "/camera/ground: must be a finite height within 1e6 m");
  d = CylinderScene();
  d["clips"][0]["profiles"][0]["profiles"] = {2, 30};
  const std::string error = BuildError(d);
  EXPECT_EQ(error.rfind("scene \"beam\": /clips/0: profiles[0].profiles[1]: part \"beam\" has", 0),
            0u)
      << error;
  d = CylinderScene();
  d["mesh"] = {{"file", "no_such_mesh.obj"}};
  EXPECT_NE(BuildError(d).find("no_such_mesh.obj"), std::string::npos);
}

// Every generator a scene may name builds with its defaults, with a material, and a rig of its
// own exactly when the scene may take its rig from the generator.
TEST(Scene, EveryProceduralGeneratorBuildsWithItsDefaults) {
  const std::vector<std::pair<std::string, bool>> generators = {
      {"octopus", true},   {"cylinder", false}, {"cone", false}, {"capsule", false},
      {"torus", false},    {"candles", true},   {"beam", true},  {"trunk", true},
      {"lamp_post", true}, {"chair", true}};
  for (const auto& [name, describes_rig] : generators) {
    SCOPED_TRACE(name);
    json d = {{"format", "wirerig.scene"},
              {"version", 1},
              {"name", name},
              {"mesh", {{"procedural", name}}},
              {"rig", {{"from", describes_rig ? "procedural" : "automatic"}}},
              {"clips", json::array()}};
    if (!describes_rig) {
      // Its rig from the procedural generator is refused, naming those that describe theirs.
      d["rig"]["from"] = "procedural";
      EXPECT_EQ(ParseError(d),
                "/rig/from: \"procedural\" needs a procedural mesh that describes its rig "
                "(octopus, candles, beam, trunk, lamp_post, chair)");
      continue;
    }
    Result<SceneDescription> scene = ParseScene(d, ".");
    ASSERT_TRUE(scene.ok()) << scene.error();
    Result<BuiltScene> built = BuildScene(scene.value());
    ASSERT_TRUE(built.ok()) << built.error();
    EXPECT_GT(built.value().mesh.triangles.size(), 0u);
    ASSERT_EQ(built.value().mesh.materials.size(), 1u);
    EXPECT_EQ(built.value().mesh.materials[0].name, name);
    EXPECT_GT(built.value().model.parts.size(), 0u);
  }
  json d = CylinderScene();
  d["mesh"]["procedural"] = "teapot";
  EXPECT_EQ(ParseError(d),
            "/mesh/procedural: unknown generator (octopus, cylinder, cone, capsule, torus, "
            "candles, beam, trunk, lamp_post, chair)");
  d = CylinderScene();
  d["mesh"] = {{"procedural", "octopus"}, {"parameters", {{"tentacle_count", 2.5}}}};
  EXPECT_EQ(BuildError(d),
            "scene \"beam\": /mesh/parameters/tentacle_count: must be a whole number >= 1");
  // Below 1 and above the octopus's own 64 name one range each, not two.
  d["mesh"]["parameters"]["tentacle_count"] = 0;
  EXPECT_EQ(BuildError(d),
            "scene \"beam\": /mesh/parameters/tentacle_count: must be a whole number >= 1");
  d["mesh"]["parameters"]["tentacle_count"] = 100;
  EXPECT_EQ(BuildError(d), "scene \"beam\": /mesh/parameters/tentacle_count: must be in [1, 64]");
  // Far above every generator's range: the generator's own range, not a bound it does not hold
  // (before: "at most 4096", and 4096 then "must be in [6, 512]").
  d["mesh"]["parameters"] = {{"radial_segments", 1e6}};
  EXPECT_EQ(BuildError(d), "scene \"beam\": /mesh/parameters/radial_segments: must be in [6, 512]");
  d["mesh"] = {{"procedural", "trunk"}, {"parameters", {{"profile_count", 1e8}}}};
  EXPECT_EQ(BuildError(d), "scene \"beam\": /mesh/parameters/profile_count: must be in [2, 1024]");
}

TEST(Scene, TheOctopusSampleBuilds) {
  Result<SceneDescription> scene =
      LoadScene(std::string(WIRERIG_SAMPLES_DIR) + "/octopus/octopus.scene.json");
  ASSERT_TRUE(scene.ok()) << scene.error();
  Result<BuiltScene> built = BuildScene(scene.value());
  ASSERT_TRUE(built.ok()) << built.error();
  EXPECT_EQ(built.value().model.parts.size(), 9u);
  ASSERT_NE(built.value().FindClip("swim"), nullptr);
  EXPECT_EQ(built.value().FindClip("swim")->duration, 10.0);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
