// Work on an untrusted file in a forked child process (ImportIsolation in mesh_import.h): the
// child limits its address space, runs `work` and sends back its bytes or its error; the parent
// waits up to the time limit. A child that dies before sending a whole answer crashed; one
// still running at the limit is killed. Assimp 5.2.5 crashes or hangs on some corrupted files:
// every Assimp import of a file from outside goes through here when isolation is asked for.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "wirerig/io/result.h"
#include "wirerig/rig/mesh_import.h"

namespace wirerig {

// `work` runs in the child only (it may use anything the caller had at the call; it never
// returns into the caller's code). Errors name `path`: the work's own error as it words it, or
// "<path>: the importer crashed on this file (<signal>)", "<path>: the importer timed out on
// this file (...)", "<path>: cannot import: out of memory (limit N MiB, ...)", "<path>: cannot
// start the importer process (...)".
Result<std::string> RunIsolated(const std::filesystem::path& path, const ImportIsolation& limits,
                                const std::function<Result<std::string>()>& work);

}  // namespace wirerig
