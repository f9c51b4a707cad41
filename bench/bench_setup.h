// Setup helpers shared by the benchmark programs.
#pragma once

#include <cstdlib>
#include <iostream>
#include <utility>

#include "wirerig/rig/result.h"

namespace wirerig::bench {

// Setup failures end the run: a benchmark of a rig that was not built would measure nothing.
template <typename T>
T Check(Result<T> result, const char* what) {
  if (!result) {
    std::cerr << what << ": " << result.error() << "\n";
    std::exit(1);
  }
  return std::move(result).value();
}

}  // namespace wirerig::bench
