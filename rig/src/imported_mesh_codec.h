// A simple binary form of an ImportedMesh, for sending one between processes of the same
// build (isolated_import.h): native byte order, no versioning. Decoding checks every count
// against the bytes left, so a short or damaged message is refused, never over-read.
#pragma once

#include <string>
#include <string_view>

#include "wirerig/io/result.h"
#include "wirerig/rig/mesh_import.h"

namespace wirerig {

std::string EncodeImportedMesh(const ImportedMesh& imported);

// Errors: "truncated or damaged mesh message (<what>)".
Result<ImportedMesh> DecodeImportedMesh(std::string_view bytes);

}  // namespace wirerig
