// A guard that turns floating-point traps off for its lifetime (the test main enables them).
#pragma once

#include <fenv.h>

namespace wirerig::testing {

// For calls into libraries that compute with Inf and NaN on purpose: Mesa's shader compiler
// and rasteriser (llvmpipe), Assimp's importers. Restores the traps afterwards.
class ScopedNoFpTraps {
 public:
  ScopedNoFpTraps() : saved_(fegetexcept()) { fedisableexcept(FE_ALL_EXCEPT); }
  ~ScopedNoFpTraps() {
    feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(saved_);
  }
  ScopedNoFpTraps(const ScopedNoFpTraps&) = delete;
  ScopedNoFpTraps& operator=(const ScopedNoFpTraps&) = delete;

 private:
  int saved_;
};

}  // namespace wirerig::testing
