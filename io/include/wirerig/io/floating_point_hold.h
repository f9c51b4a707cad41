// ScopedFloatingPointHold: runs code that may raise floating-point exceptions as a matter of
// course (CGAL, text parsers overflowing on huge literals) with every trap held.
#pragma once

#include <fenv.h>

namespace wirerig {

// Saves the floating-point environment, clears the flags and disables every trap until
// destruction, which clears whatever flags were raised meanwhile and restores the saved
// environment (traps included). CGAL raises floating-point exceptions as a matter of course:
// its filtered predicates and lazy constructions compute with intervals whose bounds may be
// infinite (seen: Interval_nt products in the circumcentre of a Delaunay cell, while the
// Voronoi poles of a UV sphere are computed, raise FE_INVALID). With traps enabled, as in the
// tests, that would be a SIGFPE; results are checked for finiteness afterwards instead.
class ScopedFloatingPointHold {
 public:
  ScopedFloatingPointHold() { feholdexcept(&saved_); }
  ~ScopedFloatingPointHold() {
    feclearexcept(FE_ALL_EXCEPT);
    fesetenv(&saved_);
  }
  ScopedFloatingPointHold(const ScopedFloatingPointHold&) = delete;
  ScopedFloatingPointHold& operator=(const ScopedFloatingPointHold&) = delete;

 private:
  fenv_t saved_;
};

}  // namespace wirerig
