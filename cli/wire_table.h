// A human-readable table of a solved wire: properties, then one row per sample.
#pragma once

#include <iosfwd>

#include "wirerig/wire_problem/wire_problem.h"

namespace wirerig::cli {

void PrintWireTable(std::ostream& out, const WireProblem& problem, const WireSolution& solution);

}  // namespace wirerig::cli
