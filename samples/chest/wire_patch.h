// The 7-wire approximation of a clamped plate (paper Fig. 3 and Eq. 18; PHYSICS.md section 5).
//
// Profile wires run along v at u_j = j/(m - 1), j = 0..m-1 (m = 7 in the paper). Wires 0 and
// m - 1 lie on the clamped edges (X = 0). Each interior wire is a clamped-clamped wire of length
// b in v carrying its strip of the load: EI_j = D b_j, line load b_j q, with the strip width
// b_j = (b_{j-1} + b_j)/2 = a/(m - 1) for evenly spaced wires. It is solved by wirerig's closed
// form (BendingJob, kClamped, one LineLoad over [0, 1]), which gives X_j(v) = q b^4 v^2 (1-v)^2
// / (24 D) for every interior wire: the width cancels and the bare model ignores u.
//
// Eq. (18) scales each wire by one coefficient, fitted by linear least squares against the
// plate deflection S along that wire:
//   xi_j = integral S(u_j, v) X_j(v) dv / integral X_j(v)^2 dv.
// The integrals use the trapezoidal rule on the plate's grid nodes v_k = k/n (the integrands
// vanish with their slopes at both ends, so the rule is O(h^4) there). xi depends only on the
// geometry, the BCs and the layout, not on q or D: fit once offline, evaluate per frame.
//
// The fitted model is xi_j X_j(v) on the wires; "surface" means the plate rebuilt from it by
// linear interpolation across u between neighbouring wires.
#pragma once

#include <span>
#include <vector>

#include "plate_reference.h"
#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/status.h"

namespace wirerig::chest {

// How the wires are scaled: xi = 1 (the bare wires), one xi fitted over all interior wires
// together, or one xi per wire (Eq. 18 as written; the default).
enum class XiFit : int { kNone = 0, kSingle = 1, kPerWire = 2 };

struct WirePatch {
  double width = 1.0;               // a, m (wires sit at x = u_j a)
  double length = 1.0;              // b, m (each wire's length)
  double flexural_rigidity = 1.0;   // D, N m
  std::vector<double> u;            // m wire positions u_j = j/(m - 1)
  std::vector<double> strip_width;  // b_j, m; 0 on the two edge wires
  std::vector<double> xi;           // m coefficients; 0 on the two edge wires

  int wire_count() const { return static_cast<int>(u.size()); }
};

// Fits the wire patch to `plate` (Eq. 18). wire_count >= 3, and the plate's n must be a multiple
// of wire_count - 1 so that every wire lies on a grid line. Refuses a plate with no deflection.
Status FitWirePatch(const PlateSolution& plate, int wire_count, XiFit fit, WirePatch* out);

// Evaluates the fitted wires under pressure q: deflection[j * K + k] = xi_j X_j(v_k), K =
// samples.size(), along the load, for all m wires (zero on the edge wires). One BendingJob per
// interior wire; never allocates. `scratch` holds K vectors.
struct WirePatchJob {
  const WirePatch* patch = nullptr;
  double pressure = 1.0;            // q, N/m^2, finite
  std::span<const double> samples;  // v_k in [0, 1], at least one
  std::span<Vec3> scratch;          // samples.size()
  std::span<double> deflection;     // wire_count * samples.size(), m

  Status Run() const;
};

// Errors of the fitted model against the plate, relative to the plate's peak |S|.
struct WirePatchErrors {
  double plate_peak = 0.0;    // m
  double max_on_wires = 0.0;  // over the interior wires at every grid node v_k
  double rms_on_wires = 0.0;
  double max_surface = 0.0;  // over every grid node, linear interpolation across u
  double rms_surface = 0.0;
  std::vector<double> max_per_wire;  // m values (0 on the edge wires)
};

// Evaluates `patch` at the plate's q on the plate's grid and compares. The plate must be the
// one the patch was fitted to, or one of the same shape and n a multiple of m - 1.
Status CompareWithPlate(const WirePatch& patch, const PlateSolution& plate, WirePatchErrors* out);

}  // namespace wirerig::chest
