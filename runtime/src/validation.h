// Internal to the runtime: input checks shared by the jobs. Each returns a Status naming
// the field (and element) at fault. None allocates.
#pragma once

#include <cmath>
#include <cstddef>
#include <span>
#include <string_view>

#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/status.h"

namespace wirerig::detail {

inline bool PositiveFinite(double x) { return std::isfinite(x) && x > 0.0; }
inline bool InUnitInterval(double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; }

// Deflections are bounded by (compliance x total load); keeping that bound far from the
// largest double guarantees no output becomes Inf or NaN.
inline constexpr double kMaxDeflectionBound = 1e150;

// The most a Young's modulus, a section area or a second moment may be: their products (the
// stiffnesses E A and E I) then stay finite.
inline constexpr double kMaxStiffnessFactor = 1e150;

// One of BendingJob's four boundary families (a value cast from an integer may be none).
inline bool IsKnownBoundary(BoundaryCondition bc) {
  switch (bc) {
    case BoundaryCondition::kSimplySupported:
    case BoundaryCondition::kClamped:
    case BoundaryCondition::kCantileverFree:
    case BoundaryCondition::kCantileverGuided:
      return true;
  }
  return false;
}

inline Status CheckBoundary(std::string_view field, BoundaryCondition bc) {
  return IsKnownBoundary(bc) ? Status::Ok() : Status::Invalid(field, "unknown boundary condition");
}

inline Status CheckPositive(std::string_view field, double x, std::string_view reason) {
  return PositiveFinite(x) ? Status::Ok() : Status::Invalid(field, reason);
}

// Position `at` of element `index` of a load array.
inline Status CheckLoadPosition(std::string_view field, int index, double at) {
  return InUnitInterval(at) ? Status::Ok()
                            : Status::InvalidElement(field, index, "at", "must lie in [0, 1]");
}

// Extent [from, to] of element `index` of a line-load array.
inline Status CheckLoadExtent(std::string_view field, int index, double from, double to) {
  if (!InUnitInterval(from))
    return Status::InvalidElement(field, index, "from", "must lie in [0, 1]");
  if (!InUnitInterval(to)) return Status::InvalidElement(field, index, "to", "must lie in [0, 1]");
  if (!(from < to)) return Status::InvalidElement(field, index, "to", "must be greater than from");
  return Status::Ok();
}

// At least one sample, each in [0, 1].
inline Status CheckSamples(std::span<const double> samples) {
  if (samples.empty()) return Status::Invalid("samples", "needs at least one sample");
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (!InUnitInterval(samples[i]))
      return Status::InvalidElement("samples", static_cast<int>(i), "", "must lie in [0, 1]");
  return Status::Ok();
}

// An output span: required ones must match the sample count; optional ones may be empty.
inline Status CheckOutput(std::string_view field, std::size_t size, std::size_t samples,
                          bool required) {
  if (size == samples || (!required && size == 0)) return Status::Ok();
  return Status::Invalid(field, required ? "must have one element per sample"
                                         : "must be empty or have one element per sample");
}

}  // namespace wirerig::detail
