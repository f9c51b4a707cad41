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

}  // namespace wirerig::cli
