// printf-style formatting into a std::string for the CLI's tables and summaries (one line, at
// most 511 characters: longer output is cut).
#pragma once

#include <cstdio>
#include <string>

namespace wirerig::cli {

std::string Format(const char* format, auto... args) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, format, args...);
  return buffer;
}

}  // namespace wirerig::cli
