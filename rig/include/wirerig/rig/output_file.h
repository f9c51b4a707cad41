// Output files: one check of where a file is to be written, made before any work, shared by
// every command that writes one. The counterpart of input_file.h.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <string_view>

#include "wirerig/rig/result.h"

namespace wirerig {

// Checks that `path` can be written as one of `extensions` (".glb", matched case-insensitively;
// any extension when the list is empty) without writing anything. Errors read "<path>: <reason>":
// the extension is not one of those listed, the path is a directory, its folder does not exist
// (named once: the nearest missing folder), is not a folder, or is not writable.
Result<bool> CheckOutputFile(const std::filesystem::path& path,
                             std::initializer_list<std::string_view> extensions);

}  // namespace wirerig
