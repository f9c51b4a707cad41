// Writing files so that readers never see half of one: the bytes go to a temporary file in
// the same folder, which is renamed over the target only after a successful write.
#pragma once

#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "wirerig/io/result.h"

namespace wirerig {

// Returns the path written, or an error naming the file and the cause. On failure the target
// is untouched and no temporary file is left behind, nor when SIGINT or SIGTERM kills the
// process meanwhile; stale temporary files of dead processes beside `path` are removed first
// (temp_files.h).
Result<std::filesystem::path> WriteFileAtomically(const std::filesystem::path& path,
                                                  std::string_view bytes);

struct FileToWrite {
  std::filesystem::path path;
  std::string_view bytes;
};

// Several files, all or none: each is written to its temporary file first, and only when every
// one was written are they renamed over their targets, in order. A failed write leaves every
// target untouched and no temporary file (the error says so when there are several). Returns the
// paths written. (A rename that fails after earlier ones succeeded, which takes the folder changing
// under the process, leaves those replaced; the error lists them.)
Result<std::vector<std::filesystem::path>> WriteFilesAtomically(std::span<const FileToWrite> files);

}  // namespace wirerig
