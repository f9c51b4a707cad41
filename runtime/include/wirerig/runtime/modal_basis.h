// ModalBasis: the bending modes of a wire, the eigenfunctions of EI X'''' = rho A omega^2 X on
// v in [0, 1] with the homogeneous boundary conditions of one of BendingJob's four families
// (bending_job.h; the end displacements X0, X1 and the tip force are zero for the modes):
//   kSimplySupported  X(0)=0, X''(0)=0, X(1)=0,  X''(1)=0   cos/sin: beta_n = n pi
//   kClamped          X(0)=0, X'(0)=0,  X(1)=0,  X'(1)=0    cos(beta) cosh(beta) = 1
//   kCantileverFree   X(0)=0, X'(0)=0,  X''(1)=0, X'''(1)=0  cos(beta) cosh(beta) = -1
//   kCantileverGuided X(0)=0, X'(0)=0,  X'(1)=0,  X'''(1)=0  tan(beta) + tanh(beta) = 0
// Modes are indexed n = 0 .. modes-1 here (index 0 is the fundamental, the literature's first
// mode); mode n satisfies phi_n'''' = beta_n^4 phi_n in the parameter v. A wire of length L,
// bending stiffness EI and mass per length rho A vibrates in mode n at omega_n = beta_n^2 sqrt(EI /
// (rho A L^4)) rad/s.
//
// The eigenvalues are roots of the characteristic equations above, found by bisection in
// brackets of width pi/2 or pi around the asymptotic roots (every bracket holds exactly one
// root). Derivation of the guided cantilever: X = a(cosh - cos) + b(sinh - sin) meets the
// clamped end; X'(1) = X'''(1) = 0 has a non-zero (a, b) iff
//   (sinh b + sin b)(cosh b + cos b) - (cosh b - cos b)(sinh b - sin b) = 2(sinh b cos b +
//   cosh b sin b) = 0,  i.e.  tan b + tanh b = 0,  beta = 2.365020, 5.497804, 8.639380, ...
// (the symmetric modes of a clamped-clamped wire of twice the length).
//
// Numerical form: each eigenfunction is stored as
//   phi(v) = A cos(beta v) + B sin(beta v) + C exp(-beta v) + D exp(-beta (1 - v)),
// a basis bounded by 1 on [0, 1]: the textbook cosh/sinh form loses digits to cancellation as
// exp(beta) grows (half of them by beta ~ 18, all by beta ~ 37), this one keeps full precision
// up to the largest mode (beta ~ 102). The
// coefficients are the null vector of the 4x4 boundary-condition matrix. Normalisation:
// integral_0^1 phi_n^2 dv = 1 (computed exactly from the boundary values, no quadrature), so
// the simply supported modes are sqrt(2) sin(n pi v). Sign: the first derivative of phi_n
// that is not fixed to zero at v = 0 is positive (phi_n'(0) > 0 simply supported,
// phi_n''(0) > 0 otherwise), so cantilever modes end at phi_n(1) = +-2.
#pragma once

#include <array>
#include <span>

#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

struct ModalBasis {
  static constexpr int kMaxModes = 32;
  static constexpr int kDefaultModes = 8;

  BoundaryCondition boundary = BoundaryCondition::kSimplySupported;
  int modes = 0;  // N in [1, kMaxModes]; 0 until built

  // beta_n, dimensionless, increasing.
  std::array<double, kMaxModes> beta{};
  // (A, B, C, D) of mode n in the numerical form above.
  std::array<std::array<double, 4>, kMaxModes> coefficients{};
  // integral_0^1 phi_n dv, the projection of a unit uniform load.
  std::array<double, kMaxModes> integral{};
  // integral_0^1 v phi_n dv, the projection of a load rising linearly from 0 at v = 0 to 1 at
  // v = 1 (ModeMoment(basis, n, 0, 1)).
  std::array<double, kMaxModes> moment{};
  // phi_n(1), the projection of a unit tip force (0 for simply supported and clamped wires).
  std::array<double, kMaxModes> end_value{};
  // exp(-beta_n), for EvaluateMode.
  std::array<double, kMaxModes> decay{};
};

// Builds the basis of `modes` modes for a boundary family. Errors name "boundary" or "modes".
// Never allocates (can run at load time or per wire without heap use).
Status BuildModalBasis(BoundaryCondition boundary, int modes, ModalBasis* out);

// phi_n(v) and d phi_n / dv for n in [0, basis.modes) and v in [0, 1] (not checked: these are
// inner-loop helpers). O(1): one sin/cos pair and two exp.
double ModeValue(const ModalBasis& basis, int n, double v);
double ModeSlope(const ModalBasis& basis, int n, double v);
// Both at once, for the price of one (a sin/cos pair and one exp).
void EvaluateMode(const ModalBasis& basis, int n, double v, double* value, double* slope);
// integral_a^b phi_n(v) dv, 0 <= a <= b <= 1, in closed form.
double ModeIntegral(const ModalBasis& basis, int n, double a, double b);
// integral_a^b (v - a) phi_n(v) dv, 0 <= a <= b <= 1: the first moment about a, in closed form.
// With d = b - a and phi(a + d t) expanded in cos, sin and the two exponentials, it is
// d^2 integral_0^1 t phi(a + d t) dt, whose four kernels (integral_0^1 t cos(x t) dt, ...,
// x = beta_n d) are taken in closed form for x >= 1 and by their Taylor series below, where the
// closed forms cancel: full precision for any width. A linearly varying load p_a at a to p_b at
// b projects as p_a ModeIntegral + (p_b - p_a) ModeRampIntegral.
double ModeMoment(const ModalBasis& basis, int n, double a, double b);
// integral_a^b ((v - a) / (b - a)) phi_n(v) dv, 0 <= a <= b <= 1 (0 when a = b): ModeMoment / (b -
// a) without the division (d integral_0^1 t phi(a + d t) dt), the projection of a load rising
// from 0 at a to 1 at b.
double ModeRampIntegral(const ModalBasis& basis, int n, double a, double b);

// Tabulates phi_n(v_i) (and d phi_n/dv (v_i) if `slopes` is not empty) for the evaluation
// jobs, so a wire whose sample parameters are fixed evaluates its modes once:
//   values[i * basis.modes + n] = phi_n(samples[i]),   #samples * basis.modes doubles
//   slopes[i * basis.modes + n] = phi_n'(samples[i])   (per unit v; empty or the same size)
// Errors name "basis", "samples", "values" or "slopes". Never allocates.
Status TabulateModes(const ModalBasis& basis, std::span<const double> samples,
                     std::span<double> values, std::span<double> slopes);

}  // namespace wirerig
