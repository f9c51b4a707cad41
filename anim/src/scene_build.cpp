// BuildScene: from a scene description to a mesh, rig, runtime model and built clips.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "procedural_generators.h"
#include "wirerig/anim/scene.h"
#include "wirerig/io/name_hint.h"
#include "wirerig/rig/automatic_description.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/mesh_subdivision.h"
#include "wirerig/rig/rig_file.h"
#include "wirerig/rig/rig_model_builder.h"

namespace wirerig {
namespace {

std::filesystem::path Resolve(const SceneDescription& scene, const std::filesystem::path& p) {
  return p.is_absolute() ? p : scene.folder / p;
}

std::vector<std::string> PartNames(const Rig& rig) {
  std::vector<std::string> names;
  for (const RigPart& part : rig.parts) names.push_back(part.name);
  return names;
}

// Applies the scene's per-part wire settings over the rig's own.
std::string ApplyWireSettings(const SceneDescription& scene, Rig& rig) {
  for (const auto& [name, settings] : scene.parts) {
    // A reference of its own: lambdas capture no structured bindings before clang 16.
    const std::string& wanted = name;
    const auto part = std::find_if(rig.parts.begin(), rig.parts.end(),
                                   [&](const RigPart& p) { return p.name == wanted; });
    if (part == rig.parts.end()) {
      return "/parts/" + name + ": the rig has no part of this name" +
             NameHint(name, PartNames(rig), "parts");
    }
    if (settings.spine_material) part->spine_wire.material = *settings.spine_material;
    if (settings.spine_section) part->spine_wire.section = *settings.spine_section;
    for (WireProperties& wire : part->profile_wires) {
      if (settings.profile_material) wire.material = *settings.profile_material;
      if (settings.profile_section) wire.section = *settings.profile_section;
    }
  }
  return {};
}

// The parts' spine kinds, the camera's part and the clips of a scene whose model is built.
std::string SetPartsAndClips(const SceneDescription& scene, BuiltScene& out) {
  for (PartModel& part : out.model.parts) {
    const auto settings = scene.parts.find(part.name);
    if (settings != scene.parts.end() && settings->second.kind) part.kind = *settings->second.kind;
  }
  if (scene.camera && !scene.camera->follow.empty()) {
    const auto& parts = out.model.parts;
    if (std::none_of(parts.begin(), parts.end(),
                     [&](const PartModel& p) { return p.name == scene.camera->follow; })) {
      return "/camera/follow: the rig has no part named \"" + scene.camera->follow + "\"" +
             NameHint(scene.camera->follow, PartNames(out.rig), "parts");
    }
  }

  // The clips, against the model.
  out.clips.clear();
  for (std::size_t i = 0; i < scene.clips.size(); ++i) {
    const std::string clip_path = "/clips/" + std::to_string(i);
    RawClip raw;
    if (const auto motion = scene.motions.find(scene.clips[i].name);
        motion != scene.motions.end()) {
      // Tracks from a motion file (motion_import.h), the clip's own merged on top.
      Result<RawClip> made = MakeMotionClip(
          motion->second, scene.clips[i], scene.folder, out.mesh,
          scene.mesh.procedural.empty() ? Resolve(scene, scene.mesh.file) : std::filesystem::path(),
          scene.mesh.import, out.model);
      if (!made) return clip_path + made.error();
      raw = std::move(made).value();
    }
    Result<Clip> clip =
        BuildClip(scene.motions.contains(scene.clips[i].name) ? raw : scene.clips[i], out.model);
    if (!clip) return clip_path + ": " + clip.error();
    out.clips.push_back(std::move(clip).value());
  }
  return {};
}

// Whether two descriptions ask for the same mesh and rig: they differ at most in what EditScene
// edits in place (per-part settings, default spine kind, clips and motions, playback, camera).
bool SameSource(const SceneDescription& a, const SceneDescription& b) {
  if (a.folder != b.folder) return false;  // the documents hold paths relative to it
  auto source = [](const SceneDescription& scene) {
    nlohmann::json document = SceneToJson(scene);
    for (const char* key : {"parts", "default_kind", "clips", "playback", "camera"})
      document.erase(key);
    return document;
  };
  return source(a) == source(b);
}

}  // namespace

std::vector<std::pair<std::filesystem::path, std::string>> SceneInputFiles(
    const SceneDescription& scene) {
  std::vector<std::pair<std::filesystem::path, std::string>> files;
  if (!scene.mesh.file.empty())
    files.emplace_back(Resolve(scene, scene.mesh.file), "the scene's mesh");
  if (!scene.rig.file.empty())
    files.emplace_back(Resolve(scene, scene.rig.file), "the scene's rig");
  for (const auto& [clip, motion] : scene.motions) {
    files.emplace_back(Resolve(scene, motion.file), "clip \"" + clip + "\"'s motion file");
    if (!motion.mapping.empty())
      files.emplace_back(Resolve(scene, motion.mapping), "clip \"" + clip + "\"'s motion mapping");
  }
  return files;
}

const Clip* BuiltScene::FindClip(const std::string& name) const {
  if (clips.empty()) return nullptr;
  if (name.empty()) return &clips.front();
  for (const Clip& clip : clips)
    if (clip.name == name) return &clip;
  return nullptr;
}

std::string BuiltScene::MissingClipMessage(const std::string& name) const {
  if (clips.empty()) return "the scene has no clips";
  std::vector<std::string> names;
  for (const Clip& clip : clips) names.push_back(clip.name);
  return "no clip is named \"" + name + "\"" + NameHint(name, names, "clips");
}

Result<BuiltScene> BuildScene(const SceneDescription& scene) {
  BuiltScene out;
  out.description = scene;
  const std::string where = scene.name.empty() ? "scene" : "scene \"" + scene.name + "\"";
  auto fail = [&](const std::string& message) { return Error{where + ": " + message}; };

  // The mesh, and the description when the generator brings one.
  std::string mesh_name;
  RigDescription procedural_description;
  if (!scene.mesh.procedural.empty()) {
    const detail::ProceduralGenerator* generator =
        detail::FindProceduralGenerator(scene.mesh.procedural);
    if (generator == nullptr) return fail("/mesh/procedural: unknown generator");
    Result<detail::GeneratedMesh> generated = generator->generate(scene.mesh);
    if (!generated) return fail(generated.error());
    out.mesh = std::move(generated.value().mesh);
    if (out.mesh.materials.empty()) {
      // A matte colour per generator, so exports and engines show the sample as it is meant
      // rather than in their default grey.
      MeshMaterial material;
      material.name = scene.mesh.procedural;
      material.base_color = generator->base_color;
      out.mesh.materials.push_back(std::move(material));
      for (MeshPart& part : out.mesh.parts) part.material = 0;
    }
    procedural_description = std::move(generated.value().description);
    mesh_name = "procedural:" + scene.mesh.procedural;
  } else {
    const std::filesystem::path file = Resolve(scene, scene.mesh.file);
    Result<ImportedMesh> imported = ImportMesh(file, scene.mesh.import);
    if (!imported) return fail(imported.error());
    out.mesh = scene.mesh.subdivide > 0
                   ? SubdivideMidpoint(imported.value().mesh, scene.mesh.subdivide)
                   : std::move(imported.value().mesh);
    mesh_name = file.string();
  }

  // The rig.
  RigBuildOptions build_options;
  build_options.skin_thickness = scene.skin_thickness;
  auto build = [&](const RigDescription& description) -> std::string {
    Result<BuiltRig> built = BuildRig(out.mesh, description, mesh_name, build_options);
    if (!built) return built.error();
    out.rig = std::move(built.value().rig);
    out.report = std::move(built.value().report);
    return {};
  };
  std::string error;
  switch (scene.rig.kind) {
    case RigSourceKind::kRigFile: {
      Result<Rig> rig = LoadRig(Resolve(scene, scene.rig.file));
      if (!rig) return fail(rig.error());
      out.rig = std::move(rig).value();
      break;
    }
    case RigSourceKind::kDescriptionFile: {
      Result<RigDescription> description = LoadRigDescription(Resolve(scene, scene.rig.file));
      if (!description) return fail(description.error());
      error = build(description.value());
      break;
    }
    case RigSourceKind::kDescription:
      error = build(scene.rig.description);
      break;
    case RigSourceKind::kAutomatic: {
      Result<AutomaticDescription> automatic = DescribeAutomatically(out.mesh);
      if (!automatic) return fail(mesh_name + ": " + automatic.error());
      error = build(automatic.value().description);
      break;
    }
    case RigSourceKind::kProcedural:
      error = build(procedural_description);
      break;
  }
  if (!error.empty()) return fail(mesh_name + ": " + error);
  out.source_rig = out.rig;
  if (std::string e = ApplyWireSettings(scene, out.rig); !e.empty()) return fail(e);

  // The runtime model, with each part's spine kind.
  RigModelOptions model_options;
  model_options.spine_kind = scene.default_kind;
  Result<BuiltRigModel> model = BuildRigModel(out.mesh, out.rig, model_options);
  if (!model) return fail(model.error());
  out.model = std::move(model.value().model);
  if (std::string e = SetPartsAndClips(scene, out); !e.empty()) return fail(e);
  return out;
}

Result<bool> EditScene(BuiltScene* scene, const SceneDescription& edited) {
  if (!SameSource(scene->description, edited)) {
    Result<BuiltScene> built = BuildScene(edited);
    if (!built) return Error{built.error()};
    *scene = std::move(built).value();
    return false;
  }
  BuiltScene out;
  out.description = edited;
  out.mesh = std::move(scene->mesh);  // given back below if the edit fails
  out.rig = scene->source_rig;
  out.source_rig = scene->source_rig;
  out.report = scene->report;
  out.model = scene->model;
  std::string error = ApplyWireSettings(edited, out.rig);
  if (error.empty()) {
    SetWireProperties(out.rig, &out.model);
    for (PartModel& part : out.model.parts) part.kind = edited.default_kind;
    error = SetPartsAndClips(edited, out);
  }
  if (!error.empty()) {
    scene->mesh = std::move(out.mesh);
    const std::string& name = edited.name;
    return Error{(name.empty() ? "scene" : "scene \"" + name + "\"") + ": " + error};
  }
  *scene = std::move(out);
  return true;
}

Result<BuiltScene> LoadAndBuildScene(const std::filesystem::path& path,
                                     const std::optional<ImportIsolation>& import_isolation) {
  Result<SceneDescription> description = LoadScene(path);
  if (!description) return Error{description.error()};
  description.value().mesh.import.isolation = import_isolation;
  Result<BuiltScene> built = BuildScene(description.value());
  if (!built) return Error{path.string() + ": " + built.error()};
  return built;
}

Clip RestClip(const RigModel& model) {
  Clip clip;
  clip.name = "rest";
  clip.parts.resize(model.parts.size());
  clip.key_times = {0.0, clip.duration};
  return clip;
}

}  // namespace wirerig
