// Checks of numeric option values whose messages state the bound readably
// ("--fps: must be in [1, 1000] (got 0)"), unlike CLI11's own (which print DBL_MAX in full).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace wirerig::cli {

// A number in [min, max].
CLI::Validator InRange(double min, double max);
// A number >= min.
CLI::Validator AtLeast(double min);
// A number > min.
CLI::Validator Above(double min);

// An image size "WIDTHxHEIGHT", each in [16, 8192].
inline constexpr const char* kImageSizeRule = "WIDTHxHEIGHT, each in [16, 8192], e.g. 1280x720";
bool ParseImageSize(const std::string& text, int* width, int* height);
CLI::Validator ImageSize();

}  // namespace wirerig::cli
