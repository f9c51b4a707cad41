#include "wirerig/runtime/wire_ik.h"

#include <array>
#include <cmath>

#include "validation.h"

namespace wirerig {
namespace {

bool AllFinite(const Vec3& x) {
  return std::isfinite(x.x()) && std::isfinite(x.y()) && std::isfinite(x.z());
}

// A BendingJob of the wire with no loads, sampled at the target (the caller adds loads).
BendingJob BareWire(const WireIkJob& job, const double* sample, Vec3* out) {
  BendingJob wire;
  wire.boundary = job.boundary;
  wire.length = job.length;
  wire.bending_stiffness = job.bending_stiffness;
  wire.samples = std::span<const double>(sample, 1);
  wire.displacement = std::span<Vec3>(out, 1);
  return wire;
}

}  // namespace

Status WireIkJob::Validate() const {
  // The wire and its fixed loads, checked by BendingJob itself.
  Vec3 scratch = Vec3::Zero();
  const double v = target_at;
  BendingJob wire = BareWire(*this, &v, &scratch);
  wire.start_displacement = start_displacement;
  wire.end_displacement = end_displacement;
  wire.tip_force = fixed_tip_force;
  wire.point_loads = fixed_point_loads;
  wire.line_loads = fixed_line_loads;
  wire.samples = {};
  wire.displacement = {};
  if (Status s = wire.Validate(); s.field != "samples") {
    if (s.field == "tip_force") return Status::Invalid("fixed_tip_force", s.reason);
    if (s.field == "point_loads")
      return Status::InvalidElement("fixed_point_loads", s.index, s.member, s.reason);
    if (s.field == "line_loads")
      return Status::InvalidElement("fixed_line_loads", s.index, s.member, s.reason);
    if (!s.ok()) return s;
  }
  if (!AllFinite(axis) || !(axis.norm() > 0.5 && axis.norm() < 2.0))
    return Status::Invalid("axis", "must be a finite unit vector");
  if (!detail::InUnitInterval(target_at)) return Status::Invalid("target_at", "must lie in [0, 1]");
  if (!AllFinite(target) || !(target.lpNorm<1>() < detail::kMaxDeflectionBound))
    return Status::Invalid("target", "must be finite (m)");
  switch (basis) {
    case WireIkBasis::kTipForce:
      if (!IsCantilever(boundary))
        return Status::Invalid("basis", "a tip force needs a cantilever; use point loads");
      if (forces.size() != 1) return Status::Invalid("forces", "must have one element");
      break;
    case WireIkBasis::kPointLoads:
      if (load_at.empty() || load_at.size() > static_cast<std::size_t>(kMaxLoads))
        return Status::Invalid("load_at", "needs 1 to 8 load positions");
      for (std::size_t i = 0; i < load_at.size(); ++i)
        if (!detail::InUnitInterval(load_at[i]))
          return Status::InvalidElement("load_at", static_cast<int>(i), "", "must lie in [0, 1]");
      if (forces.size() != load_at.size())
        return Status::Invalid("forces", "must have one element per load position");
      break;
    default:
      return Status::Invalid("basis", "unknown load basis");
  }
  if (std::isnan(max_force) || !(max_force > 0.0))
    return Status::Invalid("max_force", "must be positive (N; infinity for no limit)");
  if (result == nullptr) return Status::Invalid("result", "must not be null");
  return Status::Ok();
}

Status WireIkJob::Run() const {
  if (Status s = Validate(); !s) return s;
  const double v = target_at;
  // Displacement under the fixed loads.
  Vec3 fixed = Vec3::Zero();
  {
    BendingJob wire = BareWire(*this, &v, &fixed);
    wire.start_displacement = start_displacement;
    wire.end_displacement = end_displacement;
    wire.tip_force = fixed_tip_force;
    wire.point_loads = fixed_point_loads;
    wire.line_loads = fixed_line_loads;
    (void)wire.Run();
  }
  // Influence coefficients: the displacement under a unit load of each basis member.
  std::array<double, kMaxLoads> g{};
  const std::size_t count = basis == WireIkBasis::kTipForce ? 1 : load_at.size();
  for (std::size_t i = 0; i < count; ++i) {
    Vec3 x = Vec3::Zero();
    BendingJob wire = BareWire(*this, &v, &x);
    const std::array<PointLoad, 1> unit = {
        PointLoad{basis == WireIkBasis::kTipForce ? 1.0 : load_at[i], Vec3::UnitX()}};
    if (basis == WireIkBasis::kTipForce)
      wire.tip_force = Vec3::UnitX();
    else
      wire.point_loads = unit;
    (void)wire.Run();
    g[i] = x.x();
  }
  double g2 = 0.0;
  for (std::size_t i = 0; i < count; ++i) g2 += g[i] * g[i];

  WireIkResult& out = *result;
  out = WireIkResult{};
  const Vec3 a = axis.normalized();
  const Vec3 d = target - fixed;
  const Vec3 d_axial = d.dot(a) * a;
  const Vec3 d_lateral = d - d_axial;
  out.axial_component = d_axial.norm() > 1e-12 * length;
  // A point moves less than 1e-14 of the compliance L^3/EI under unit loads: pinned.
  const double compliance = length * length * length / bending_stiffness;
  const bool movable = std::sqrt(g2) > 1e-14 * compliance;
  out.pinned = !movable && d_lateral.norm() > 1e-12 * length;
  Vec3 scale = Vec3::Zero();  // F_i = g_i * scale
  if (movable) {
    scale = d_lateral / g2;
    const double norm = d_lateral.norm() / std::sqrt(g2);  // |F| stacked
    if (norm > max_force) {
      out.force_limited = true;
      scale *= max_force / norm;
    }
  }
  for (std::size_t i = 0; i < count; ++i) forces[i] = g[i] * scale;
  out.reached = fixed + g2 * scale;
  out.miss = (out.reached - target).norm();
  out.reached_target = !(out.axial_component || out.pinned || out.force_limited);
  return Status::Ok();
}

}  // namespace wirerig
