// Internal to the runtime: small vector helpers that never raise floating-point exceptions
// (no division by zero, no overflow in norms), shared by the curve and binding code.
#pragma once

#include <algorithm>
#include <cmath>

#include "wirerig/runtime/conventions.h"

namespace wirerig::detail {

inline double MaxAbs(const Vec3& v) {
  return std::max({std::abs(v.x()), std::abs(v.y()), std::abs(v.z())});
}

// Makes *unit the direction of v and returns |v|; returns 0 (and leaves *unit alone) for the
// zero vector. Scaling by the largest component first avoids overflow and underflow.
inline double Unit(const Vec3& v, Vec3* unit) {
  const double scale = MaxAbs(v);
  if (!(scale > 0.0)) return 0.0;
  const Vec3 scaled = v / scale;
  const double norm = scaled.norm();  // in [1, sqrt(3)]
  *unit = scaled / norm;
  return scale * norm;
}

// A unit vector perpendicular to the unit vector t: the world axis least aligned with t
// (ties go to the lower axis), made perpendicular by Gram-Schmidt (its length is then at
// least sqrt(2/3) before normalising).
inline Vec3 PerpendicularTo(const Vec3& t) {
  const Vec3 a = t.cwiseAbs();
  int axis = 0;
  if (a.y() < a(axis)) axis = 1;
  if (a.z() < a(axis)) axis = 2;
  const Vec3 e = Vec3::Unit(axis);
  Vec3 n = e;
  Unit(e - e.dot(t) * t, &n);
  return n;
}

// v made a unit vector perpendicular to the unit vector t (Gram-Schmidt); any perpendicular
// when v is (nearly) parallel to t.
inline Vec3 OrthonormalizeAgainst(const Vec3& v, const Vec3& t) {
  Vec3 n = Vec3::Zero();
  if (Unit(v - v.dot(t) * t, &n) > 1e-8 * MaxAbs(v)) return n;
  return PerpendicularTo(t);
}

}  // namespace wirerig::detail
