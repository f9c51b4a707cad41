// ImportMesh in a forked child process (isolated_process.h): the child imports with the same
// options (isolation off) and sends back the mesh (imported_mesh_codec.h) or the error.
#pragma once

#include <filesystem>

#include "wirerig/io/result.h"
#include "wirerig/rig/mesh_import.h"

namespace wirerig {

// `options.isolation` must be set. Errors name the file (RunIsolated's, or ImportMesh's own).
Result<ImportedMesh> ImportMeshIsolated(const std::filesystem::path& path,
                                        const ImportOptions& options);

}  // namespace wirerig
