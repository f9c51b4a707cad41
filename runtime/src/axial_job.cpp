#include "wirerig/runtime/axial_job.h"

#include <algorithm>
#include <cmath>

#include "validation.h"

namespace wirerig {
namespace {

// g(v, u) of PHYSICS.md section 3 with d = v - v0, e = u - v0.
double Influence(double d, double e) {
  return d * e > 0.0 ? std::min(std::abs(d), std::abs(e)) : 0.0;
}

// integral of min(d, t) dt over t in [lo, hi], with 0 <= lo <= hi and d >= 0.
double IntegralOfMin(double d, double lo, double hi) {
  if (d <= lo) return d * (hi - lo);
  if (d >= hi) return (hi * hi - lo * lo) / 2.0;
  return (d * d - lo * lo) / 2.0 + d * (hi - d);
}

// integral of g(v, u) du over u in [a, b]: the influence of a uniform unit line load.
double LineInfluence(double v, double v0, double a, double b) {
  const double d = v - v0;
  if (d > 0.0 && b > v0) return IntegralOfMin(d, std::max(a, v0) - v0, b - v0);
  if (d < 0.0 && a < v0) return IntegralOfMin(-d, v0 - std::min(b, v0), v0 - a);
  return 0.0;
}

// Length of [a, b] intersected with [lo, hi].
double Overlap(double a, double b, double lo, double hi) {
  return std::max(0.0, std::min(b, hi) - std::max(a, lo));
}

}  // namespace

Status AxialJob::Validate() const {
  if (Status s = detail::CheckPositive("length", length, "must be positive and finite (m)"); !s)
    return s;
  if (Status s = detail::CheckPositive("axial_stiffness", axial_stiffness,
                                       "must be positive and finite (N)");
      !s)
    return s;
  if (!detail::InUnitInterval(fixed_at)) return Status::Invalid("fixed_at", "must lie in [0, 1]");
  double load_sum = 0.0;
  for (std::size_t i = 0; i < point_loads.size(); ++i) {
    const int index = static_cast<int>(i);
    if (Status s = detail::CheckLoadPosition("point_loads", index, point_loads[i].at); !s) return s;
    if (!std::isfinite(point_loads[i].force))
      return Status::InvalidElement("point_loads", index, "force", "must be finite (N)");
    load_sum += std::abs(point_loads[i].force);
  }
  for (std::size_t i = 0; i < line_loads.size(); ++i) {
    const AxialLineLoad& load = line_loads[i];
    const int index = static_cast<int>(i);
    if (Status s = detail::CheckLoadExtent("line_loads", index, load.from, load.to); !s) return s;
    if (!std::isfinite(load.force_per_length))
      return Status::InvalidElement("line_loads", index, "force_per_length",
                                    "must be finite (N/m)");
    load_sum += std::abs(load.force_per_length) * length * (load.to - load.from);
  }
  const double bound = length / axial_stiffness * load_sum;
  if (!(std::isfinite(bound) && bound < detail::kMaxDeflectionBound))
    return Status::Invalid("loads", "too large for the stiffness: the displacement would overflow");
  if (Status s = detail::CheckSamples(samples); !s) return s;
  if (Status s = detail::CheckOutput("displacement", displacement.size(), samples.size(), true); !s)
    return s;
  return detail::CheckOutput("normal_force", normal_force.size(), samples.size(), false);
}

Status AxialJob::Run() const {
  if (Status s = Validate(); !s) return s;
  const double compliance = length / axial_stiffness;  // EA -> EA / L (PHYSICS.md section 0)
  const double v0 = fixed_at;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double v = samples[i];
    double sum = 0.0;
    for (const AxialPointLoad& load : point_loads)
      sum += load.force * Influence(v - v0, load.at - v0);
    for (const AxialLineLoad& load : line_loads)
      sum += load.force_per_length * length * LineInfluence(v, v0, load.from, load.to);
    displacement[i] = compliance * sum;
  }
  if (normal_force.empty()) return Status::Ok();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double v = samples[i];
    // Above the support N sums the loads beyond v; below it, minus the loads before v. At the
    // wire's ends too, the interior side's value: a load on the end face counts.
    const bool above = v > v0 || (v == v0 && v0 < 1.0);
    double n = 0.0;
    for (const AxialPointLoad& load : point_loads) {
      if (above && (load.at > v || (v == 1.0 && load.at == 1.0))) n += load.force;
      if (!above && (load.at < v || (v == 0.0 && load.at == 0.0))) n -= load.force;
    }
    for (const AxialLineLoad& load : line_loads) {
      const double f = load.force_per_length * length;
      n += above ? f * Overlap(load.from, load.to, v, 1.0)
                 : -f * Overlap(load.from, load.to, 0.0, v);
    }
    normal_force[i] = n;
  }
  return Status::Ok();
}

}  // namespace wirerig
