#include "wirerig/runtime/modal_basis.h"

#include <cmath>
#include <numbers>

#include <Eigen/SVD>

#include "validation.h"

namespace wirerig {
namespace {

using Row = Eigen::Matrix<double, 1, 4>;

// The k-th derivative (k = -1: antiderivative) of the four basis functions cos(beta v),
// sin(beta v), exp(-beta v), exp(-beta (1 - v)), divided by beta^k. All bounded by 1.
Row BasisRow(double beta, double v, int k) {
  const double x = beta * v;
  const double c = std::cos(x), s = std::sin(x);
  const double e1 = std::exp(-x), e2 = std::exp(-beta * (1.0 - v));
  switch (k) {
    case -1:
      return Row(s, -c, -e1, e2);
    case 0:
      return Row(c, s, e1, e2);
    case 1:
      return Row(-s, c, -e1, e2);
    case 2:
      return Row(-c, -s, e1, e2);
    default:
      return Row(s, -c, -e1, e2);
  }
}

// Characteristic function of a family, scaled so that it stays O(1) for every beta.
double Characteristic(BoundaryCondition bc, double beta) {
  switch (bc) {
    case BoundaryCondition::kSimplySupported:
      return std::sin(beta);
    case BoundaryCondition::kClamped:
      return std::cos(beta) - 1.0 / std::cosh(beta);  // cos b cosh b = 1
    case BoundaryCondition::kCantileverFree:
      return std::cos(beta) + 1.0 / std::cosh(beta);  // cos b cosh b = -1
    case BoundaryCondition::kCantileverGuided:
      return std::sin(beta) + std::cos(beta) * std::tanh(beta);  // tan b + tanh b = 0
  }
  return 0.0;
}

// Bracket [lo, hi] of the root of mode index n (0-based); each holds exactly one root.
void Bracket(BoundaryCondition bc, int n, double* lo, double* hi) {
  const double pi = std::numbers::pi;
  switch (bc) {
    case BoundaryCondition::kSimplySupported:  // n pi
      *lo = (n + 0.5) * pi;
      *hi = (n + 1.5) * pi;
      return;
    case BoundaryCondition::kClamped:  // near (n + 1.5) pi
      *lo = (n + 1.0) * pi;
      *hi = (n + 2.0) * pi;
      return;
    case BoundaryCondition::kCantileverFree:  // near (n + 0.5) pi
      *lo = n * pi;
      *hi = (n + 1.0) * pi;
      return;
    case BoundaryCondition::kCantileverGuided:  // near (n + 0.75) pi
      *lo = (n + 0.5) * pi;
      *hi = (n + 1.0) * pi;
      return;
  }
}

// Bisection to the last representable double: the characteristic functions have slopes of
// order 1 at their roots, so beta is found to a few ulp.
double SolveRoot(BoundaryCondition bc, double lo, double hi) {
  double f_lo = Characteristic(bc, lo);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    const double f_mid = Characteristic(bc, mid);
    if (f_mid == 0.0) return mid;
    if ((f_mid < 0.0) == (f_lo < 0.0)) {
      lo = mid;
      f_lo = f_mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

// The derivative orders fixed to zero at v = 0 and at v = 1.
void BoundaryOrders(BoundaryCondition bc, int start[2], int end[2]) {
  const bool ss = bc == BoundaryCondition::kSimplySupported;
  start[0] = 0;
  start[1] = ss ? 2 : 1;
  switch (bc) {
    case BoundaryCondition::kSimplySupported:
      end[0] = 0, end[1] = 2;
      break;
    case BoundaryCondition::kClamped:
      end[0] = 0, end[1] = 1;
      break;
    case BoundaryCondition::kCantileverFree:
      end[0] = 2, end[1] = 3;
      break;
    case BoundaryCondition::kCantileverGuided:
      end[0] = 1, end[1] = 3;
      break;
  }
}

// The kernels of ModeMoment for x >= 0:
//   c = integral_0^1 t cos(x t) dt = (x sin x + cos x - 1) / x^2,
//   s = integral_0^1 t sin(x t) dt = (sin x - x cos x) / x^2,
//   e = integral_0^1 t exp(-x t) dt = (1 - (1 + x) exp(-x)) / x^2,
//   f = integral_0^1 (1 - t) exp(-x t) dt = (x + expm1(-x)) / x^2,
// the closed forms from x = 1 on (they lose at most a few digits there) and below it the
// Taylor series sum_k (-x)^k/k! times 1/(k+2) (e), 1/((k+1)(k+2)) (f), and the even (c) or
// odd (s) terms with alternating signs; 22 terms reach 1/22! < 1e-21.
struct MomentKernels {
  double c, s, e, f;
};

MomentKernels Kernels(double x) {
  MomentKernels k{0.0, 0.0, 0.0, 0.0};
  if (x >= 1.0) {
    const double inv2 = 1.0 / (x * x);
    const double sin_x = std::sin(x), cos_x = std::cos(x), exp_x = std::exp(-x);
    k.c = (x * sin_x + cos_x - 1.0) * inv2;
    k.s = (sin_x - x * cos_x) * inv2;
    k.e = (-std::expm1(-x) - x * exp_x) * inv2;
    k.f = (x + std::expm1(-x)) * inv2;
    return k;
  }
  double power = 1.0;  // x^j / j!
  for (int j = 0; j < 22; ++j) {
    const double sign = (j % 2 == 0) ? 1.0 : -1.0;  // (-1)^j
    k.e += sign * power / (j + 2);
    k.f += sign * power / ((j + 1) * (j + 2));
    const double trig = (j % 4 < 2) ? 1.0 : -1.0;  // (-1)^(j/2) for even j, ((j-1)/2) for odd
    if (j % 2 == 0)
      k.c += trig * power / (j + 2);
    else
      k.s += trig * power / (j + 2);
    power *= x / (j + 1);
  }
  return k;
}

// integral_0^1 t phi_n(a + d t) dt.
double MomentIntegrand(const ModalBasis& basis, int n, double a, double d) {
  const double beta = basis.beta[n];
  const std::array<double, 4>& c = basis.coefficients[n];
  const MomentKernels k = Kernels(beta * d);
  const double cos_a = std::cos(beta * a), sin_a = std::sin(beta * a);
  // cos(beta (a + d t)) = cos_a cos(x t) - sin_a sin(x t), likewise sin; exp(-beta (a + d t)) =
  // exp(-beta a) exp(-x t); exp(-beta (1 - a - d t)) = exp(-beta (1 - b)) exp(-x (1 - t)),
  // whose moment is integral_0^1 t exp(-x (1 - t)) dt = f.
  return c[0] * (cos_a * k.c - sin_a * k.s) + c[1] * (sin_a * k.c + cos_a * k.s) +
         c[2] * std::exp(-beta * a) * k.e + c[3] * std::exp(-beta * (1.0 - (a + d))) * k.f;
}

double Dot(const std::array<double, 4>& c, const Row& r) {
  return c[0] * r[0] + c[1] * r[1] + c[2] * r[2] + c[3] * r[3];
}

}  // namespace

Status BuildModalBasis(BoundaryCondition boundary, int modes, ModalBasis* out) {
  if (Status s = detail::CheckBoundary("boundary", boundary); !s) return s;
  if (modes < 1 || modes > ModalBasis::kMaxModes)
    return Status::Invalid("modes", "must lie in [1, 32]");
  if (out == nullptr) return Status::Invalid("out", "must not be null");

  ModalBasis basis;
  basis.boundary = boundary;
  basis.modes = modes;
  int start[2], end[2];
  BoundaryOrders(boundary, start, end);
  for (int n = 0; n < modes; ++n) {
    double beta = (n + 1) * std::numbers::pi;  // simply supported: exact
    if (boundary != BoundaryCondition::kSimplySupported) {
      double lo = 0.0, hi = 0.0;
      Bracket(boundary, n, &lo, &hi);
      beta = SolveRoot(boundary, lo, hi);
    }
    // Coefficients: the null vector of the boundary conditions in the bounded basis.
    Eigen::Matrix4d m;
    m.row(0) = BasisRow(beta, 0.0, start[0]);
    m.row(1) = BasisRow(beta, 0.0, start[1]);
    m.row(2) = BasisRow(beta, 1.0, end[0]);
    m.row(3) = BasisRow(beta, 1.0, end[1]);
    const Eigen::JacobiSVD<Eigen::Matrix4d> svd(m, Eigen::ComputeFullV);
    const Eigen::Vector4d null = svd.matrixV().col(3);
    std::array<double, 4> c = {null[0], null[1], null[2], null[3]};

    // integral_0^1 phi^2 dv from the boundary values (psi_k = phi^(k) / beta^k):
    //   4 beta^4 phi^2 = d/dv [ v (beta^4 phi^2 - 2 phi' phi''' + phi''^2) + 3 phi phi''' - phi'
    //   phi'' ]
    // (differentiate and use phi'''' = beta^4 phi), hence
    //   integral = [v (psi0^2 - 2 psi1 psi3 + psi2^2)]_0^1 / 4 + [3 psi0 psi3 - psi1 psi2]_0^1 / (4
    //   beta).
    double psi0[4], psi1[4];
    for (int k = 0; k < 4; ++k) {
      psi0[k] = Dot(c, BasisRow(beta, 0.0, k));
      psi1[k] = Dot(c, BasisRow(beta, 1.0, k));
    }
    const double norm2 = 0.25 * (psi1[0] * psi1[0] - 2.0 * psi1[1] * psi1[3] + psi1[2] * psi1[2]) +
                         0.25 / beta *
                             ((3.0 * psi1[0] * psi1[3] - psi1[1] * psi1[2]) -
                              (3.0 * psi0[0] * psi0[3] - psi0[1] * psi0[2]));
    const double first = boundary == BoundaryCondition::kSimplySupported ? psi0[1] : psi0[2];
    const double scale = (first < 0.0 ? -1.0 : 1.0) / std::sqrt(norm2);
    for (double& x : c) x *= scale;

    basis.beta[n] = beta;
    basis.coefficients[n] = c;
    basis.integral[n] = (Dot(c, BasisRow(beta, 1.0, -1)) - Dot(c, BasisRow(beta, 0.0, -1))) / beta;
    basis.end_value[n] = Dot(c, BasisRow(beta, 1.0, 0));
    basis.decay[n] = std::exp(-beta);
    basis.moment[n] = ModeMoment(basis, n, 0.0, 1.0);
  }
  *out = basis;
  return Status::Ok();
}

double ModeValue(const ModalBasis& basis, int n, double v) {
  const double beta = basis.beta[n];
  const std::array<double, 4>& c = basis.coefficients[n];
  const double x = beta * v;
  const double e1 = std::exp(-x);
  return c[0] * std::cos(x) + c[1] * std::sin(x) + c[2] * e1 + c[3] * (basis.decay[n] / e1);
}

double ModeSlope(const ModalBasis& basis, int n, double v) {
  const double beta = basis.beta[n];
  const std::array<double, 4>& c = basis.coefficients[n];
  const double x = beta * v;
  return beta * (-c[0] * std::sin(x) + c[1] * std::cos(x) - c[2] * std::exp(-x) +
                 c[3] * std::exp(x - beta));
}

void EvaluateMode(const ModalBasis& basis, int n, double v, double* value, double* slope) {
  const double beta = basis.beta[n];
  const std::array<double, 4>& c = basis.coefficients[n];
  const double x = beta * v;
  const double cos_x = std::cos(x), sin_x = std::sin(x);
  // exp(-x) and exp(x - beta) = exp(-beta) / exp(-x): beta <= 106, so neither underflows.
  const double e1 = std::exp(-x), e2 = basis.decay[n] / e1;
  *value = c[0] * cos_x + c[1] * sin_x + c[2] * e1 + c[3] * e2;
  *slope = beta * (-c[0] * sin_x + c[1] * cos_x - c[2] * e1 + c[3] * e2);
}

double ModeIntegral(const ModalBasis& basis, int n, double a, double b) {
  const double beta = basis.beta[n];
  const std::array<double, 4>& c = basis.coefficients[n];
  const auto antiderivative = [&](double v) {
    const double x = beta * v;
    return c[0] * std::sin(x) - c[1] * std::cos(x) - c[2] * std::exp(-x) +
           c[3] * std::exp(x - beta);
  };
  return (antiderivative(b) - antiderivative(a)) / beta;
}

double ModeMoment(const ModalBasis& basis, int n, double a, double b) {
  const double d = b - a;
  return d * d * MomentIntegrand(basis, n, a, d);
}

double ModeRampIntegral(const ModalBasis& basis, int n, double a, double b) {
  const double d = b - a;
  return d * MomentIntegrand(basis, n, a, d);
}

Status TabulateModes(const ModalBasis& basis, std::span<const double> samples,
                     std::span<double> values, std::span<double> slopes) {
  if (basis.modes < 1 || basis.modes > ModalBasis::kMaxModes)
    return Status::Invalid("basis", "is not built (modes must lie in [1, 32])");
  if (samples.empty()) return Status::Invalid("samples", "needs at least one sample");
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (!std::isfinite(samples[i]) || samples[i] < 0.0 || samples[i] > 1.0)
      return Status::InvalidElement("samples", static_cast<int>(i), "", "must lie in [0, 1]");
  const std::size_t size = samples.size() * std::size_t(basis.modes);
  if (values.size() != size) return Status::Invalid("values", "must hold samples x modes values");
  if (!slopes.empty() && slopes.size() != size)
    return Status::Invalid("slopes", "must be empty or hold samples x modes values");
  for (std::size_t i = 0; i < samples.size(); ++i)
    for (int n = 0; n < basis.modes; ++n) {
      double value = 0.0, slope = 0.0;
      EvaluateMode(basis, n, samples[i], &value, &slope);
      values[i * basis.modes + n] = value;
      if (!slopes.empty()) slopes[i * basis.modes + n] = slope;
    }
  return Status::Ok();
}

}  // namespace wirerig
