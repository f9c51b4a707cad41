// Rig files: versioned JSON ("format": "wirerig.rig", "version": 1). Loading validates every
// field and reports errors with their JSON pointer; saving writes atomically; a saved rig loads
// back exactly (doubles are written with round-trip precision).
#pragma once

#include <filesystem>

#include <nlohmann/json_fwd.hpp>

#include "wirerig/io/result.h"
#include "wirerig/rig/rig.h"

namespace wirerig {

nlohmann::json RigToJson(const Rig& rig);
// Errors read "<json pointer>: <reason>".
Result<Rig> RigFromJson(const nlohmann::json& document);

Result<std::filesystem::path> SaveRig(const Rig& rig, const std::filesystem::path& path);
// Errors read "<path>: <json pointer>: <reason>".
Result<Rig> LoadRig(const std::filesystem::path& path);

}  // namespace wirerig
