// Writing files so that readers never see half of one: the bytes go to a temporary file in
// the same folder, which is renamed over the target only after a successful write.
#pragma once

#include <filesystem>
#include <string_view>

#include "wirerig/io/result.h"

namespace wirerig {

// Returns the path written, or an error naming the file and the cause. On failure the target
// is untouched and no temporary file is left behind, nor when SIGINT or SIGTERM kills the
// process meanwhile; stale temporary files of dead processes beside `path` are removed first
// (temp_files.h).
Result<std::filesystem::path> WriteFileAtomically(const std::filesystem::path& path,
                                                  std::string_view bytes);

}  // namespace wirerig
