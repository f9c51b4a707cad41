#include "wirerig/runtime/bending_job.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bending_internal.h"
#include "validation.h"

namespace wirerig {
namespace {
// Elementwise: Eigen's allFinite() computes x - x, which raises FE_INVALID on infinities.
bool AllFinite(const Vec3& x) {
  return std::isfinite(x.x()) && std::isfinite(x.y()) && std::isfinite(x.z());
}
}  // namespace

std::string_view ToString(BoundaryCondition bc) {
  switch (bc) {
    case BoundaryCondition::kSimplySupported:
      return "simply_supported";
    case BoundaryCondition::kClamped:
      return "clamped";
    case BoundaryCondition::kCantileverFree:
      return "cantilever_free";
    case BoundaryCondition::kCantileverGuided:
      return "cantilever_guided";
  }
  return "unknown";
}

bool ParseBoundaryCondition(std::string_view name, BoundaryCondition* out) {
  for (BoundaryCondition bc :
       {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped,
        BoundaryCondition::kCantileverFree, BoundaryCondition::kCantileverGuided}) {
    if (ToString(bc) == name) {
      *out = bc;
      return true;
    }
  }
  return false;
}

bool IsCantilever(BoundaryCondition bc) {
  return bc == BoundaryCondition::kCantileverFree || bc == BoundaryCondition::kCantileverGuided;
}

std::string_view ToString(BendingMode mode) {
  switch (mode) {
    case BendingMode::kExact:
      return "exact";
    case BendingMode::kSeries:
      return "series";
  }
  return "unknown";
}

bool ParseBendingMode(std::string_view name, BendingMode* out) {
  if (name == "exact")
    *out = BendingMode::kExact;
  else if (name == "series")
    *out = BendingMode::kSeries;
  else
    return false;
  return true;
}

Status BendingJob::Validate() const {
  if (Status s = detail::CheckBoundary("boundary", boundary); !s) return s;
  switch (mode) {
    case BendingMode::kExact:
      break;
    case BendingMode::kSeries:
      if (series_terms < 1 || series_terms > kMaxSeriesTerms)
        return Status::Invalid("series_terms", "must lie in [1, 100000]");
      break;
    default:
      return Status::Invalid("mode", "unknown bending mode");
  }
  if (Status s = detail::CheckPositive("length", length, "must be positive and finite (m)"); !s)
    return s;
  // Curvature is scaled by 1 / L^2 (compared, not computed: callers may trap overflow).
  if (length < 1.0 / std::sqrt(std::numeric_limits<double>::max()))
    return Status::Invalid("length", "too small: 1/L^2 overflows (m)");
  if (Status s = detail::CheckPositive("bending_stiffness", bending_stiffness,
                                       "must be positive and finite (N m^2)");
      !s)
    return s;
  const double compliance = detail::NormalizedCompliance(*this);
  if (!std::isfinite(compliance))
    return Status::Invalid("bending_stiffness", "too small for the length: L^3/EI overflows");
  if (!AllFinite(start_displacement))
    return Status::Invalid("start_displacement", "must be finite (m)");
  if (!AllFinite(end_displacement))
    return Status::Invalid("end_displacement", "must be finite (m)");
  if (!AllFinite(tip_force)) return Status::Invalid("tip_force", "must be finite (N)");
  if (!IsCantilever(boundary) && !tip_force.isZero(0.0))
    return Status::Invalid("tip_force", "applies to cantilevers only");

  if (!AllFinite(tip_couple)) return Status::Invalid("tip_couple", "must be finite (N m)");
  if (boundary != BoundaryCondition::kCantileverFree && !tip_couple.isZero(0.0))
    return Status::Invalid("tip_couple", "applies to free cantilevers only");

  double load_sum = tip_force.lpNorm<1>() + tip_couple.lpNorm<1>() / length;
  for (std::size_t i = 0; i < point_loads.size(); ++i) {
    const int index = static_cast<int>(i);
    if (Status s = detail::CheckLoadPosition("point_loads", index, point_loads[i].at); !s) return s;
    if (!AllFinite(point_loads[i].force))
      return Status::InvalidElement("point_loads", index, "force", "must be finite (N)");
    load_sum += point_loads[i].force.lpNorm<1>();
  }
  for (std::size_t i = 0; i < line_loads.size(); ++i) {
    const LineLoad& load = line_loads[i];
    const int index = static_cast<int>(i);
    if (Status s = detail::CheckLoadExtent("line_loads", index, load.from, load.to); !s) return s;
    if (!AllFinite(load.force_per_length))
      return Status::InvalidElement("line_loads", index, "force_per_length",
                                    "must be finite (N/m)");
    load_sum += load.force_per_length.lpNorm<1>() * length * (load.to - load.from);
  }
  for (std::size_t i = 0; i < linear_line_loads.size(); ++i) {
    const LinearLineLoad& load = linear_line_loads[i];
    const int index = static_cast<int>(i);
    if (Status s = detail::CheckLoadExtent("linear_line_loads", index, load.from, load.to); !s)
      return s;
    if (!AllFinite(load.start_force_per_length))
      return Status::InvalidElement("linear_line_loads", index, "start_force_per_length",
                                    "must be finite (N/m)");
    if (!AllFinite(load.end_force_per_length))
      return Status::InvalidElement("linear_line_loads", index, "end_force_per_length",
                                    "must be finite (N/m)");
    // The trapezoid's total load, bounded by its mean end value times its length.
    load_sum += 0.5 *
                (load.start_force_per_length.lpNorm<1>() + load.end_force_per_length.lpNorm<1>()) *
                length * (load.to - load.from);
  }
  const double bound =
      start_displacement.lpNorm<1>() + end_displacement.lpNorm<1>() + compliance * load_sum;
  if (!(std::isfinite(bound) && bound < detail::kMaxDeflectionBound))
    return Status::Invalid("loads", "too large for the stiffness: the deflection would overflow");
  if (Status s = detail::CheckSamples(samples); !s) return s;
  if (Status s = detail::CheckOutput("displacement", displacement.size(), samples.size(), true); !s)
    return s;
  if (Status s = detail::CheckOutput("slope", slope.size(), samples.size(), false); !s) return s;
  if (Status s = detail::CheckOutput("curvature", curvature.size(), samples.size(), false); !s)
    return s;
  return Status::Ok();
}

Status BendingJob::Run() const {
  const Status status = Validate();
  if (!status) return status;
  if (mode == BendingMode::kExact)
    detail::RunExactBending(*this);
  else
    detail::RunSeriesBending(*this);
  return Status::Ok();
}

namespace detail {
namespace {

// A linearly varying load's Macaulay terms (bending_job.h): with t_a = <v-a>, t_b = <v-b> and
// d = b - a, the k-th derivative of its particular solution is
//   M^(k) = p_a (t_a^j/j! - R_j) + p_b (R_j - t_b^j/j!),   j = 4 - k,
//   R_j = (t_a^(j+1) - t_b^(j+1)) / ((j+1)! d).
// Before b (t_b = 0, t_a <= d) R_j = (t_a/d) t_a^j/(j+1)!; past b, where t_a - t_b = d,
// R_j = (t_a^j + t_a^(j-1) t_b + ... + t_b^j)/(j+1)!: no division by a small width.
struct RampTerms {
  double ramp[4];   // R_j, j = 4, 3, 2, 1 (for M, M', M'', M''')
  double start[4];  // t_a^j / j!
  double end[4];    // t_b^j / j!
};

RampTerms MacaulayRamp(double ta, double tb, double width) {
  RampTerms r;
  const double ta2 = ta * ta, ta3 = ta2 * ta, ta4 = ta2 * ta2;
  const double tb2 = tb * tb, tb3 = tb2 * tb, tb4 = tb2 * tb2;
  r.start[0] = ta4 / 24.0, r.start[1] = ta3 / 6.0, r.start[2] = ta2 / 2.0, r.start[3] = ta;
  r.end[0] = tb4 / 24.0, r.end[1] = tb3 / 6.0, r.end[2] = tb2 / 2.0, r.end[3] = tb;
  if (tb <= 0.0) {
    const double f = std::min(ta / width, 1.0);
    r.ramp[0] = f * ta4 / 120.0, r.ramp[1] = f * ta3 / 24.0;
    r.ramp[2] = f * ta2 / 6.0, r.ramp[3] = f * ta / 2.0;
  } else {
    const double s1 = ta + tb;
    const double s2 = ta2 + ta * tb + tb2;
    const double s3 = (ta2 + tb2) * s1;
    const double s4 = ta4 + ta3 * tb + ta2 * tb2 + ta * tb3 + tb4;
    r.ramp[0] = s4 / 120.0, r.ramp[1] = s3 / 24.0, r.ramp[2] = s2 / 6.0, r.ramp[3] = s1 / 2.0;
  }
  return r;
}

// M^(k) of a linear load from its terms (p_a, p_b per unit v).
Vec3 RampDerivative(const RampTerms& r, int k, const Vec3& pa, const Vec3& pb) {
  return pa * (r.start[k] - r.ramp[k]) + pb * (r.ramp[k] - r.end[k]);
}

}  // namespace

ExactPolynomial SolveExactPolynomial(const BendingJob& job, double compliance) {
  // m_k = M^(k)(1) (PHYSICS.md section 2), accumulated without the compliance factor.
  Vec3 m0 = Vec3::Zero(), m1 = Vec3::Zero(), m2 = Vec3::Zero(), m3 = Vec3::Zero();
  for (const PointLoad& load : job.point_loads) {
    const double w = 1.0 - load.at;
    m0 += load.force * (w * w * w / 6.0);
    m1 += load.force * (w * w / 2.0);
    m2 += load.force * w;
    m3 += load.force;
  }
  for (const LineLoad& load : job.line_loads) {
    const Vec3 q = load.force_per_length * job.length;  // per unit v
    const double wa = 1.0 - load.from, wb = 1.0 - load.to;
    m0 += q * ((wa * wa * wa * wa - wb * wb * wb * wb) / 24.0);
    m1 += q * ((wa * wa * wa - wb * wb * wb) / 6.0);
    m2 += q * ((wa * wa - wb * wb) / 2.0);
    m3 += q * (load.to - load.from);
  }
  for (const LinearLineLoad& load : job.linear_line_loads) {
    const Vec3 pa = load.start_force_per_length * job.length;  // per unit v
    const Vec3 pb = load.end_force_per_length * job.length;
    const RampTerms r = MacaulayRamp(1.0 - load.from, 1.0 - load.to, load.to - load.from);
    m0 += RampDerivative(r, 0, pa, pb);
    m1 += RampDerivative(r, 1, pa, pb);
    m2 += RampDerivative(r, 2, pa, pb);
    m3 += RampDerivative(r, 3, pa, pb);
  }
  m0 *= compliance;
  m1 *= compliance;
  m2 *= compliance;
  m3 *= compliance;
  const Vec3 q_tip = -job.tip_force * compliance;
  const Vec3 couple = job.tip_couple * (compliance / job.length);  // tip couple L^2 / EI
  const Vec3 d = job.end_displacement - job.start_displacement;
  switch (job.boundary) {
    case BoundaryCondition::kSimplySupported:
      return {d - m0 + m2 / 6.0, Vec3::Zero(), -m2 / 6.0};
    case BoundaryCondition::kClamped:
      return {Vec3::Zero(), 3.0 * d + m1 - 3.0 * m0, -2.0 * d + 2.0 * m0 - m1};
    case BoundaryCondition::kCantileverFree:
      return {Vec3::Zero(), (m3 - m2 - q_tip + couple) / 2.0, (q_tip - m3) / 6.0};
    case BoundaryCondition::kCantileverGuided:
      return {Vec3::Zero(), -(q_tip - m3) / 4.0 - m1 / 2.0, (q_tip - m3) / 6.0};
  }
  return {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
}

namespace {

// Evaluates X (and optionally dX/dv, d2X/dv2) at every sample; derivatives are converted to
// arc length on output. Templated so the displacement-only loop carries no branches.
template <bool kSlope, bool kCurvature>
void EvaluateExact(const BendingJob& job, const ExactPolynomial& poly, double compliance) {
  const double inv_length = 1.0 / job.length;
  const Vec3 x0 = job.start_displacement;
  for (std::size_t i = 0; i < job.samples.size(); ++i) {
    const double v = job.samples[i];
    Vec3 m = Vec3::Zero(), dm = Vec3::Zero(), ddm = Vec3::Zero();
    for (const PointLoad& load : job.point_loads) {
      const double t = std::max(v - load.at, 0.0);
      m += load.force * (t * t * t / 6.0);
      if constexpr (kSlope) dm += load.force * (t * t / 2.0);
      if constexpr (kCurvature) ddm += load.force * t;
    }
    for (const LineLoad& load : job.line_loads) {
      const Vec3 q = load.force_per_length * job.length;
      const double ta = std::max(v - load.from, 0.0), tb = std::max(v - load.to, 0.0);
      const double ta2 = ta * ta, tb2 = tb * tb;
      m += q * ((ta2 * ta2 - tb2 * tb2) / 24.0);
      if constexpr (kSlope) dm += q * ((ta2 * ta - tb2 * tb) / 6.0);
      if constexpr (kCurvature) ddm += q * ((ta2 - tb2) / 2.0);
    }
    for (const LinearLineLoad& load : job.linear_line_loads) {
      const Vec3 pa = load.start_force_per_length * job.length;
      const Vec3 pb = load.end_force_per_length * job.length;
      const RampTerms r = MacaulayRamp(std::max(v - load.from, 0.0), std::max(v - load.to, 0.0),
                                       load.to - load.from);
      m += RampDerivative(r, 0, pa, pb);
      if constexpr (kSlope) dm += RampDerivative(r, 1, pa, pb);
      if constexpr (kCurvature) ddm += RampDerivative(r, 2, pa, pb);
    }
    job.displacement[i] = x0 + v * (poly.c1 + v * (poly.c2 + v * poly.c3)) + compliance * m;
    if constexpr (kSlope)
      job.slope[i] =
          (poly.c1 + v * (2.0 * poly.c2 + 3.0 * v * poly.c3) + compliance * dm) * inv_length;
    if constexpr (kCurvature)
      job.curvature[i] =
          (2.0 * poly.c2 + 6.0 * v * poly.c3 + compliance * ddm) * (inv_length * inv_length);
  }
}

}  // namespace

void RunExactBending(const BendingJob& job) {
  const double compliance = NormalizedCompliance(job);
  const ExactPolynomial poly = SolveExactPolynomial(job, compliance);
  if (FitsSegmentedBending(job)) {
    RunSegmentedBending(job, poly, compliance);
    return;
  }
  const bool slope = !job.slope.empty(), curvature = !job.curvature.empty();
  if (slope && curvature)
    EvaluateExact<true, true>(job, poly, compliance);
  else if (slope)
    EvaluateExact<true, false>(job, poly, compliance);
  else if (curvature)
    EvaluateExact<false, true>(job, poly, compliance);
  else
    EvaluateExact<false, false>(job, poly, compliance);
}

}  // namespace detail
}  // namespace wirerig
