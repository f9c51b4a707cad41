// Output files: one check of where a file is to be written, made before any work, shared by
// every command that writes one. The counterpart of input_file.h.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "wirerig/io/result.h"

namespace wirerig {

// Checks that `path` can be written as one of `extensions` (".glb", matched case-insensitively;
// any extension when the list is empty) without writing it (an empty probe file is made and
// removed beside it, as permission bits do not show a read-only mount). Errors read
// "<path>: <reason>":
// the extension is not one of those listed, the path is a directory or another file that is not
// a regular file (NotARegularTarget), its folder does not exist (named once: the nearest missing
// folder), is not a folder, or is not writable.
Result<bool> CheckOutputFile(const std::filesystem::path& path,
                             std::initializer_list<std::string_view> extensions);

// Refuses an `output` that is the file `input` (through any path or link), which the command
// reads: "<output>: is <what> (<input>), which this command reads; write elsewhere". Passes
// when either does not exist.
Result<bool> CheckNotAnInput(const std::filesystem::path& output,
                             const std::filesystem::path& input, std::string_view what);

// Why an existing `path` must not be replaced by a written file: it is a device, a FIFO, a
// socket or a symbolic link (writing renames a new file over the name, which would destroy the
// device or the link, not write through it). Empty when `path` does not exist or is a regular
// file. Checked again by every atomic writer.
std::optional<std::string> NotARegularTarget(const std::filesystem::path& path);

}  // namespace wirerig
