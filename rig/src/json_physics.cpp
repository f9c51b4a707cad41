#include "wirerig/rig/json_physics.h"

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "wirerig/io/name_hint.h"

namespace wirerig {
namespace {

constexpr std::string_view kKindNames[] = {"custom", "strip", "tube"};

}  // namespace

void ThrowIfInvalid(const Status& status, const std::string& path) {
  if (status) return;
  std::string full = path;
  if (!status.field.empty()) full.append("/").append(status.field);
  throw FieldError(full, std::string(status.reason));
}

Material ReadMaterial(const JsonObject& parent, std::string_view key) {
  const nlohmann::json& value = parent.Required(key);
  if (value.is_string()) {
    const std::string name = value.get<std::string>();
    const Material* preset = FindMaterialPreset(name);
    if (!preset) {
      std::vector<std::string> names;
      for (const MaterialPreset& known : MaterialPresets()) names.emplace_back(known.name);
      throw FieldError(parent.PathOf(key),
                       "unknown material preset '" + name + "'" + NameHint(name, names, "presets"));
    }
    return *preset;
  }
  const JsonObject m = parent.Object(key);
  m.RejectUnknownKeys({"E", "nu", "density"});
  const Material material{m.Number("E"), m.Number("nu"), m.Number("density", 0.0)};
  ThrowIfInvalid(ValidateMaterial(material), m.path());
  return material;
}

Section ReadSection(const JsonObject& parent, std::string_view key) {
  const JsonObject s = parent.Object(key);
  s.RejectUnknownKeys({"A", "I", "kind", "strip", "tube"});
  const int kinds = int(s.Has("strip")) + int(s.Has("tube")) + int(s.Has("A") || s.Has("I"));
  if (kinds != 1)
    throw FieldError(s.path(), "needs exactly one of {A, I}, {strip: {b, h}} or {tube: {r, h}}");
  if (s.Has("strip")) {
    const JsonObject strip = s.Object("strip");
    strip.RejectUnknownKeys({"b", "h"});
    const double b = strip.Number("b"), h = strip.Number("h");
    ThrowIfInvalid(ValidateStrip(b, h), strip.path());
    return StripSection(b, h);
  }
  if (s.Has("tube")) {
    const JsonObject tube = s.Object("tube");
    tube.RejectUnknownKeys({"r", "h"});
    const double r = tube.Number("r"), h = tube.Number("h");
    ThrowIfInvalid(ValidateTube(r, h), tube.path());
    return TubeSection(r, h);
  }
  Section section = CustomSection(s.Number("A"), s.Number("I"));
  if (s.Has("kind")) {
    const std::string kind = s.String("kind");
    int index = 0;
    while (index < 3 && kKindNames[index] != kind) ++index;
    if (index == 3) throw FieldError(s.PathOf("kind"), "must be custom, strip or tube");
    section.kind = static_cast<SectionKind>(index);
  }
  ThrowIfInvalid(ValidateSection(section), s.path());
  return section;
}

nlohmann::json MaterialToJson(const Material& material) {
  return {{"E", material.youngs_modulus},
          {"nu", material.poisson_ratio},
          {"density", material.density}};
}

nlohmann::json SectionToJson(const Section& section) {
  return {{"A", section.area},
          {"I", section.second_moment},
          {"kind", kKindNames[static_cast<int>(section.kind)]}};
}

}  // namespace wirerig
