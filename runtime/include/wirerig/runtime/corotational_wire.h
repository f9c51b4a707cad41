// CorotationalWireJob: large planar curls of a cantilever wire, as a chain of K segments each
// solved by the small-deflection closed form (BendingJob) in its own, rotated frame.
//
// Frame: the wire's own frame. The root (v = 0) is clamped at the origin with its tangent along
// +X; bending happens in the X-Y plane (planar elastica). Every load is a DEAD load: it keeps
// its direction in this frame however the wire turns (the classic elastica load). Loads must lie
// in the plane (z = 0); out-of-plane loads are refused. The wire is inextensible.
//
// Method (co-rotational chain). Segment k covers v in [k/K, (k+1)/K] (length h = L/K). Its frame
// starts at node p_k with the tangent angle theta_k reached by the segment before it (theta_0 =
// 0). In that frame it is a cantilever solved by BendingJob (kCantileverFree) with
//   - the lateral components of its own point and line loads,
//   - at its tip, the lateral component of the force carried from beyond (every load further
//     out: dead loads, so their sum does not depend on the shape), and the bending moment
//     M_{k+1} of everything beyond about node p_{k+1} (added as the exact tip-moment solution
//     M x^2 / 2EI).
// The moment balance of each segment uses its deformed geometry (the axial components of the
// loads times the segment's own deflection), which makes M_{k+1} a linear function of M_k.
// Kinematics: the linear slope w'(x) is the segment's turn (it is the integral of M / EI), and
// the point at x sits at (x - integral of w'^2 / 2, w(x)) in the segment's frame (inextensible
// to second order; three-point Gauss). The next segment starts at the tip, turned by w'(h).
// The chain is a one-unknown shooting problem on the root moment M_0, solved by bracketing and
// Brent's method to machine precision: the free tip needs M_K = tip_moment; the guided tip
// (kCantileverGuided) needs its tangent back at theta_K = 0, its support taking the moment.
// Large loads also admit looped (non-natural) equilibria; the natural one is followed by load
// continuation from the straight wire (steps adding at most ~1 rad of possible turn each),
// unless warm_start gives the root moment of a nearby solution.
//
// Accuracy: the error falls as K^-2. Tip error / L against the exact elastica under a tip force
// perpendicular to the root (tests/runtime/corotational_wire_test.cpp): 60-degree tip rotation
// 3.3e-3 (K = 8), 8.3e-4 (16), 2.1e-4 (32); 89 degrees (F L^2/EI = 27.5) 8.3e-4 (K = 32). For
// loads small enough the chain is BendingJob (lateral displacement equal to 1e-9 relative).
//
// Families: kCantileverFree and kCantileverGuided only. The simply supported and clamped
// families are refused (their large-deflection form needs the end reactions and an axial
// constraint, not done). Of the follower loads (turning with the wire) only the tip force is
// supported (tip_force_follows).
//
// Cost: one chain sweep is K BendingJob runs (about 0.5 us per segment); a solve takes about 8
// sweeps warm-started (per frame: pass the last frame's root moment), and about 7 per
// continuation step otherwise (15-80 sweeps for F L^2/EI from 1 to 9). No allocation: state
// lives on the stack, bounded by kMaxSegments, kMaxPointLoads and kMaxLineLoads.
#pragma once

#include <span>

#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/loads.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

// What a solved chain reports besides its samples.
struct CorotationalWireResult {
  Vec3 tip_position = Vec3::Zero();  // p(v = 1), m, wire frame (z = 0)
  Vec3 tip_tangent = Vec3::UnitX();  // unit tangent at v = 1
  double tip_rotation = 0.0;         // theta(1), rad, counter-clockwise about +Z
  double root_moment = 0.0;          // M_0 = EI * curvature at the root, N m
  int segments = 0;                  // K used
  int iterations = 0;                // shooting evaluations (chain sweeps)
};

struct CorotationalWireJob {
  static constexpr int kMaxSegments = 256;
  static constexpr int kMaxPointLoads = 16;
  static constexpr int kMaxLineLoads = 8;
  // Automatic K (segments == 0) lets each segment turn at most about this much, bounded by the
  // largest curvature the loads could produce (|M| <= |tip_moment| + L * sum |F|).
  static constexpr double kAutoSegmentTurn = 0.1;  // rad
  // Validate() refuses a K whose segments could turn more than this (the linear theory inside a
  // segment would be meaningless).
  static constexpr double kMaxSegmentTurn = 1.0;  // rad

  BoundaryCondition boundary = BoundaryCondition::kCantileverFree;  // or kCantileverGuided

  double length = 0.0;             // L in [1e-9, 1e10], m
  double bending_stiffness = 0.0;  // EI > 0 and at least 1e-100 L^2, N m^2
  // Tapered wires: EI at the tip, EI(v) = EI (EI_tip / EI)^v (a cone's EI falls as r^4); each
  // segment takes the inverse of its mean 1/EI. 0: uniform. N m^2, 0 or within 1e12 of EI.
  double tip_bending_stiffness = 0.0;

  // K, in [1, kMaxSegments]; 0 chooses K from the loads (see kAutoSegmentTurn), at least 8.
  int segments = 0;

  // Dead loads in the wire frame, z = 0, each component at most 1e100 in magnitude. The tip
  // force acts at v = 1.
  Vec3 tip_force = Vec3::Zero();  // N
  // A follower tip force instead (free tip; a guided tip does not turn, so there it is the dead
  // force): tip_force is then given in the tip's frame (X along the tip's tangent, Y across it)
  // and turns with the tip. The chain then has two unknowns, the root moment and the tip's
  // turn, solved by damped Newton with load continuation from the straight wire (warm_start is
  // not used). The other loads stay dead.
  bool tip_force_follows = false;
  double tip_moment = 0.0;                 // N m about +Z at v = 1 (kCantileverFree only)
  std::span<const PointLoad> point_loads;  // at most kMaxPointLoads; a load at v = 0 does nothing
  std::span<const LineLoad> line_loads;    // at most kMaxLineLoads; N per metre of wire

  // Warm start: the root moment of a nearby solution (the last frame's, or an IK's previous
  // step). The solve then takes the equilibrium nearest to it instead of applying the loads in
  // steps from the straight wire (load continuation, which follows the natural branch).
  bool warm_start = false;
  double root_moment_guess = 0.0;  // N m, finite

  // Sample parameters v_i in [0, 1], any order; may be empty (the result still has the tip).
  std::span<const double> samples;
  // Outputs, each empty or of samples.size().
  std::span<Vec3> position;  // p(v_i), m, wire frame (z = 0)
  std::span<Vec3> tangent;   // unit tangent at v_i (z = 0)

  // Optional: filled by Run() on success.
  CorotationalWireResult* result = nullptr;

  // Checks every input; names the first invalid one.
  Status Validate() const;
  // Validates, then solves the chain and fills the outputs. Never allocates; never writes NaN.
  // result->iterations counts every chain sweep (for a follower force, its Newton evaluations).
  // Fails with "loads" if the shooting does not converge (not seen for valid inputs in tests),
  // "tip_force" if a follower force's continuation stalls (2 of ~430 random large follower cases).
  Status Run() const;
};

// The K that segments == 0 selects for these loads.
int AutomaticSegmentCount(const CorotationalWireJob& job);

}  // namespace wirerig
