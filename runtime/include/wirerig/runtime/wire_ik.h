// WireIkJob: the loads that put one point of a wire at a target displacement (small-deflection
// theory, BendingJob). Deflection is linear in the loads, so with the influence coefficients
//   g_i = X(v_target) under a unit load of basis i (each component solved independently),
// the wanted displacement d = target - X_fixed(v_target) (X_fixed: the wire under its fixed loads
// and end displacements) is reached by the least-norm loads
//   F_i = g_i d_lat / sum_j g_j^2,
// where d_lat is d without its component along the wire's axis (bending moves a point only
// across the wire). One BendingJob run per basis load plus one for the fixed loads; no matrix.
//
// When the target cannot be reached exactly the result is the closest reachable displacement
// (least squares) and says why; it is not an error:
//   axial_component  the target has a component along the wire (beyond 1e-12 L), dropped;
//   pinned           the point cannot move under the basis loads (at a support, or every basis
//                    load at a support): the loads are zero;
//   force_limited    the least-norm loads exceed max_force; they are scaled down to it, which
//                    gives the closest point the bounded loads reach (the reachable set is a
//                    disc in the lateral plane).
//
// Load basis: kTipForce (cantilevers only) solves one tip force; kPointLoads solves one lateral
// force at each v in load_at (at most kMaxLoads), least-norm over all of them.
#pragma once

#include <limits>
#include <span>

#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/loads.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

enum class WireIkBasis : int { kTipForce = 0, kPointLoads = 1 };

struct WireIkResult {
  Vec3 reached = Vec3::Zero();  // X(v_target) with the fixed and the solved loads, m
  double miss = 0.0;            // |reached - target|, m
  bool reached_target = false;  // none of the three reasons below applies
  bool axial_component = false;
  bool pinned = false;
  bool force_limited = false;
};

struct WireIkJob {
  static constexpr int kMaxLoads = 8;

  // The wire, as for BendingJob.
  BoundaryCondition boundary = BoundaryCondition::kCantileverFree;
  double length = 0.0;             // L > 0, m
  double bending_stiffness = 0.0;  // EI > 0, N m^2
  // The wire's axis in the coordinates of the displacements and forces (unit length); bending
  // loads and displacements are perpendicular to it.
  Vec3 axis = Vec3::UnitX();

  // Fixed loads and end displacements (gravity, a support's motion...), kept as they are.
  Vec3 start_displacement = Vec3::Zero();  // m
  Vec3 end_displacement = Vec3::Zero();    // m (ignored by cantilevers)
  Vec3 fixed_tip_force = Vec3::Zero();     // N, cantilevers only
  std::span<const PointLoad> fixed_point_loads;
  std::span<const LineLoad> fixed_line_loads;

  // The point to place and where: X(target_at) = target.
  double target_at = 1.0;      // v in [0, 1]
  Vec3 target = Vec3::Zero();  // m, same axes as the displacements

  WireIkBasis basis = WireIkBasis::kTipForce;
  std::span<const double> load_at;  // kPointLoads: v of each solved load, 1..kMaxLoads entries
  // Bound on the Euclidean norm of all solved forces together (N); infinity: none.
  double max_force = std::numeric_limits<double>::infinity();

  // Outputs. forces: the solved lateral forces, one per basis load (1 for kTipForce, else
  // load_at.size()), N. result: required.
  std::span<Vec3> forces;
  WireIkResult* result = nullptr;

  // Checks every input; names the first invalid one ("loads": the fixed loads together would
  // make the deflection overflow).
  Status Validate() const;
  // Validates, then solves. Never allocates; never writes NaN.
  Status Run() const;
};

}  // namespace wirerig
