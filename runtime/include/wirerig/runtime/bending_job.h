// BendingJob: closed-form lateral deflection of a wire, EI X'''' = p (paper Eq. 3).
//
// The four boundary-condition families of the paper (Eqs. 4-7) with end displacements
// X0, X1 (PHYSICS.md section 0 scales them to a physical length L):
//   kSimplySupported  X(0)=X0, X''(0)=0, X(1)=X1, X''(1)=0
//   kClamped          X(0)=X0, X'(0)=0,  X(1)=X1, X'(1)=0
//   kCantileverFree   X(0)=X0, X'(0)=0,  X''(1)=0, EI X'''(1) = -F_tip   (rotation at free end)
//   kCantileverGuided X(0)=X0, X'(0)=0,  X'(1)=0,  EI X'''(1) = -F_tip   (no rotation at free end)
// X1 is ignored by the cantilevers: their free end's position is an output.
//
// Modes: kExact evaluates the piecewise-polynomial Green's-function solution of PHYSICS.md
// section 2 (exact for point, uniform and linearly varying patch loads, O(J) per sample; with
// point loads only, at most 16 of them, one cubic per interval between loads: O(J^2) once per
// Run() and O(1) per sample).
// kSeries evaluates the paper's sine series, Eqs. (10)-(17), truncated at N terms, with each
// load's exact sine coefficients; it converges as N^-3 for simply supported and clamped wires
// and only as N^-1 for cantilevers.
//
// A linearly varying load over [a, b] (per unit v: p_a at a, p_b at b, width d = b - a) adds
// the Macaulay particular solution
//   M(v) = p_a <v-a>^4/24 - p_b <v-b>^4/24 + (p_b - p_a) (<v-a>^5 - <v-b>^5) / (120 d),
// evaluated as p_a (t_a^4/24 - R) + p_b (R - t_b^4/24) with R = (t_a^5 - t_b^5) / (120 d) summed
// as (t_a^4 + t_a^3 t_b + ... + t_b^4) / 120 past b, so a narrow load divides by nothing small;
// and its sine coefficients
//   p_n = 2/(n pi) [p_a cos(n pi a) - p_b cos(n pi b) + (p_b - p_a) cos(n pi m) sinc(n pi d/2)],
// m = (a + b)/2, sinc(x) = sin(x)/x.
//
// Degenerate cases, each tested by name: a point load at a support (v = 0; v = 1 for simply
// supported and clamped) produces no deflection; a line load (uniform or linear) of zero width
// is refused; a tip force on a simply supported or clamped wire is refused (the supports would
// take it).
#pragma once

#include <span>
#include <string_view>

#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/loads.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

enum class BoundaryCondition : int {
  kSimplySupported = 0,
  kClamped = 1,
  kCantileverFree = 2,
  kCantileverGuided = 3,
};

enum class BendingMode : int { kExact = 0, kSeries = 1 };

// Names used in files: "simply_supported", "clamped", "cantilever_free", "cantilever_guided".
std::string_view ToString(BoundaryCondition bc);
// False if the name is unknown.
bool ParseBoundaryCondition(std::string_view name, BoundaryCondition* out);
bool IsCantilever(BoundaryCondition bc);

// Names used in files: "exact", "series".
std::string_view ToString(BendingMode mode);
bool ParseBendingMode(std::string_view name, BendingMode* out);

struct BendingJob {
  // Largest accepted number of series terms (bounds the work of one Run()).
  static constexpr int kMaxSeriesTerms = 100000;

  BoundaryCondition boundary = BoundaryCondition::kSimplySupported;
  BendingMode mode = BendingMode::kExact;
  int series_terms = 20;  // N, used in kSeries mode only; 1 <= N <= kMaxSeriesTerms

  double length = 0.0;             // L > 0, m
  double bending_stiffness = 0.0;  // EI > 0, N*m^2 (a strip uses E/(1-nu^2), see section.h)

  Vec3 start_displacement = Vec3::Zero();  // X0, m
  Vec3 end_displacement = Vec3::Zero();    // X1, m (ignored by cantilevers)
  Vec3 tip_force = Vec3::Zero();           // N at v = 1; must be zero unless a cantilever
  // A bending couple at the free tip (v = 1), N m, as the lateral direction the tip turns
  // towards times the couple's magnitude (the couple vector is tangent x tip_couple); adds
  // tip_couple L^2 v^2 / 2EI. Must be zero unless kCantileverFree (a guided tip's support takes
  // it).
  Vec3 tip_couple = Vec3::Zero();

  std::span<const PointLoad> point_loads;  // any order, any count
  std::span<const LineLoad> line_loads;    // any order, any count
  // Linearly varying line loads (loads.h), any order, any count.
  std::span<const LinearLineLoad> linear_line_loads;

  // Sample parameters v_i in [0, 1], any order; at least one.
  std::span<const double> samples;

  // Outputs, each either empty (not computed) or of samples.size(); displacement is required.
  std::span<Vec3> displacement;  // X(v_i), m
  std::span<Vec3> slope;         // dX/ds at v_i, dimensionless (s = L v)
  std::span<Vec3> curvature;     // d2X/ds2 at v_i, 1/m; the bending moment is -EI * curvature

  // Checks every input; names the first invalid one.
  Status Validate() const;
  // Validates, then fills the outputs. Never allocates; never writes NaN.
  Status Run() const;
};

}  // namespace wirerig
