// Setup helpers shared by the benchmark programs.
#pragma once

#include <time.h>

#include <cstdlib>
#include <iostream>
#include <utility>

#include "wirerig/io/result.h"

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

// This thread's CPU time, s (for ratios of two paths timed alternately in one loop).
inline double ThreadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

}  // namespace wirerig::bench
