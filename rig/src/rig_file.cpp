#include "wirerig/rig/rig_file.h"

#include "wirerig/io/json_text.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <nlohmann/json.hpp>

#include "wirerig/io/atomic_file.h"
#include "wirerig/io/input_file.h"
#include "wirerig/io/json_fields.h"
#include "wirerig/io/name_hint.h"
#include "wirerig/rig/json_physics.h"
#include "wirerig/rig/rig_description.h"

namespace wirerig {
namespace {

nlohmann::json ToJson(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json ToJson(const std::vector<Vec3>& points) {
  nlohmann::json array = nlohmann::json::array();
  for (const Vec3& p : points) array.push_back(ToJson(p));
  return array;
}

nlohmann::json ToJson(const WireProperties& wire) {
  return {{"material", MaterialToJson(wire.material)}, {"section", SectionToJson(wire.section)}};
}

WireProperties ReadWire(const JsonObject& parent, std::string_view key) {
  const JsonObject wire = parent.Object(key);
  wire.RejectUnknownKeys({"material", "section"});
  return {ReadMaterial(wire, "material"), ReadSection(wire, "section")};
}

void RequireFinite(const Vec3& v, const std::string& path) {
  if (!(std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z())))
    throw FieldError(path, "must be finite");
}

void RequireUnit(const Vec3& v, const std::string& path) {
  RequireFinite(v, path);
  if (std::abs(v.norm() - 1.0) > 1e-6) throw FieldError(path, "must be a unit vector");
}

std::size_t ReadCount(const JsonObject& object, std::string_view key) {
  const nlohmann::json& value = object.Required(key);
  if (!value.is_number_unsigned()) throw FieldError(object.PathOf(key), "must be a count");
  return value.get<std::size_t>();
}

ProfileCurve ReadProfile(const JsonObject& p) {
  p.RejectUnknownKeys({"v", "origin", "tangent", "normal", "binormal", "closed", "points", "wire"});
  ProfileCurve profile;
  profile.v = p.Number("v");
  if (!(profile.v > 0.0 && profile.v < 1.0)) throw FieldError(p.PathOf("v"), "must lie in (0, 1)");
  profile.origin = ReadVector3(p.Required("origin"), p.PathOf("origin"));
  RequireFinite(profile.origin, p.PathOf("origin"));
  profile.frame.tangent = ReadVector3(p.Required("tangent"), p.PathOf("tangent"));
  profile.frame.normal = ReadVector3(p.Required("normal"), p.PathOf("normal"));
  profile.frame.binormal = ReadVector3(p.Required("binormal"), p.PathOf("binormal"));
  RequireUnit(profile.frame.tangent, p.PathOf("tangent"));
  RequireUnit(profile.frame.normal, p.PathOf("normal"));
  RequireUnit(profile.frame.binormal, p.PathOf("binormal"));
  profile.closed = p.Bool("closed");
  profile.points = ReadVector3Array(p.Required("points"), p.PathOf("points"));
  if (profile.points.size() < 2) throw FieldError(p.PathOf("points"), "needs at least 2 points");
  for (std::size_t i = 0; i < profile.points.size(); ++i)
    RequireFinite(profile.points[i], p.PathOf("points") + "/" + std::to_string(i));
  return profile;
}

RigPart ReadPart(const JsonObject& p, const std::vector<RigPart>& earlier) {
  p.RejectUnknownKeys({"name", "parent", "attachment", "central_curve", "profile_count",
                       "points_per_profile", "profiles", "spine_points", "spine_wire", "joint",
                       "skin"});
  RigPart part;
  part.name = p.String("name");
  if (part.name.empty()) throw FieldError(p.PathOf("name"), "must not be empty");
  for (const RigPart& other : earlier)
    if (other.name == part.name) throw FieldError(p.PathOf("name"), "is used twice");
  if (!p.Required("parent").is_null()) {
    const std::string parent = p.String("parent");
    for (std::size_t i = 0; i < earlier.size(); ++i)
      if (earlier[i].name == parent) part.parent = int(i);
    if (part.parent < 0) {
      std::vector<std::string> names;
      for (const RigPart& other : earlier) names.push_back(other.name);
      throw FieldError(p.PathOf("parent"), "'" + parent + "' is not an earlier part" +
                                               NameHint(parent, names, "parts"));
    }
  } else if (!earlier.empty()) {
    throw FieldError(p.PathOf("parent"), "only the first part may be a root");
  }
  part.attachment = p.Number("attachment");
  if (!(part.attachment >= 0.0 && part.attachment <= 1.0))
    throw FieldError(p.PathOf("attachment"), "must lie in [0, 1]");
  part.central_curve = ReadVector3Array(p.Required("central_curve"), p.PathOf("central_curve"));
  if (part.central_curve.size() < 2)
    throw FieldError(p.PathOf("central_curve"), "needs at least 2 points");
  part.skin = p.Bool("skin", true);
  if (part.skin) {
    part.profile_count = p.Integer("profile_count", 0);
    part.points_per_profile = p.Integer("points_per_profile", 0);
    if (part.profile_count < 2) throw FieldError(p.PathOf("profile_count"), "must be at least 2");
    if (part.points_per_profile < 3)
      throw FieldError(p.PathOf("points_per_profile"), "must be at least 3");
    RequireArray(p.Required("profiles"), p.PathOf("profiles"));
    ForEachElement(p, "profiles", [&](const JsonObject& profile) {
      part.profiles.push_back(ReadProfile(profile));
      part.profile_wires.push_back(ReadWire(profile, "wire"));
    });
  } else {
    // A skinless bone: no profiles; its spine is its 2-point bone.
    if (earlier.empty()) throw FieldError(p.PathOf("skin"), "the root part must have skin");
    for (const char* key : {"profile_count", "points_per_profile", "profiles"})
      if (p.Has(key)) throw FieldError(p.PathOf(key), "a skinless part (\"skin\": false) has none");
  }
  part.spine_points = ReadVector3Array(p.Required("spine_points"), p.PathOf("spine_points"));
  if (part.skin && (part.spine_points.size() != part.profiles.size() || part.profiles.size() < 2))
    throw FieldError(p.PathOf("spine_points"), "needs one point per profile, at least 2");
  if (!part.skin && (part.spine_points.size() != 2 ||
                     (part.spine_points[1] - part.spine_points[0]).norm() <= 0.0))
    throw FieldError(p.PathOf("spine_points"), "a skinless part's bone is 2 distinct points");
  for (std::size_t i = 0; i < part.spine_points.size(); ++i)
    RequireFinite(part.spine_points[i], p.PathOf("spine_points") + "/" + std::to_string(i));
  part.spine_wire = ReadWire(p, "spine_wire");
  part.joint = ReadJointDescription(p);
  return part;
}

}  // namespace

nlohmann::json RigToJson(const Rig& rig) {
  nlohmann::json mesh = {
      {"path", rig.mesh}, {"vertices", rig.mesh_vertices}, {"triangles", rig.mesh_triangles}};
  if (rig.import.up_axis) mesh["up_axis"] = ToString(*rig.import.up_axis);
  if (rig.import.unit_scale) mesh["unit_scale"] = *rig.import.unit_scale;
  nlohmann::json parts = nlohmann::json::array();
  for (const RigPart& part : rig.parts) {
    nlohmann::json profiles = nlohmann::json::array();
    for (std::size_t k = 0; k < part.profiles.size(); ++k) {
      const ProfileCurve& p = part.profiles[k];
      profiles.push_back({{"v", p.v},
                          {"origin", ToJson(p.origin)},
                          {"tangent", ToJson(p.frame.tangent)},
                          {"normal", ToJson(p.frame.normal)},
                          {"binormal", ToJson(p.frame.binormal)},
                          {"closed", p.closed},
                          {"points", ToJson(p.points)},
                          {"wire", ToJson(part.profile_wires[k])}});
    }
    nlohmann::json out = {{"name", part.name},
                          {"parent", part.parent >= 0 ? nlohmann::json(rig.parts[part.parent].name)
                                                      : nlohmann::json(nullptr)},
                          {"attachment", part.attachment},
                          {"central_curve", ToJson(part.central_curve)},
                          {"spine_points", ToJson(part.spine_points)},
                          {"spine_wire", ToJson(part.spine_wire)},
                          {"joint", WriteJointDescription(part.joint)}};
    if (part.skin) {
      out["profile_count"] = part.profile_count;
      out["points_per_profile"] = part.points_per_profile;
      out["profiles"] = std::move(profiles);
    } else {
      out["skin"] = false;
    }
    parts.push_back(std::move(out));
  }
  return {{"format", "wirerig.rig"},
          {"version", Rig::kFormatVersion},
          {"mesh", std::move(mesh)},
          {"parts", std::move(parts)},
          {"vertex_part", rig.vertex_part}};
}

Result<Rig> RigFromJson(const nlohmann::json& document) {
  try {
    const JsonObject root(document, "");
    // The format first: another kind of file (a scene) is named as such, not by its fields.
    if (root.String("format") != "wirerig.rig")
      throw FieldError("/format", "must be \"wirerig.rig\"");
    root.RejectUnknownKeys({"format", "version", "mesh", "parts", "vertex_part"});
    if (root.Integer("version", -1) != Rig::kFormatVersion)
      throw FieldError("/version", "unsupported version (this build reads version 1)");
    Rig rig;
    const JsonObject mesh = root.Object("mesh");
    mesh.RejectUnknownKeys({"path", "vertices", "triangles", "up_axis", "unit_scale"});
    rig.mesh = mesh.String("path");
    rig.mesh_vertices = ReadCount(mesh, "vertices");
    rig.mesh_triangles = ReadCount(mesh, "triangles");
    if (mesh.Has("up_axis")) {
      UpAxis axis;
      if (!ParseUpAxis(mesh.String("up_axis"), &axis))
        throw FieldError(mesh.PathOf("up_axis"), "must be \"x\", \"y\" or \"z\"");
      rig.import.up_axis = axis;
    }
    if (mesh.Has("unit_scale")) {
      const double scale = mesh.Number("unit_scale");
      if (!(std::isfinite(scale) && scale > 0.0))
        throw FieldError(mesh.PathOf("unit_scale"), "must be positive and finite");
      rig.import.unit_scale = scale;
    }
    if (RequireArray(root.Required("parts"), "/parts").size() > kMaxRigParts)
      throw FieldError("/parts", "at most " + std::to_string(kMaxRigParts) + " parts");
    ForEachElement(root, "parts",
                   [&](const JsonObject& p) { rig.parts.push_back(ReadPart(p, rig.parts)); });
    if (rig.parts.empty()) throw FieldError("/parts", "needs at least one part");
    for (std::size_t i = 0; i < rig.parts.size(); ++i)
      if (!rig.parts[i].skin &&
          std::none_of(rig.parts.begin(), rig.parts.end(),
                       [&](const RigPart& other) { return other.parent == int(i); }))
        throw FieldError("/parts/" + std::to_string(i) + "/skin", "a skinless part needs a child");
    const nlohmann::json& vertex_part = RequireArray(root.Required("vertex_part"), "/vertex_part");
    if (vertex_part.size() != rig.mesh_vertices)
      throw FieldError("/vertex_part", "needs one entry per mesh vertex (" +
                                           std::to_string(rig.mesh_vertices) + ")");
    for (std::size_t i = 0; i < vertex_part.size(); ++i) {
      if (!vertex_part[i].is_number_integer() || vertex_part[i].get<long long>() < 0 ||
          vertex_part[i].get<long long>() >= static_cast<long long>(rig.parts.size()))
        throw FieldError("/vertex_part/" + std::to_string(i), "must be a part index");
      if (!rig.parts[vertex_part[i].get<std::size_t>()].skin)
        throw FieldError("/vertex_part/" + std::to_string(i), "names a skinless part");
      rig.vertex_part.push_back(vertex_part[i].get<int>());
    }
    return rig;
  } catch (const FieldError& e) {
    return Error{e.what()};
  }
}

Result<std::filesystem::path> SaveRig(const Rig& rig, const std::filesystem::path& path) {
  return WriteFileAtomically(path, DumpJson(RigToJson(rig), 1) + "\n");
}

Result<Rig> LoadRig(const std::filesystem::path& path) {
  Result<std::string> text = ReadInputFile(path, "rig file (JSON)");
  if (!text) return Error{text.error()};
  const Result<nlohmann::json> document = ParseJsonText(text.value(), path.string());
  if (!document) return Error{document.error()};
  Result<Rig> rig = RigFromJson(document.value());
  if (!rig) return Error{path.string() + ": " + rig.error()};
  return rig;
}

}  // namespace wirerig
