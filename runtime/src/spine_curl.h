// Large curls of a deformable part's spine inside EvaluateRigJob (SpineLoads::large_deflection):
// the bending in the plane of the spine's largest deflection is the co-rotational chain
// (corotational_wire.h); the rest (loads across that plane, and a wire's motion beyond its
// static shape, SpineLoads::extra_slope) is added as small turns of the chain's tangents.
#pragma once

#include <span>

#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/rig_evaluation.h"
#include "wirerig/runtime/status.h"

namespace wirerig::detail {

// Buffers of the spine's sample count (made once per workspace).
struct SpineCurlScratch {
  std::span<Vec3> chain_points;    // the chain's positions, wire frame
  std::span<Vec3> chain_tangents;  // the chain's unit tangents, wire frame
};

// In: the samples v_k, the small-deflection displacement and slope (local axes, x normal,
// y binormal, z tangent; the extras of `loads` already added). Out: `displacement` replaced by
// the large-curl displacement (z: the shortening along the rest tangent, m) and `turn[k]` the
// rotation of sample k's frame (local axes). Refuses families other than the cantilevers and
// more loads than the chain holds, naming "poses".
Status CurlSpine(double length, double bending_stiffness, const SpineLoads& loads,
                 std::span<const double> samples, std::span<const Vec3> slope,
                 std::span<Vec3> displacement, std::span<Mat3> turn,
                 const SpineCurlScratch& scratch);

}  // namespace wirerig::detail
