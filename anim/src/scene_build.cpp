// BuildScene: from a scene description to a mesh, rig, runtime model and built clips.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "wirerig/anim/scene.h"
#include "wirerig/rig/automatic_description.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/mesh_subdivision.h"
#include "wirerig/rig/name_hint.h"
#include "wirerig/rig/procedural_mesh.h"
#include "wirerig/rig/procedural_octopus.h"
#include "wirerig/rig/procedural_props.h"
#include "wirerig/rig/rig_file.h"
#include "wirerig/rig/rig_model_builder.h"

namespace wirerig {
namespace {

std::filesystem::path Resolve(const SceneDescription& scene, const std::filesystem::path& p) {
  return p.is_absolute() ? p : scene.folder / p;
}

double Parameter(const MeshSource& source, const std::string& name, double fallback) {
  const auto it = source.parameters.find(name);
  return it == source.parameters.end() ? fallback : it->second;
}

// A parameter that must be a positive length (m) or a count in [lo, hi].
std::string CheckLength(double value, const char* name) {
  if (std::isfinite(value) && value > 0.0 && value < 1e6) return {};
  return std::string("/mesh/parameters/") + name + ": must be a positive length (m)";
}
std::string CheckCount(double value, const char* name, double lo, double hi) {
  if (value >= lo && value <= hi && value == std::floor(value)) return {};
  return std::string("/mesh/parameters/") + name + ": must be a whole number in [" +
         std::to_string(int(lo)) + ", " + std::to_string(int(hi)) + "]";
}

// A procedural mesh's material: one matte colour per generator (linear RGB), so exports and
// engines show it as the sample means it rather than as their default grey.
MeshMaterial ProceduralMaterial(const std::string& generator) {
  static const std::pair<const char*, Vec4> kColors[] = {
      {"octopus", Vec4(0.62, 0.16, 0.09, 1.0)}, {"candles", Vec4(0.85, 0.78, 0.60, 1.0)},
      {"trunk", Vec4(0.23, 0.13, 0.06, 1.0)},   {"lamp_post", Vec4(0.05, 0.06, 0.06, 1.0)},
      {"chair", Vec4(0.40, 0.22, 0.10, 1.0)},   {"beam", Vec4(0.50, 0.52, 0.55, 1.0)},
  };
  MeshMaterial material;
  material.name = generator;
  material.base_color = Vec4(0.60, 0.60, 0.62, 1.0);  // shapes: a light clay
  for (const auto& [name, color] : kColors)
    if (generator == name) material.base_color = color;
  return material;
}

struct Generated {
  Mesh mesh;
  RigDescription description;  // the generator's own (octopus and the props)
};

// A generator of rig/procedural_props.h: lengths (m) and counts by name over its defaults,
// then the generator, which checks them (its error names the parameter).
template <typename Parameters>
Result<Generated> GenerateProp(
    const MeshSource& source, Parameters parameters,
    std::initializer_list<std::pair<const char*, double Parameters::*>> lengths,
    std::initializer_list<std::pair<const char*, int Parameters::*>> counts,
    Result<ProceduralRigSource> (*make)(const Parameters&)) {
  for (auto [name, field] : lengths) parameters.*field = Parameter(source, name, parameters.*field);
  for (auto [name, field] : counts) {
    const double value = Parameter(source, name, parameters.*field);
    if (std::string e = CheckCount(value, name, 1, 4096); !e.empty()) return Error{e};
    parameters.*field = static_cast<int>(value);
  }
  Result<ProceduralRigSource> made = make(parameters);
  if (!made) return Error{"/mesh/parameters/" + made.error()};
  return Generated{std::move(made.value().mesh), std::move(made.value().description)};
}

Result<Generated> Generate(const MeshSource& source) {
  auto p = [&](const char* name, double fallback) { return Parameter(source, name, fallback); };
  Generated out;
  std::string error;
  auto first_error = [&](std::initializer_list<std::string> errors) {
    for (const std::string& e : errors)
      if (!e.empty()) return e;
    return std::string();
  };
  if (source.procedural == "octopus") {
    OctopusParameters o;
    o.mantle_radius = p("mantle_radius", o.mantle_radius);
    o.mantle_height = p("mantle_height", o.mantle_height);
    o.tentacle_length = p("tentacle_length", o.tentacle_length);
    o.tentacle_radius = p("tentacle_radius", o.tentacle_radius);
    o.tip_radius = p("tip_radius", o.tip_radius);
    o.spread = p("spread", o.spread);
    for (auto [name, field] :
         {std::pair{"tentacle_count", &o.tentacle_count},
          std::pair{"radial_segments", &o.radial_segments}, std::pair{"rings", &o.rings},
          std::pair{"profile_count", &o.profile_count},
          std::pair{"points_per_profile", &o.points_per_profile}}) {
      const double value = p(name, *field);
      if (std::string e = CheckCount(value, name, 1, 4096); !e.empty()) return Error{e};
      *field = static_cast<int>(value);
    }
    Result<ProceduralRigSource> octopus = MakeOctopus(o);
    if (!octopus) return Error{"/mesh/parameters/" + octopus.error()};
    out.mesh = std::move(octopus.value().mesh);
    out.description = std::move(octopus.value().description);
    return out;
  }
  if (source.procedural == "candles") {
    using P = CandleRowParameters;
    return GenerateProp<P>(
        source, {}, {{"radius", &P::radius}, {"height", &P::height}, {"spacing", &P::spacing}},
        {{"count", &P::count},
         {"radial_segments", &P::radial_segments},
         {"height_segments", &P::height_segments},
         {"profile_count", &P::profile_count},
         {"points_per_profile", &P::points_per_profile}},
        &MakeCandleRow);
  }
  if (source.procedural == "beam") {
    using P = BeamParameters;
    return GenerateProp<P>(source, {}, {{"length", &P::length}, {"radius", &P::radius}},
                           {{"radial_segments", &P::radial_segments},
                            {"rings", &P::rings},
                            {"profile_count", &P::profile_count},
                            {"points_per_profile", &P::points_per_profile}},
                           &MakeBeam);
  }
  if (source.procedural == "trunk") {
    using P = TrunkParameters;
    return GenerateProp<P>(source, {},
                           {{"height", &P::height},
                            {"base_radius", &P::base_radius},
                            {"top_radius", &P::top_radius},
                            {"flare", &P::flare}},
                           {{"radial_segments", &P::radial_segments},
                            {"rings", &P::rings},
                            {"profile_count", &P::profile_count},
                            {"points_per_profile", &P::points_per_profile}},
                           &MakeTrunk);
  }
  if (source.procedural == "lamp_post") {
    using P = LampPostParameters;
    return GenerateProp<P>(source, {},
                           {{"height", &P::height},
                            {"pole_radius", &P::pole_radius},
                            {"base_radius", &P::base_radius},
                            {"base_height", &P::base_height},
                            {"lantern_radius", &P::lantern_radius},
                            {"lantern_height", &P::lantern_height}},
                           {{"radial_segments", &P::radial_segments},
                            {"rings", &P::rings},
                            {"profile_count", &P::profile_count},
                            {"points_per_profile", &P::points_per_profile}},
                           &MakeLampPost);
  }
  if (source.procedural == "chair") {
    using P = ChairParameters;
    return GenerateProp<P>(source, {},
                           {{"seat_width", &P::seat_width},
                            {"seat_depth", &P::seat_depth},
                            {"seat_height", &P::seat_height},
                            {"seat_thickness", &P::seat_thickness},
                            {"leg_radius", &P::leg_radius},
                            {"back_height", &P::back_height},
                            {"back_thickness", &P::back_thickness}},
                           {{"radial_segments", &P::radial_segments},
                            {"rings", &P::rings},
                            {"profile_count", &P::profile_count},
                            {"points_per_profile", &P::points_per_profile}},
                           &MakeChair);
  }
  const double radial = p("radial_segments", 32), height_segments = p("height_segments", 16);
  if (source.procedural == "cylinder") {
    error = first_error({CheckLength(p("radius", 0.1), "radius"),
                         CheckLength(p("height", 1.0), "height"),
                         CheckCount(radial, "radial_segments", 3, 4096),
                         CheckCount(height_segments, "height_segments", 1, 4096)});
    if (error.empty())
      out.mesh =
          MakeCylinder(p("radius", 0.1), p("height", 1.0), int(radial), int(height_segments));
  } else if (source.procedural == "cone") {
    const double r0 = p("r0", 0.1), r1 = p("r1", 0.05);
    error = first_error({CheckLength(r0, "r0"), r1 == 0.0 ? std::string() : CheckLength(r1, "r1"),
                         CheckLength(p("height", 1.0), "height"),
                         CheckCount(radial, "radial_segments", 3, 4096),
                         CheckCount(height_segments, "height_segments", 1, 4096)});
    if (error.empty())
      out.mesh = MakeCone(r0, r1, p("height", 1.0), int(radial), int(height_segments));
  } else if (source.procedural == "capsule") {
    const double height = p("height", 1.0), rings = p("cap_rings", 8);
    error = first_error({CheckLength(p("radius", 0.1), "radius"),
                         height == 0.0 ? std::string() : CheckLength(height, "height"),
                         CheckCount(radial, "radial_segments", 3, 4096),
                         CheckCount(height_segments, "height_segments", 1, 4096),
                         CheckCount(rings, "cap_rings", 1, 4096)});
    if (error.empty())
      out.mesh =
          MakeCapsule(p("radius", 0.1), height, int(radial), int(height_segments), int(rings));
  } else if (source.procedural == "torus") {
    const double major = p("major_radius", 0.5), minor = p("minor_radius", 0.1);
    const double rings = p("ring_segments", 48), tube = p("tube_segments", 24);
    error = first_error({CheckLength(major, "major_radius"), CheckLength(minor, "minor_radius"),
                         minor < major ? std::string()
                                       : std::string("/mesh/parameters/minor_radius: must be "
                                                     "below major_radius"),
                         CheckCount(rings, "ring_segments", 3, 4096),
                         CheckCount(tube, "tube_segments", 3, 4096)});
    if (error.empty()) out.mesh = MakeTorus(major, minor, int(rings), int(tube));
  } else {
    error = "/mesh/procedural: unknown generator";
  }
  if (!error.empty()) return Error{error};
  return out;
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

}  // namespace

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
    Result<Generated> generated = Generate(scene.mesh);
    if (!generated) return fail(generated.error());
    out.mesh = std::move(generated.value().mesh);
    if (out.mesh.materials.empty()) {
      out.mesh.materials.push_back(ProceduralMaterial(scene.mesh.procedural));
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
  if (std::string e = ApplyWireSettings(scene, out.rig); !e.empty()) return fail(e);

  // The runtime model, with each part's spine kind.
  RigModelOptions model_options;
  model_options.spine_kind = scene.default_kind;
  Result<BuiltRigModel> model = BuildRigModel(out.mesh, out.rig, model_options);
  if (!model) return fail(model.error());
  out.model = std::move(model.value().model);
  for (PartModel& part : out.model.parts) {
    const auto settings = scene.parts.find(part.name);
    if (settings != scene.parts.end() && settings->second.kind) part.kind = *settings->second.kind;
  }

  if (scene.camera && !scene.camera->follow.empty()) {
    const auto& parts = out.model.parts;
    if (std::none_of(parts.begin(), parts.end(),
                     [&](const PartModel& p) { return p.name == scene.camera->follow; })) {
      return fail("/camera/follow: the rig has no part named \"" + scene.camera->follow + "\"" +
                  NameHint(scene.camera->follow, PartNames(out.rig), "parts"));
    }
  }

  // The clips, against the model.
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
      if (!made) {
        const std::string& e = made.error();
        return fail(clip_path + (e.starts_with("/") ? "" : "/motion/") + e);
      }
      raw = std::move(made).value();
    }
    Result<Clip> clip =
        BuildClip(scene.motions.contains(scene.clips[i].name) ? raw : scene.clips[i], out.model);
    if (!clip) return fail(clip_path + ": " + clip.error());
    out.clips.push_back(std::move(clip).value());
  }
  return out;
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
