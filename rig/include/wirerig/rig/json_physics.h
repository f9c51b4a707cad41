// JSON forms of materials and sections, shared by every wirerig file format.
//   material: a preset name ("steel") or {"E": Pa, "nu": -, "density": kg/m^3 (optional)}
//   section:  exactly one of {"A": m^2, "I": m^4, "kind": "custom"|"strip"|"tube" (optional)},
//             {"strip": {"b": m, "h": m}} or {"tube": {"r": m, "h": m}}
// Readers throw FieldError (json_fields.h) naming the field; writers produce forms the
// readers read back exactly.
#pragma once

#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "wirerig/io/json_fields.h"
#include "wirerig/runtime/material.h"
#include "wirerig/runtime/section.h"

namespace wirerig {

Material ReadMaterial(const JsonObject& parent, std::string_view key);
Section ReadSection(const JsonObject& parent, std::string_view key);

nlohmann::json MaterialToJson(const Material& material);
// Writes {"A", "I", "kind"}: exact, whatever the section was made from.
nlohmann::json SectionToJson(const Section& section);

// Throws FieldError(path, reason) when `status` is not ok; `path` prefixes the status's field.
void ThrowIfInvalid(const Status& status, const std::string& path);

}  // namespace wirerig
