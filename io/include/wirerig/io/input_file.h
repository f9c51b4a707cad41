// Input files: one check of what a path names before anything reads it, shared by every loader
// (wire problems, rig descriptions, rig files, scenes, motion mappings) and the mesh import. A
// directory, a FIFO or a device (/dev/zero) is refused with a reason instead of throwing from
// a stream, blocking on an open or reading forever; a file over its size limit is refused
// before it is read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "wirerig/io/result.h"

namespace wirerig {

// Largest JSON document wirerig reads (64 MiB): far above any rig or scene it writes (a few
// MB for a 100k-vertex mesh), far below what parsing would take to exhaust memory.
inline constexpr std::uintmax_t kMaxJsonFileBytes = std::uintmax_t{64} << 20;

// The size in bytes of the regular file at `path`, without opening it. `what` names the
// expected kind ("mesh file"). Errors read "<path>: <reason>": no such file, is a directory (not
// a <what>), is not a regular file, or is larger than `max_bytes`.
Result<std::uintmax_t> CheckInputFile(const std::filesystem::path& path, std::string_view what,
                                      std::uintmax_t max_bytes);

// The whole content of the regular file at `path`, checked as CheckInputFile does on the open
// file itself (opened without blocking, so a FIFO swapped in after a check is refused too).
// Read errors come back as errors, never as exceptions.
Result<std::string> ReadInputFile(const std::filesystem::path& path, std::string_view what,
                                  std::uintmax_t max_bytes = kMaxJsonFileBytes);

}  // namespace wirerig
