// IsFinite for the rig and anim libraries: component-wise, so no arithmetic touches an infinity.
#pragma once

#include <cmath>

#include "wirerig/runtime/conventions.h"

namespace wirerig {

inline bool IsFinite(double x) { return std::isfinite(x); }

// Not Eigen's allFinite(): it computes inf - inf, which traps when FE_INVALID is enabled.
inline bool IsFinite(const Vec3& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

}  // namespace wirerig
