// Reading and writing scene files (docs/scene-format.md).
#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "procedural_generators.h"
#include "wirerig/anim/clip_json.h"
#include "wirerig/anim/scene.h"
#include "wirerig/io/finite.h"

#include "wirerig/io/atomic_file.h"
#include "wirerig/io/input_file.h"
#include "wirerig/io/json_text.h"
#include "wirerig/io/name_hint.h"
#include "wirerig/rig/json_physics.h"

namespace wirerig {
namespace {

using nlohmann::json;

constexpr const char* kFormat = "wirerig.scene";
// The duration a clip with a motion holds until BuildScene reads the motion (the longest a clip
// may be: room for any key of its own tracks; BuildClip checks them against the motion's).
constexpr double kMotionPlaceholderDuration = kMaxClipDuration;

MeshSource ReadMeshSource(const JsonObject& o) {
  o.RejectUnknownKeys({"file", "up_axis", "unit_scale", "procedural", "parameters", "subdivide"});
  MeshSource mesh;
  mesh.subdivide = o.Integer("subdivide", 0);
  if (mesh.subdivide < 0 || mesh.subdivide > 4)
    throw FieldError(o.PathOf("subdivide"), "must be a whole number of levels in [0, 4]");
  if (o.Has("file") == o.Has("procedural"))
    throw FieldError(o.path(), "needs exactly one of \"file\" and \"procedural\"");
  if (o.Has("file")) {
    mesh.file = o.String("file");
    if (o.Has("up_axis")) {
      UpAxis axis;
      if (!ParseUpAxis(o.String("up_axis"), &axis))
        throw FieldError(o.PathOf("up_axis"), "must be \"x\", \"y\" or \"z\"");
      mesh.import.up_axis = axis;
    }
    if (o.Has("unit_scale")) {
      const double scale = o.Number("unit_scale");
      if (!(std::isfinite(scale) && scale > 0.0))
        throw FieldError(o.PathOf("unit_scale"), "must be positive (metres per unit)");
      mesh.import.unit_scale = scale;
    }
    return mesh;
  }
  mesh.procedural = o.String("procedural");
  const detail::ProceduralGenerator* generator = detail::FindProceduralGenerator(mesh.procedural);
  if (generator == nullptr)
    throw FieldError(o.PathOf("procedural"),
                     "unknown generator (" + detail::ProceduralGeneratorNames(false) + ")");
  if (o.Has("parameters")) {
    const JsonObject parameters = o.Object("parameters");
    for (const auto& item : o.Required("parameters").items()) {
      const std::vector<std::string>& names = generator->parameters;
      if (std::find(names.begin(), names.end(), item.key()) == names.end())
        throw FieldError(
            parameters.PathOf(item.key()),
            "unknown parameter of " + mesh.procedural + NameHint(item.key(), names, "parameters"));
      mesh.parameters[item.key()] = parameters.Number(item.key());
    }
  }
  return mesh;
}

json MeshSourceToJson(const MeshSource& mesh) {
  if (!mesh.procedural.empty()) {
    json out = {{"procedural", mesh.procedural}};
    if (!mesh.parameters.empty()) out["parameters"] = mesh.parameters;
    return out;
  }
  json out = {{"file", mesh.file.generic_string()}};
  if (mesh.subdivide > 0) out["subdivide"] = mesh.subdivide;
  if (mesh.import.up_axis) out["up_axis"] = std::string(ToString(*mesh.import.up_axis));
  if (mesh.import.unit_scale) out["unit_scale"] = *mesh.import.unit_scale;
  return out;
}

RigSource ReadRigSource(const JsonObject& o) {
  o.RejectUnknownKeys({"file", "description", "from"});
  if (int(o.Has("file")) + int(o.Has("description")) + int(o.Has("from")) != 1)
    throw FieldError(o.path(), "needs exactly one of \"file\", \"description\" and \"from\"");
  RigSource rig;
  if (o.Has("file")) {
    rig.kind = RigSourceKind::kRigFile;
    rig.file = o.String("file");
  } else if (o.Has("from")) {
    const std::string from = o.String("from");
    if (from == "automatic") {
      rig.kind = RigSourceKind::kAutomatic;
    } else if (from == "procedural") {
      rig.kind = RigSourceKind::kProcedural;
    } else {
      throw FieldError(o.PathOf("from"), "must be \"automatic\" or \"procedural\"");
    }
  } else if (o.Required("description").is_string()) {
    rig.kind = RigSourceKind::kDescriptionFile;
    rig.file = o.String("description");
  } else {
    rig.kind = RigSourceKind::kDescription;
    const json& inline_description = o.Required("description");
    Result<RigDescription> parsed = ParseRigDescription(inline_description);
    if (!parsed) throw FieldError(o.PathOf("description"), parsed.error());
    rig.description = std::move(parsed).value();
    rig.description_json = DumpJson(inline_description);
  }
  return rig;
}

json RigSourceToJson(const RigSource& rig) {
  switch (rig.kind) {
    case RigSourceKind::kRigFile:
      return {{"file", rig.file.generic_string()}};
    case RigSourceKind::kDescriptionFile:
      return {{"description", rig.file.generic_string()}};
    case RigSourceKind::kDescription:
      return {{"description", json::parse(rig.description_json)}};
    case RigSourceKind::kAutomatic:
      return {{"from", "automatic"}};
    case RigSourceKind::kProcedural:
      return {{"from", "procedural"}};
  }
  return {};
}

SpineKind ReadKind(const JsonObject& o, std::string_view key) {
  const std::string kind = o.String(key);
  if (kind == "rigid") return SpineKind::kRigid;
  if (kind == "deformable") return SpineKind::kDeformable;
  throw FieldError(o.PathOf(key), "must be \"rigid\" or \"deformable\"");
}
const char* KindName(SpineKind kind) { return kind == SpineKind::kRigid ? "rigid" : "deformable"; }

PartSettings ReadPartSettings(const JsonObject& o) {
  o.RejectUnknownKeys({"kind", "spine", "profiles"});
  PartSettings settings;
  if (o.Has("kind")) settings.kind = ReadKind(o, "kind");
  auto read_wire = [&](std::string_view key, std::optional<Material>* material,
                       std::optional<Section>* section) {
    if (!o.Has(key)) return;
    const JsonObject wire = o.Object(key);
    wire.RejectUnknownKeys({"material", "section"});
    if (wire.Has("material")) *material = ReadMaterial(wire, "material");
    if (wire.Has("section")) *section = ReadSection(wire, "section");
  };
  read_wire("spine", &settings.spine_material, &settings.spine_section);
  read_wire("profiles", &settings.profile_material, &settings.profile_section);
  return settings;
}

json PartSettingsToJson(const PartSettings& settings) {
  json out = json::object();
  if (settings.kind) out["kind"] = KindName(*settings.kind);
  auto write_wire = [&](const char* key, const std::optional<Material>& material,
                        const std::optional<Section>& section) {
    if (!material && !section) return;
    json wire = json::object();
    if (material) wire["material"] = MaterialToJson(*material);
    if (section) wire["section"] = SectionToJson(*section);
    out[key] = wire;
  };
  write_wire("spine", settings.spine_material, settings.spine_section);
  write_wire("profiles", settings.profile_material, settings.profile_section);
  return out;
}

TrackingOptions ReadTracking(const JsonObject& o) {
  o.RejectUnknownKeys({"frequency", "damping_ratio", "gravity"});
  TrackingOptions tracking;
  tracking.frequency = o.Number("frequency");
  if (!(std::isfinite(tracking.frequency) && tracking.frequency > 0.0 &&
        tracking.frequency <= 100.0))
    throw FieldError(o.PathOf("frequency"), "must be in (0, 100] Hz");
  tracking.damping_ratio = o.Number("damping_ratio", tracking.damping_ratio);
  if (!(std::isfinite(tracking.damping_ratio) && tracking.damping_ratio >= 0.0 &&
        tracking.damping_ratio <= 10.0))
    throw FieldError(o.PathOf("damping_ratio"), "must be in [0, 10]");
  tracking.gravity = o.Vector3("gravity", tracking.gravity);
  if (!IsFinite(tracking.gravity)) throw FieldError(o.PathOf("gravity"), "must be finite");
  return tracking;
}

// "modes" (default 8; 0 off) and "damping_ratio" of "wires" or "profile_wires".
template <class Options>
Options ReadModes(const JsonObject& o, Options out) {
  out.modes = o.Integer("modes", ModalBasis::kDefaultModes);
  if (!(out.modes >= 0 && out.modes <= ModalBasis::kMaxModes))
    throw FieldError(o.PathOf("modes"), "must be in [0, 32] (0: static wires)");
  out.damping_ratio = o.Number("damping_ratio", out.damping_ratio);
  if (!(std::isfinite(out.damping_ratio) && out.damping_ratio >= 0.0 && out.damping_ratio <= 100.0))
    throw FieldError(o.PathOf("damping_ratio"), "must be in [0, 100]");
  return out;
}

// "wires": {"modes": N, "damping_ratio": z}.
WireDynamicsOptions ReadWireDynamics(const JsonObject& o, const WireDynamicsOptions& defaults) {
  o.RejectUnknownKeys({"modes", "damping_ratio"});
  return ReadModes(o, defaults);
}

// "profile_wires": {"modes": N, "damping_ratio": z, "frequency": Hz, "limit": fraction,
// "parts": [names]}.
ProfileWireOptions ReadProfileWires(const JsonObject& o, const ProfileWireOptions& defaults) {
  o.RejectUnknownKeys({"modes", "damping_ratio", "frequency", "limit", "parts"});
  ProfileWireOptions out = ReadModes(o, defaults);
  out.frequency = o.Number("frequency", out.frequency);
  if (!(std::isfinite(out.frequency) && out.frequency > 0.0 && out.frequency <= 1000.0))
    throw FieldError(o.PathOf("frequency"), "must be in (0, 1000] Hz");
  out.limit = o.Number("limit", out.limit);
  if (!(std::isfinite(out.limit) && out.limit > 0.0 && out.limit <= 1.0))
    throw FieldError(o.PathOf("limit"), "must be in (0, 1] (of a loop's mean radius)");
  if (o.Has("parts")) {
    const json& names = RequireArray(o.Required("parts"), o.PathOf("parts"));
    for (std::size_t i = 0; i < ArraySize(names); ++i) {
      const json& name = ArrayElement(names, i);
      if (!name.is_string())
        throw FieldError(o.PathOf("parts") + "/" + std::to_string(i), "must be a part's name");
      out.parts.push_back(name.get<std::string>());
    }
  }
  return out;
}

PlaybackOptions ReadPlayback(const JsonObject& o) {
  o.RejectUnknownKeys({"rigid_step", "integrator", "checkpoint_interval", "gravity",
                       "preserve_volume", "tracking", "wires", "profile_wires"});
  PlaybackOptions playback;
  playback.rigid_step = o.Number("rigid_step", playback.rigid_step);
  if (!(std::isfinite(playback.rigid_step) && playback.rigid_step > 0.0 &&
        playback.rigid_step <= 1.0))
    throw FieldError(o.PathOf("rigid_step"), "must be in (0, 1] s");
  playback.integrator = o.Keyword<RigidIntegrator>(
      "integrator", {{"rk4", RigidIntegrator::kRk4}, {"momentum", RigidIntegrator::kMomentum}},
      playback.integrator);
  const int interval = o.Integer("checkpoint_interval", 24);
  if (interval < 1) throw FieldError(o.PathOf("checkpoint_interval"), "must be at least 1");
  playback.checkpoint_interval = static_cast<std::size_t>(interval);
  playback.gravity = o.Vector3("gravity", Vec3::Zero());
  if (!IsFinite(playback.gravity)) throw FieldError(o.PathOf("gravity"), "must be finite");
  playback.preserve_volume = o.Bool("preserve_volume", playback.preserve_volume);
  if (o.Has("tracking")) playback.tracking = ReadTracking(o.Object("tracking"));
  if (o.Has("wires")) playback.wires = ReadWireDynamics(o.Object("wires"), playback.wires);
  if (o.Has("profile_wires"))
    playback.profile_wires = ReadProfileWires(o.Object("profile_wires"), playback.profile_wires);
  return playback;
}

json PlaybackToJson(const PlaybackOptions& p) {
  json out = {{"rigid_step", p.rigid_step},
              {"integrator", p.integrator == RigidIntegrator::kRk4 ? "rk4" : "momentum"},
              {"checkpoint_interval", p.checkpoint_interval},
              {"gravity", {p.gravity.x(), p.gravity.y(), p.gravity.z()}},
              {"preserve_volume", p.preserve_volume}};
  const TrackingOptions& t = p.tracking;
  if (t.frequency > 0.0)
    out["tracking"] = {{"frequency", t.frequency},
                       {"damping_ratio", t.damping_ratio},
                       {"gravity", {t.gravity.x(), t.gravity.y(), t.gravity.z()}}};
  if (p.wires.modes > 0)
    out["wires"] = {{"modes", p.wires.modes}, {"damping_ratio", p.wires.damping_ratio}};
  if (p.profile_wires.modes > 0)
    out["profile_wires"] = {{"modes", p.profile_wires.modes},
                            {"damping_ratio", p.profile_wires.damping_ratio},
                            {"frequency", p.profile_wires.frequency},
                            {"limit", p.profile_wires.limit}};
  if (!p.profile_wires.parts.empty()) out["profile_wires"]["parts"] = p.profile_wires.parts;
  return out;
}

CameraHint ReadCamera(const JsonObject& o) {
  o.RejectUnknownKeys({"target", "yaw", "pitch", "distance", "fov", "follow", "ground"});
  CameraHint camera;
  camera.target = o.Vector3("target", camera.target);
  camera.yaw = o.Number("yaw", camera.yaw);
  camera.pitch = o.Number("pitch", camera.pitch);
  camera.distance = o.Number("distance", camera.distance);
  camera.fov = o.Number("fov", camera.fov);
  if (o.Has("follow")) camera.follow = o.String("follow");
  if (o.Has("ground")) {
    camera.ground = o.Number("ground");
    if (!(std::abs(*camera.ground) < 1e6))
      throw FieldError(o.PathOf("ground"), "must be a finite height within 1e6 m");
  }
  if (!IsFinite(camera.target)) throw FieldError(o.PathOf("target"), "must be finite");
  if (!std::isfinite(camera.yaw)) throw FieldError(o.PathOf("yaw"), "must be finite");
  if (!(camera.pitch > -1.57 && camera.pitch < 1.57))
    throw FieldError(o.PathOf("pitch"), "must lie within (-pi/2, pi/2)");
  if (!(camera.distance >= 0.0 && camera.distance < 1e6))
    throw FieldError(o.PathOf("distance"), "must be 0 (frame the model) or positive, below 1e6 m");
  if (!(camera.fov > 0.01 && camera.fov < 3.0))
    throw FieldError(o.PathOf("fov"), "must lie within (0.01, 3) rad");
  return camera;
}

json CameraToJson(const CameraHint& c) {
  json out = {{"target", {c.target.x(), c.target.y(), c.target.z()}},
              {"yaw", c.yaw},
              {"pitch", c.pitch},
              {"distance", c.distance},
              {"fov", c.fov}};
  if (!c.follow.empty()) out["follow"] = c.follow;
  if (c.ground) out["ground"] = *c.ground;
  return out;
}

}  // namespace

Result<SceneDescription> ParseScene(const nlohmann::json& document,
                                    const std::filesystem::path& folder) {
  try {
    const JsonObject root(document, "");
    root.RejectUnknownKeys({"format", "version", "name", "mesh", "rig", "skin_thickness",
                            "default_kind", "parts", "playback", "clips", "camera"});
    if (root.String("format") != kFormat)
      throw FieldError("/format", std::string("must be \"") + kFormat + "\"");
    const int version = root.Integer("version", -1);
    if (version != SceneDescription::kFormatVersion)
      throw FieldError("/version", "must be 1 (this wirerig reads scene format version 1)");
    SceneDescription scene;
    scene.folder = folder;
    scene.name = root.String("name");
    scene.mesh = ReadMeshSource(root.Object("mesh"));
    scene.rig = ReadRigSource(root.Object("rig"));
    const detail::ProceduralGenerator* generator =
        detail::FindProceduralGenerator(scene.mesh.procedural);
    if (scene.rig.kind == RigSourceKind::kProcedural &&
        (generator == nullptr || !generator->describes_rig))
      throw FieldError("/rig/from",
                       "\"procedural\" needs a procedural mesh that describes its "
                       "rig (" +
                           detail::ProceduralGeneratorNames(true) + ")");
    scene.skin_thickness = root.Number("skin_thickness", scene.skin_thickness);
    if (!(std::isfinite(scene.skin_thickness) && scene.skin_thickness > 0.0))
      throw FieldError("/skin_thickness", "must be positive (m)");
    if (root.Has("default_kind")) scene.default_kind = ReadKind(root, "default_kind");
    if (root.Has("parts")) {
      const JsonObject parts = root.Object("parts");
      for (const auto& item : root.Required("parts").items())
        scene.parts[item.key()] = ReadPartSettings(parts.Object(item.key()));
    }
    if (root.Has("playback")) scene.playback = ReadPlayback(root.Object("playback"));
    std::size_t index = 0;
    ForEachElement(root, "clips", [&](const JsonObject& clip) {
      // A clip with a motion (motion_import.h) takes its duration from the motion file.
      std::optional<MotionSource> motion;
      json copy;
      if (clip.Has("motion")) {
        motion = ReadMotionSource(clip.Object("motion"));
        if (clip.Has("duration"))
          throw FieldError(clip.PathOf("duration"),
                           "a clip with a motion takes its duration from the motion (cut it "
                           "with motion/frames)");
        copy = document.at(json::json_pointer(clip.path()));
        copy.erase("motion");
        copy["duration"] = kMotionPlaceholderDuration;
      }
      RawClip raw = motion ? ReadClip(JsonObject(copy, clip.path())) : ReadClip(clip);
      if (motion) scene.motions[raw.name] = *motion;
      if (std::string error = ValidateRawClip(raw); !error.empty())
        throw FieldError(clip.path(), error);
      for (const RawClip& earlier : scene.clips)
        if (earlier.name == raw.name)
          throw FieldError(clip.path() + "/name", "another clip has this name");
      scene.clips.push_back(std::move(raw));
      ++index;
    });
    if (root.Has("camera")) scene.camera = ReadCamera(root.Object("camera"));
    return scene;
  } catch (const FieldError& e) {
    return Error{e.what()};
  } catch (const nlohmann::json::exception& e) {
    return Error{std::string("/: ") + e.what()};
  }
}

Result<SceneDescription> LoadScene(const std::filesystem::path& path) {
  Result<std::string> text = ReadInputFile(path, "scene file (JSON)");
  if (!text) return Error{text.error()};
  const Result<json> document = ParseJsonText(text.value(), path.string());
  if (!document) return Error{document.error()};
  Result<SceneDescription> scene = ParseScene(document.value(), path.parent_path());
  if (!scene) return Error{path.string() + ": " + scene.error()};
  return scene;
}

nlohmann::json SceneToJson(const SceneDescription& scene) {
  json out = {{"format", kFormat},
              {"version", SceneDescription::kFormatVersion},
              {"name", scene.name},
              {"mesh", MeshSourceToJson(scene.mesh)},
              {"rig", RigSourceToJson(scene.rig)},
              {"skin_thickness", scene.skin_thickness},
              {"default_kind", KindName(scene.default_kind)},
              {"playback", PlaybackToJson(scene.playback)}};
  if (!scene.parts.empty()) {
    json parts = json::object();
    for (const auto& [name, settings] : scene.parts) parts[name] = PartSettingsToJson(settings);
    out["parts"] = parts;
  }
  json clips = json::array();
  for (const RawClip& clip : scene.clips) {
    clips.push_back(ClipToJson(clip));
    if (const auto motion = scene.motions.find(clip.name); motion != scene.motions.end()) {
      clips.back().erase("duration");
      clips.back()["motion"] = MotionSourceToJson(motion->second);
    }
  }
  out["clips"] = clips;
  if (scene.camera) out["camera"] = CameraToJson(*scene.camera);
  return out;
}

Result<std::filesystem::path> SaveScene(const SceneDescription& scene,
                                        const std::filesystem::path& path) {
  return WriteFileAtomically(path, DumpJson(SceneToJson(scene), 2) + "\n");
}

}  // namespace wirerig
