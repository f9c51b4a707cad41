// ImportMesh in a forked child process (ImportIsolation in mesh_import.h): the child imports
// with the same options (isolation off) under its memory limit and sends back the mesh or the
// error (imported_mesh_codec.h); the parent waits up to the time limit. A child that dies
// before sending a whole answer crashed; one still running at the limit is killed.
#pragma once

#include <filesystem>

#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/result.h"

namespace wirerig {

// `options.isolation` must be set. Errors name the file: the child's own error as ImportMesh
// words it, or "<path>: the importer crashed on this file (<signal>)", "<path>: the importer
// timed out on this file (...)", "<path>: cannot start the importer process (...)".
Result<ImportedMesh> ImportMeshIsolated(const std::filesystem::path& path,
                                        const ImportOptions& options);

}  // namespace wirerig
