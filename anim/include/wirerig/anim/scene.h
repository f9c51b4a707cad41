// Scenes: everything `bake`, `render` and `view` need in one versioned JSON file
// (docs/scene-format.md): the mesh source (a file, or a procedural generator with its
// parameters), the rig (a rig file, a rig description, or found automatically), per-part
// spine kinds and wire properties, playback settings, clips and camera hints.
//
// LoadScene reads and checks the file (errors "<file>: <json pointer>: <reason>"); BuildScene
// imports or generates the mesh, builds or loads the rig, the runtime model and the clips
// (errors name the scene file and the part, clip or field at fault). SaveScene writes a file
// LoadScene reads back to the same description, atomically.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "wirerig/anim/clip.h"
#include "wirerig/anim/motion_import.h"
#include "wirerig/anim/playback.h"
#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/rig/rig.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_description.h"

namespace wirerig {

struct MeshSource {
  std::filesystem::path file;  // relative to the scene's folder; empty for procedural meshes
  ImportOptions import;
  // "octopus", "cylinder", "cone", "capsule", "torus", or a prop of the paper's samples
  // ("candles", "beam", "trunk", "lamp_post", "chair"); empty for files. Parameters by name
  // (metres, counts); those left out keep the generator's defaults.
  std::string procedural;
  std::map<std::string, double> parameters;
  int subdivide = 0;  // midpoint subdivision levels applied after import, 0..4
};

enum class RigSourceKind : int {
  kRigFile = 0,          // a rig file made by `wirerig rig`
  kDescriptionFile = 1,  // a rig description file
  kDescription = 2,      // a rig description inline in the scene
  kAutomatic = 3,        // the mesh's skeleton, else its curve skeleton
  kProcedural = 4,       // the procedural generator's own description (octopus, props)
};

struct RigSource {
  RigSourceKind kind = RigSourceKind::kAutomatic;
  std::filesystem::path file;    // kRigFile, kDescriptionFile; relative to the scene's folder
  RigDescription description;    // kDescription
  std::string description_json;  // kDescription: the inline JSON as read, for SaveScene
};

// Per-part settings over the defaults; every member optional.
struct PartSettings {
  std::optional<SpineKind> kind;
  std::optional<Material> spine_material;
  std::optional<Section> spine_section;
  std::optional<Material> profile_material;
  std::optional<Section> profile_section;
};

struct CameraHint {
  Vec3 target = Vec3::Zero();  // m
  double yaw = 0.0;            // rad, about +Y, 0 looking along -Z
  double pitch = 0.0;          // rad, positive looking down
  double distance = 0.0;       // m from the target; 0: frame the model
  double fov = 0.8;            // rad, vertical
  // A part whose spine root the target moves with (a walking character); empty: fixed.
  std::string follow;
  // The ground plane's height (m), fixed, so a body that swims or jumps is seen to travel;
  // empty: under the model's lowest point in every frame.
  std::optional<double> ground;
};

struct SceneDescription {
  static constexpr int kFormatVersion = 1;

  std::string name;
  std::filesystem::path folder;  // where relative paths resolve (the scene file's folder)
  MeshSource mesh;
  RigSource rig;
  double skin_thickness = 0.005;  // m, for automatically made wire sections
  SpineKind default_kind = SpineKind::kDeformable;
  std::map<std::string, PartSettings> parts;  // by part name
  PlaybackOptions playback;
  std::vector<RawClip> clips;
  // By clip name: the clips whose tracks come from a motion file (motion_import.h); BuildScene
  // makes them, their own tracks in `clips` merged on top.
  std::map<std::string, MotionSource> motions;
  std::optional<CameraHint> camera;
};

// Reads the document; errors read "<json pointer>: <reason>". `folder` resolves paths.
Result<SceneDescription> ParseScene(const nlohmann::json& document,
                                    const std::filesystem::path& folder);
Result<SceneDescription> LoadScene(const std::filesystem::path& path);
nlohmann::json SceneToJson(const SceneDescription& scene);
// Paths are written as given (relative to the scene's folder).
Result<std::filesystem::path> SaveScene(const SceneDescription& scene,
                                        const std::filesystem::path& path);

// A scene made ready to play: mesh, rig, runtime model and built clips.
struct BuiltScene {
  SceneDescription description;
  Mesh mesh;
  Rig rig;
  Rig source_rig;         // `rig` as built or read, before the scene's per-part wire settings
  RigBuildReport report;  // empty when the rig came from a rig file
  RigModel model;
  std::vector<Clip> clips;  // one per description clip, same order

  // The clip named `name`, the first clip if `name` is empty; null if there is none.
  const Clip* FindClip(const std::string& name) const;
  // Why FindClip(name) found nothing: `no clip is named "wav"; did you mean "wave"? (clips:
  // wave, pose)`, or "the scene has no clips".
  std::string MissingClipMessage(const std::string& name) const;
};

Result<BuiltScene> BuildScene(const SceneDescription& scene);

// Makes *scene what BuildScene(edited) would. When `edited` differs from scene->description only
// in what needs no new mesh or rig (per-part materials, sections and spine kinds, the clips, the
// playback options, the camera), the built scene is edited in place: the wire properties are
// set on the model (SetWireProperties) and the clips rebuilt; nothing is imported or rigged
// again, and it returns true. Otherwise the scene is built anew and it returns false. On error
// *scene is left as it was.
Result<bool> EditScene(BuiltScene* scene, const SceneDescription& edited);

// The files `scene` reads, each with what it is for messages ("the scene's mesh"): the mesh,
// a rig or rig description file, motion files and their mappings, resolved against its folder.
std::vector<std::pair<std::filesystem::path, std::string>> SceneInputFiles(
    const SceneDescription& scene);

// LoadScene then BuildScene; every error starts with the file's path. `import_isolation`, when
// set, imports the scene's mesh file in a child process (mesh_import.h).
Result<BuiltScene> LoadAndBuildScene(
    const std::filesystem::path& path,
    const std::optional<ImportIsolation>& import_isolation = std::nullopt);

// A clip that holds every part of `model` at rest (for scenes without clips).
Clip RestClip(const RigModel& model);

}  // namespace wirerig
