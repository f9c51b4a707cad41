// AxialJob: closed-form axial displacement of a straight wire, EA X' = N(v) (paper Eq. 1,
// corrected in PHYSICS.md section 3), with the fixed point v0 anywhere in [0, 1] and loads on
// both sides of it.
//
// N(v) is the internal normal force (tension > 0). For v > v0 it is the sum of the loads
// beyond v; for v < v0 it is minus the sum of the loads before v. Loads on one side of v0 never
// move the other side; beyond the last load on a side the wire translates rigidly. A load
// exactly at v0 goes into the support. Closed form, with s = L v:
//   X(v) = (L/EA) sum_j P_j g(v, v_j),
//   g = min(|v-v0|, |v_j-v0|) when v and v_j lie on the same side of v0, else 0.
// A uniform line load integrates g exactly (it is not replaced by its resultant).
//
// For a curved wire X is the change of arc length from v0 (the strain form of PHYSICS.md
// section 3); mapping it onto the curve is the caller's job.
#pragma once

#include <span>

#include "wirerig/runtime/loads.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

struct AxialJob {
  double length = 0.0;           // L > 0, m
  double axial_stiffness = 0.0;  // EA > 0, N
  double fixed_at = 0.0;         // v0 in [0, 1]

  std::span<const AxialPointLoad> point_loads;
  std::span<const AxialLineLoad> line_loads;

  // Sample parameters v_i in [0, 1], any order; at least one.
  std::span<const double> samples;

  // Outputs, each either empty (not computed) or of samples.size(); displacement is required.
  std::span<double> displacement;  // X(v_i) along +v, m
  // N(v_i), tension > 0, N. At v_i == v0 the value on the side towards the wire's interior
  // (v0 < 1: just above v0; v0 == 1: just below); likewise at the ends v_i = 0 and 1 (a point
  // load on the end face counts: N(1) of a tip load F is F).
  std::span<double> normal_force;

  Status Validate() const;
  // Validates, then fills the outputs. Never allocates; never writes NaN.
  Status Run() const;
};

}  // namespace wirerig
