#include "wirerig/rig/rig_description.h"

#include "wirerig/io/json_text.h"
#include "wirerig/io/name_hint.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "wirerig/io/input_file.h"
#include "wirerig/io/json_fields.h"
#include "wirerig/rig/json_physics.h"

namespace wirerig {
namespace {

constexpr int kMaxPointsPerProfile = 1024;
constexpr int kMaxProfiles = 4096;

std::vector<std::string> ReadNames(const JsonObject& object, std::string_view key) {
  std::vector<std::string> names;
  if (!object.Has(key)) return names;
  const nlohmann::json& array = RequireArray(object.Required(key), object.PathOf(key));
  for (std::size_t i = 0; i < array.size(); ++i) {
    if (!array[i].is_string())
      throw FieldError(object.PathOf(key) + "/" + std::to_string(i), "must be a string");
    names.push_back(array[i].get<std::string>());
  }
  return names;
}

PartDescription ReadPart(const JsonObject& p, const PartDescription& defaults) {
  p.RejectUnknownKeys({"name", "central_curve", "profile_count", "points_per_profile", "parent",
                       "mesh_parts", "joint", "skin"});
  PartDescription part = defaults;
  part.name = p.String("name");
  part.central_curve = ReadVector3Array(p.Required("central_curve"), p.PathOf("central_curve"));
  part.skin = p.Bool("skin", true);
  if (part.skin) {
    part.profile_count = p.Integer("profile_count", defaults.profile_count);
    part.points_per_profile = p.Integer("points_per_profile", defaults.points_per_profile);
  } else {
    // A bone with no skin: nothing to cast profiles for (the defaults do not apply).
    for (const char* key : {"profile_count", "points_per_profile", "mesh_parts"})
      if (p.Has(key)) throw FieldError(p.PathOf(key), "a skinless part (\"skin\": false) has none");
    part.profile_count = part.points_per_profile = 0;
  }
  if (p.Has("parent") && !p.Required("parent").is_null()) part.parent = p.String("parent");
  part.mesh_parts = ReadNames(p, "mesh_parts");
  part.joint = ReadJointDescription(p);
  return part;
}

// "a -> b -> a" when following parents from part `start` comes back to a part already
// visited; empty otherwise (a missing parent ends the walk).
std::string ParentCycle(const RigDescription& description, std::size_t start) {
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < description.parts.size(); ++i)
    index.emplace(description.parts[i].name, i);
  std::vector<std::size_t> path{start};
  for (;;) {
    const auto parent = index.find(description.parts[path.back()].parent);
    if (parent == index.end()) return {};
    const std::size_t seen =
        std::size_t(std::find(path.begin(), path.end(), parent->second) - path.begin());
    path.push_back(parent->second);
    if (seen + 1 < path.size()) {
      std::string text;
      for (std::size_t k = seen; k < path.size(); ++k)
        text += (text.empty() ? "" : " -> ") + description.parts[path[k]].name;
      return text;
    }
  }
}

// Part i's profile counts, or what makes it a bad skinless part: "/<field>: <reason>", empty
// when valid.
std::string ValidateSkin(const RigDescription& description, std::size_t i) {
  const PartDescription& part = description.parts[i];
  if (part.skin) {
    if (part.profile_count < 2 || part.profile_count > kMaxProfiles)
      return "/profile_count: must lie in [2, 4096]";
    if (part.points_per_profile < 3 || part.points_per_profile > kMaxPointsPerProfile)
      return "/points_per_profile: must lie in [3, 1024]";
    return {};
  }
  if (part.profile_count != 0 || part.points_per_profile != 0)
    return "/profile_count: a skinless part (\"skin\": false) has no profiles";
  if (!part.mesh_parts.empty())
    return "/mesh_parts: a skinless part (\"skin\": false) owns no mesh parts";
  if (part.central_curve.size() != 2)
    return "/central_curve: a skinless part's bone is 2 points (its joint, then its end)";
  if (i == 0) return "/skin: the root part must have skin";
  const bool has_child =
      std::any_of(description.parts.begin(), description.parts.end(),
                  [&](const PartDescription& other) { return other.parent == part.name; });
  if (!has_child)
    return "/skin: a skinless part needs a child (a bone with no skin and nothing hanging from "
           "it moves nothing)";
  return {};
}

}  // namespace

Result<RigDescription> ParseRigDescription(const nlohmann::json& document) {
  try {
    const JsonObject root(document, "");
    // The format first: another kind of file (a scene) is named as such, not by its fields.
    if (root.Has("format") && root.String("format") != "wirerig.rig_description")
      throw FieldError("/format", "must be \"wirerig.rig_description\"");
    root.RejectUnknownKeys({"format", "version", "mesh", "up_axis", "unit_scale", "material",
                            "defaults", "parts", "passive_mesh_parts", "clean_assignment"});
    if (root.Integer("version", 1) != 1) throw FieldError("/version", "unsupported version");
    RigDescription description;
    if (root.Has("mesh")) description.mesh = root.String("mesh");
    if (root.Has("up_axis")) {
      UpAxis axis;
      const std::string name = root.String("up_axis");
      if (!ParseUpAxis(name, &axis)) throw FieldError("/up_axis", "must be \"x\", \"y\" or \"z\"");
      description.import.up_axis = axis;
    }
    if (root.Has("unit_scale")) {
      const double scale = root.Number("unit_scale");
      if (!(std::isfinite(scale) && scale > 0.0))
        throw FieldError("/unit_scale", "must be positive and finite (metres per unit)");
      description.import.unit_scale = scale;
    }
    if (root.Has("material")) description.material = ReadMaterial(root, "material");
    PartDescription defaults;
    if (root.Has("defaults")) {
      const JsonObject d = root.Object("defaults");
      d.RejectUnknownKeys({"profile_count", "points_per_profile"});
      defaults.profile_count = d.Integer("profile_count", defaults.profile_count);
      defaults.points_per_profile = d.Integer("points_per_profile", defaults.points_per_profile);
      // Judged here, where they are written, even when every part sets its own.
      if (defaults.profile_count < 2 || defaults.profile_count > kMaxProfiles)
        throw FieldError("/defaults/profile_count", "must lie in [2, 4096]");
      if (defaults.points_per_profile < 3 || defaults.points_per_profile > kMaxPointsPerProfile)
        throw FieldError("/defaults/points_per_profile", "must lie in [3, 1024]");
    }
    description.passive_mesh_parts = ReadNames(root, "passive_mesh_parts");
    description.clean_assignment = root.Bool("clean_assignment", false);
    if (RequireArray(root.Required("parts"), "/parts").size() > kMaxRigParts)
      throw FieldError("/parts", "at most " + std::to_string(kMaxRigParts) + " parts");
    ForEachElement(root, "parts", [&](const JsonObject& p) {
      description.parts.push_back(ReadPart(p, defaults));
    });
    if (std::string error = ValidateRigDescription(description); !error.empty())
      return Error{error};
    return description;
  } catch (const FieldError& e) {
    return Error{e.what()};
  }
}

Result<RigDescription> LoadRigDescription(const std::filesystem::path& path) {
  Result<std::string> text = ReadInputFile(path, "rig description (JSON)");
  if (!text) return Error{text.error()};
  const Result<nlohmann::json> document = ParseJsonText(text.value(), path.string());
  if (!document) return Error{document.error()};
  Result<RigDescription> description = ParseRigDescription(document.value());
  if (!description) return Error{path.string() + ": " + description.error()};
  if (!description.value().mesh.empty() && description.value().mesh.is_relative())
    description.value().mesh = path.parent_path() / description.value().mesh;
  return description;
}

std::string ValidateRigDescription(const RigDescription& description) {
  if (Status s = ValidateMaterial(description.material); !s)
    return "/material/" + std::string(s.field) + ": " + std::string(s.reason);
  if (description.parts.empty()) return "/parts: needs at least one part";
  // Checked here, not only when a file is parsed: a skeleton's bones become parts too.
  if (description.parts.size() > kMaxRigParts)
    return "/parts: at most " + std::to_string(kMaxRigParts) + " parts (this rig has " +
           std::to_string(description.parts.size()) + ")";
  // The profile curves' rays, all parts together (each part is bounded alone as well).
  std::size_t profile_points = 0;
  for (const PartDescription& part : description.parts)
    profile_points += std::size_t(std::max(part.profile_count, 0)) *
                      std::size_t(std::max(part.points_per_profile, 0));
  if (profile_points > kMaxRigProfilePoints)
    return "/parts: " + std::to_string(profile_points) +
           " profile points in all (profile_count x points_per_profile, summed over the parts); "
           "at most " +
           std::to_string(kMaxRigProfilePoints);
  std::set<std::string> seen;
  for (std::size_t i = 0; i < description.parts.size(); ++i) {
    const PartDescription& part = description.parts[i];
    const std::string path = "/parts/" + std::to_string(i);
    if (part.name.empty()) return path + "/name: must not be empty";
    if (!seen.insert(part.name).second) return path + "/name: '" + part.name + "' is used twice";
    if (part.central_curve.size() < 2) return path + "/central_curve: needs at least 2 points";
    for (std::size_t k = 0; k < part.central_curve.size(); ++k) {
      const Vec3& p = part.central_curve[k];
      if (!(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z())))
        return path + "/central_curve/" + std::to_string(k) + ": must be finite";
      if (k > 0 && (p - part.central_curve[k - 1]).norm() <= 0.0)
        return path + "/central_curve/" + std::to_string(k) + ": repeats the previous point";
    }
    if (std::string error = ValidateSkin(description, i); !error.empty()) return path + error;
    if (i == 0 && !part.parent.empty()) return path + "/parent: the first part is the root";
    if (i > 0 && part.parent.empty()) return path + "/parent: only the first part may be a root";
    if (part.parent == part.name) return path + "/parent: a part cannot be its own parent";
    if (i > 0 && !seen.contains(part.parent)) {
      if (std::string cycle = ParentCycle(description, i); !cycle.empty())
        return path + "/parent: the chain has a cycle: " + cycle;
      std::vector<std::string> names;
      for (std::size_t e = 0; e < i; ++e) names.push_back(description.parts[e].name);
      return path + "/parent: '" + part.parent + "' is not an earlier part" +
             NameHint(part.parent, names, "parts");
    }
    if (std::string error = ValidateJointDescription(part.joint); !error.empty())
      return path + "/joint/" + error;
  }
  for (int p : description.vertex_part) {
    if (p < -1 || p >= static_cast<int>(description.parts.size()))
      return "/vertex_part: names a part that does not exist";
    if (p >= 0 && !description.parts[std::size_t(p)].skin)
      return "/vertex_part: gives vertices to skinless part '" +
             description.parts[std::size_t(p)].name + "'";
  }
  return {};
}

}  // namespace wirerig
