// Messages about files, shared by the rig library's readers and writers: "<path>: <problem>",
// and extensions compared without case.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "wirerig/io/result.h"

namespace wirerig::detail {

inline Error PathError(const std::filesystem::path& path, std::string_view problem) {
  return Error{path.string() + ": " + std::string(problem)};
}

// ASCII lower case (file extensions, format names).
inline std::string Lowercase(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

}  // namespace wirerig::detail
