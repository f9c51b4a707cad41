// CorotationalWireIkJob: the dead tip force that puts the tip of a large-curl cantilever
// (CorotationalWireJob) at a point of its plane. The tip is no longer linear in the force, so
// the force is found by Levenberg-Marquardt on |tip(F) - target|^2 (2 unknowns, Jacobian by
// central differences), with F kept inside the ball |F| <= max_force (projected steps; on the
// bound with the miss falling outwards, steps along the bound's circle). Every trial force is
// solved from the straight wire (load continuation), so the answer is an equilibrium on the
// natural branch, the one the wire reaches as its load grows; the difference steps warm-start
// from it.
//
// Reachable targets are met to `tolerance` L (default 1e-10; measured 1e-13 to 7e-11 L for curls
// of 30 to 120 degrees, 7 to 10 iterations, about 40-50 chain solves). Reachable means: the tip
// of the natural equilibrium under some dead tip force |F| <= max_force. That set lies strictly
// inside the disc of radius L about the root but is smaller than the disc: a tip force bends the
// wire into shapes whose shortening grows with their deflection, so e.g. (0.95, 0.2) L is not
// reachable. Otherwise the result is the closest point found and says so (not an error):
//   force_limited  the search ended on |F| = max_force: a nearer point needs more force (every
//                  target at or beyond L is in this case: the wire only straightens towards it
//                  as F grows without bound);
//   beyond_length  |target| >= L: no inextensible wire of length L reaches it.
// A target missed for another reason (a shape no tip force makes; a local minimum of the miss)
// ends with neither flag and reached_target false.
//
// The wire's own fixed loads (point and line loads, tip moment) stay applied; its tip_force is
// the first guess when nonzero (otherwise the linear-theory force for the target's lateral
// offset). K: the wire's segments, or if 0 the automatic K for a tip force of max_force, fixed
// for the whole search. If the wire job has samples and outputs they receive the solved shape.
#pragma once

#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/corotational_wire.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

struct CorotationalWireIkResult {
  Vec3 tip_force = Vec3::Zero();  // the solved dead tip force, N (z = 0)
  Vec3 reached = Vec3::Zero();    // the tip with it, m (z = 0)
  double miss = 0.0;              // |reached - target|, m
  bool reached_target = false;    // miss <= tolerance * L
  bool force_limited = false;
  bool beyond_length = false;
  double root_moment = 0.0;  // of the solved chain (a warm start for the next frame's wire), N m
  int iterations = 0;        // Levenberg-Marquardt iterations
  int chain_solves = 0;      // CorotationalWireJob runs
};

struct CorotationalWireIkJob {
  // The wire (free or guided cantilever) with its fixed loads; see above for tip_force,
  // segments and outputs. Its result pointer is ignored.
  CorotationalWireJob wire;

  Vec3 target = Vec3::Zero();  // wanted tip position, m, wire frame, z = 0
  double max_force = 0.0;      // > 0 and finite, N
  double tolerance = 1e-10;    // in (0, 1e-3], fraction of L
  int max_iterations = 100;    // in [1, 1000]

  CorotationalWireIkResult* result = nullptr;  // required

  // Checks every input (the wire with a tip force of max_force); names the first invalid one.
  Status Validate() const;
  // Validates, then solves. Never allocates; never writes NaN.
  Status Run() const;
};

}  // namespace wirerig
