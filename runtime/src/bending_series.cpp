// The paper's sine-series solutions, Eqs. (10)-(17), in normalised form (bending_internal.h).
// With p_n the sine coefficients of the load (Eq. 11 for point loads; the exact patch-load
// coefficients 2 q (cos n pi a - cos n pi b) / (n pi) for line loads, and for a linearly varying
// load p_a -> p_b over [a, b] (width d, middle m)
//   2/(n pi) [p_a cos(n pi a) - p_b cos(n pi b) + (p_b - p_a) cos(n pi m) sin(x)/x], x = n pi d/2,
// the integral of (v - a) sin(n pi v) over [a, b] written with sin(n pi b) - sin(n pi a) =
// 2 cos(n pi m) sin(x) so that a narrow load divides by nothing small),
//   A_n = p_n / (n^4 pi^4 EI_n),  B_n = n pi A_n,
//   X(v) = X0 + a1 v + a2 v^2 + a3 v^3 + sum_n A_n sin(n pi v),
// where the cubic's coefficients come from the boundary conditions through the sums
//   SB = sum B_n,  S1 = sum (-1)^n B_n,  S2 = sum (-1)^n p_n / (n pi EI_n).
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "bending_internal.h"

namespace wirerig::detail {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kBlock = 64;  // terms kept on the stack at a time

// p_n * compliance, i.e. p_n / EI_n.
Vec3 SeriesCoefficient(const BendingJob& job, int n, double compliance) {
  const double npi = n * kPi;
  Vec3 p = Vec3::Zero();
  for (const PointLoad& load : job.point_loads) p += 2.0 * std::sin(npi * load.at) * load.force;
  for (const LineLoad& load : job.line_loads)
    p += (2.0 * job.length * (std::cos(npi * load.from) - std::cos(npi * load.to)) / npi) *
         load.force_per_length;
  for (const LinearLineLoad& load : job.linear_line_loads) {
    const double x = 0.5 * npi * (load.to - load.from);  // > 0
    const double ramp = std::cos(0.5 * npi * (load.from + load.to)) * (std::sin(x) / x);
    p += (2.0 * job.length / npi) *
         ((std::cos(npi * load.from) - ramp) * load.start_force_per_length +
          (ramp - std::cos(npi * load.to)) * load.end_force_per_length);
  }
  return p * compliance;
}

struct SeriesPolynomial {
  Vec3 a1, a2, a3;
};

SeriesPolynomial SolveSeriesPolynomial(const BendingJob& job, double compliance) {
  Vec3 sb = Vec3::Zero(), s1 = Vec3::Zero(), s2 = Vec3::Zero();
  for (int n = 1; n <= job.series_terms; ++n) {
    const double npi = n * kPi;
    const Vec3 p = SeriesCoefficient(job, n, compliance);
    const Vec3 b = p / (npi * npi * npi);
    const double sign = (n % 2 == 0) ? 1.0 : -1.0;
    sb += b;
    s1 += sign * b;
    s2 += sign * p / npi;
  }
  const Vec3 q = -job.tip_force * compliance;
  const Vec3 x0_minus_x1 = job.start_displacement - job.end_displacement;
  switch (job.boundary) {
    case BoundaryCondition::kSimplySupported:
      return {-x0_minus_x1, Vec3::Zero(), Vec3::Zero()};  // Eq. (12)
    case BoundaryCondition::kClamped: {                   // Eq. (14)
      const Vec3 k2 = 1.5 * x0_minus_x1 - sb - 0.5 * s1;
      const Vec3 k3 = x0_minus_x1 - 0.5 * sb - 0.5 * s1;
      return {-sb, -2.0 * k2, 2.0 * k3};
    }
    case BoundaryCondition::kCantileverFree:  // Eq. (16)
      return {-sb, -0.5 * (q + s2) + job.tip_couple * (compliance / job.length) / 2.0,
              (q + s2) / 6.0};
    case BoundaryCondition::kCantileverGuided:  // Eq. (17)
      return {-sb, -0.5 * (0.5 * q - sb + s1 + 0.5 * s2), (q + s2) / 6.0};
  }
  return {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
}

}  // namespace

void RunSeriesBending(const BendingJob& job) {
  const double compliance = NormalizedCompliance(job);
  const double inv_length = 1.0 / job.length;
  const double inv_length2 = inv_length * inv_length;
  const bool want_slope = !job.slope.empty(), want_curvature = !job.curvature.empty();

  const SeriesPolynomial poly = SolveSeriesPolynomial(job, compliance);
  for (std::size_t i = 0; i < job.samples.size(); ++i) {
    const double v = job.samples[i];
    job.displacement[i] = job.start_displacement + v * (poly.a1 + v * (poly.a2 + v * poly.a3));
    if (want_slope) job.slope[i] = (poly.a1 + v * (2.0 * poly.a2 + 3.0 * v * poly.a3)) * inv_length;
    if (want_curvature) job.curvature[i] = (2.0 * poly.a2 + 6.0 * v * poly.a3) * inv_length2;
  }

  // Sine part, a block of terms at a time: A_n on the stack, sin/cos(n pi v) by rotation.
  std::array<Vec3, kBlock> a;
  for (int first = 1; first <= job.series_terms; first += kBlock) {
    const int count = std::min(kBlock, job.series_terms - first + 1);
    for (int k = 0; k < count; ++k) {
      const double npi = (first + k) * kPi;
      a[k] = SeriesCoefficient(job, first + k, compliance) / (npi * npi * npi * npi);
    }
    for (std::size_t i = 0; i < job.samples.size(); ++i) {
      const double x = kPi * job.samples[i];
      const double step_sin = std::sin(x), step_cos = std::cos(x);
      double s = step_sin, c = step_cos;  // sin, cos of first * x
      if (first > 1) s = std::sin(first * x), c = std::cos(first * x);
      Vec3 sum = Vec3::Zero(), dsum = Vec3::Zero(), ddsum = Vec3::Zero();
      for (int k = 0; k < count; ++k) {
        const double npi = (first + k) * kPi;
        sum += s * a[k];
        if (want_slope) dsum += (npi * c) * a[k];
        if (want_curvature) ddsum -= (npi * npi * s) * a[k];
        const double next_s = s * step_cos + c * step_sin;
        c = c * step_cos - s * step_sin;
        s = next_s;
      }
      job.displacement[i] += sum;
      if (want_slope) job.slope[i] += dsum * inv_length;
      if (want_curvature) job.curvature[i] += ddsum * inv_length2;
    }
  }
}

}  // namespace wirerig::detail
