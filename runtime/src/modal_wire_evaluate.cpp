// ModalWireEvaluateJob: the static closed form (BendingJob, plus the supports' inertial loads)
// and the modal residual sum_n (q_n - q_n_static) phi_n(v).
#include <algorithm>
#include <cmath>

#include "bending_internal.h"
#include "modal_wire_internal.h"
#include "validation.h"
#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/modal_wire.h"

namespace wirerig {
namespace {

// Deflection g(v) and dg/dv of a unit uniform load over the whole wire with EI = L = 1 and
// homogeneous ends (PHYSICS.md section 2, "Distributed loads, exact"):
//   SS (v - 2v^3 + v^4)/24, CC v^2 (1-v)^2/24, CF v^2 (6 - 4v + v^2)/24, CG v^2 (2-v)^2/24.
void UniformLoadShape(BoundaryCondition bc, double v, double* g, double* dg) {
  const double v2 = v * v;
  switch (bc) {
    case BoundaryCondition::kSimplySupported:
      *g = (v - 2.0 * v2 * v + v2 * v2) / 24.0;
      *dg = (1.0 - 6.0 * v2 + 4.0 * v2 * v) / 24.0;
      return;
    case BoundaryCondition::kClamped:
      *g = v2 * (1.0 - v) * (1.0 - v) / 24.0;
      *dg = 2.0 * v * (1.0 - v) * (1.0 - 2.0 * v) / 24.0;
      return;
    case BoundaryCondition::kCantileverFree:
      *g = v2 * (6.0 - 4.0 * v + v2) / 24.0;
      *dg = (12.0 * v - 12.0 * v2 + 4.0 * v2 * v) / 24.0;
      return;
    case BoundaryCondition::kCantileverGuided:
      *g = v2 * (2.0 - v) * (2.0 - v) / 24.0;
      *dg = 4.0 * v * (2.0 - v) * (1.0 - v) / 24.0;
      return;
  }
  *g = *dg = 0.0;
}

// Deflection g(v) and dg/dv of a load rising linearly from 0 at v = 0 to 1 at v = 1 with EI = L
// = 1 and homogeneous ends (the Macaulay solution of bending_job.h with a = 0, b = 1: m0 = 1/120,
// m1 = 1/24, m2 = 1/6, m3 = 1/2 in the table of PHYSICS.md section 2):
//   SS v (7 - 10 v^2 + 3 v^4)/360, CC v^2 (2 - 3v + v^3)/120, CF v^2 (20 - 10 v + v^3)/120,
//   CG v^2 (25 - 20 v + 2 v^3)/240.
void RampLoadShape(BoundaryCondition bc, double v, double* g, double* dg) {
  const double v2 = v * v, v4 = v2 * v2;
  switch (bc) {
    case BoundaryCondition::kSimplySupported:
      *g = v * (7.0 - 10.0 * v2 + 3.0 * v4) / 360.0;
      *dg = (7.0 - 30.0 * v2 + 15.0 * v4) / 360.0;
      return;
    case BoundaryCondition::kClamped:
      *g = v2 * (2.0 - 3.0 * v + v2 * v) / 120.0;
      *dg = v * (4.0 - 9.0 * v + 5.0 * v2 * v) / 120.0;
      return;
    case BoundaryCondition::kCantileverFree:
      *g = v2 * (20.0 - 10.0 * v + v2 * v) / 120.0;
      *dg = v * (40.0 - 30.0 * v + 5.0 * v2 * v) / 120.0;
      return;
    case BoundaryCondition::kCantileverGuided:
      *g = v2 * (25.0 - 20.0 * v + 2.0 * v2 * v) / 240.0;
      *dg = v * (50.0 - 60.0 * v + 10.0 * v2 * v) / 240.0;
      return;
  }
  *g = *dg = 0.0;
}

BendingJob StaticJob(const ModalWireEvaluateJob& job) {
  BendingJob b;
  b.boundary = job.model->basis.boundary;
  b.length = job.model->length;
  b.bending_stiffness = job.model->bending_stiffness;
  b.start_displacement = job.loads.start_displacement;
  b.end_displacement = job.loads.end_displacement;
  b.tip_force = job.loads.tip_force;
  b.tip_couple = job.loads.tip_couple;
  b.point_loads = job.loads.point_loads;
  b.line_loads = job.loads.line_loads;
  b.linear_line_loads = job.loads.linear_line_loads;
  b.samples = job.samples;
  b.displacement = job.displacement;
  b.slope = job.slope;
  return b;
}

// Adds the closed forms of a uniform load (N/m over the whole wire) and of a load rising
// linearly from 0 at v = 0 to turning_load (N/m) at v = 1, for a wire of the family.
void AddInertialShapes(BoundaryCondition boundary, double length, double bending_stiffness,
                       const Vec3& uniform_load, const Vec3& turning_load,
                       std::span<const double> samples, std::span<Vec3> displacement,
                       std::span<Vec3> slope) {
  const double l3 = length * length * length / bending_stiffness;
  const auto add = [&](const Vec3& w, auto shape) {
    if (w.isZero(0.0)) return;
    const Vec3 x_scale = w * (l3 * length), s_scale = w * l3;  // w L^4/EI, w L^3/EI
    for (std::size_t i = 0; i < samples.size(); ++i) {
      double g = 0.0, dg = 0.0;
      shape(boundary, samples[i], &g, &dg);
      displacement[i] += x_scale * g;
      if (!slope.empty()) slope[i] += s_scale * dg;
    }
  };
  add(uniform_load, UniformLoadShape);
  add(turning_load, RampLoadShape);
}

// Adds the modal residual sum_n r_n phi_n(v_i), from the tables or evaluating the modes here.
template <bool kTables, bool kSlope>
void AddResidualOf(const ModalBasis* basis, double length,
                   const std::array<Vec3, ModalBasis::kMaxModes>& r, int modes,
                   std::span<const double> samples, std::span<const double> mode_values,
                   std::span<const double> mode_slopes, std::span<Vec3> displacement,
                   std::span<Vec3> slope) {
  const double inv_length = 1.0 / length;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    Vec3 x = Vec3::Zero(), dx = Vec3::Zero();
    if constexpr (kTables) {
      const double* phi = mode_values.data() + i * std::size_t(modes);
      const double* dphi = kSlope ? mode_slopes.data() + i * std::size_t(modes) : nullptr;
      for (int n = 0; n < modes; ++n) {
        x += r[n] * phi[n];
        if constexpr (kSlope) dx += r[n] * dphi[n];
      }
    } else {
      const double v = samples[i];
      for (int n = 0; n < modes; ++n) {
        if constexpr (kSlope) {
          double phi = 0.0, dphi = 0.0;
          EvaluateMode(*basis, n, v, &phi, &dphi);
          x += r[n] * phi;
          dx += r[n] * dphi;
        } else {
          x += r[n] * ModeValue(*basis, n, v);
        }
      }
    }
    displacement[i] += x;
    if constexpr (kSlope) slope[i] += dx * inv_length;
  }
}

// Dispatches AddResidualOf on whether tables and a slope are given; the basis is read only
// without tables (it may be null with them).
void AddResidual(const ModalBasis* basis, double length,
                 const std::array<Vec3, ModalBasis::kMaxModes>& r, int modes,
                 std::span<const double> samples, std::span<const double> mode_values,
                 std::span<const double> mode_slopes, std::span<Vec3> displacement,
                 std::span<Vec3> slope) {
  const bool tables = !mode_values.empty(), with_slope = !slope.empty();
  if (tables && with_slope)
    AddResidualOf<true, true>(basis, length, r, modes, samples, mode_values, mode_slopes,
                              displacement, slope);
  else if (tables)
    AddResidualOf<true, false>(basis, length, r, modes, samples, mode_values, mode_slopes,
                               displacement, slope);
  else if (with_slope)
    AddResidualOf<false, true>(basis, length, r, modes, samples, mode_values, mode_slopes,
                               displacement, slope);
  else
    AddResidualOf<false, false>(basis, length, r, modes, samples, mode_values, mode_slopes,
                                displacement, slope);
}

bool Bounded(const Vec3& x, double bound) {
  return x.allFinite() && x.cwiseAbs().maxCoeff() <= bound;
}

}  // namespace

Status ModalWireEvaluateJob::Validate() const {
  if (model == nullptr) return Status::Invalid("model", "must not be null");
  if (Status s = ValidateModalWireModel(*model); !s) return s;
  if (Status s = detail::ValidateModalState(*model, state); !s) return s;
  // The loads, samples and outputs by BendingJob's rules, then the support acceleration.
  if (Status s = StaticJob(*this).Validate(); !s) return s;
  if (Status s = detail::ValidateSupportMotion(*model, loads); !s) return s;
  const std::size_t table = samples.size() * std::size_t(model->basis.modes);
  if (!mode_values.empty() && mode_values.size() != table)
    return Status::Invalid("mode_values", "must be empty or hold samples x modes values");
  if (!mode_slopes.empty() && (mode_values.empty() || mode_slopes.size() != table))
    return Status::Invalid("mode_slopes",
                           "must be empty or hold samples x modes values (with mode_values)");
  if (!slope.empty() && !mode_values.empty() && mode_slopes.empty())
    return Status::Invalid("mode_slopes", "is needed for the slope when mode_values is given");
  return Status::Ok();
}

Status ModalWireEvaluateJob::Run() const {
  if (Status s = Validate(); !s) return s;
  const ModalWireModel& m = *model;
  // The static closed form for the loads and end displacements.
  const BendingJob static_job = StaticJob(*this);
  detail::RunExactBending(static_job);
  // The supports' inertial loads in closed form: -rho A a over the whole wire, and the
  // turning's -rho A L r_support (N/m) at v = 1 falling linearly to zero at v = 0.
  const Vec3 turning = TurningAccelerationPerLength(loads.support_angular_velocity,
                                                    loads.support_angular_acceleration);
  AddInertialShapes(m.basis.boundary, m.length, m.bending_stiffness,
                    -m.mass_per_length * loads.support_acceleration,
                    -m.mass_per_length * m.length * turning, samples, displacement, slope);
  // The modal residual.
  std::array<Vec3, ModalBasis::kMaxModes> r;
  for (int n = 0; n < m.basis.modes; ++n) r[n] = state->q[n] - state->q_static[n];
  AddResidual(&m.basis, m.length, r, m.basis.modes, samples, mode_values, mode_slopes, displacement,
              slope);
  return Status::Ok();
}

ModalResidual::ModalResidual() { coordinates.fill(Vec3::Zero()); }

Status ModalResidualJob::Validate() const {
  if (Status s = detail::CheckBoundary("boundary", boundary); !s) return s;
  if (Status s = detail::CheckPositive("length", length, "must be finite and positive (m)"); !s)
    return s;
  if (Status s = detail::CheckPositive("bending_stiffness", bending_stiffness,
                                       "must be finite and positive (N m^2)");
      !s)
    return s;
  if (residual == nullptr) return Status::Invalid("residual", "must not be null");
  const ModalResidual& r = *residual;
  if (r.modes < 0 || r.modes > ModalBasis::kMaxModes)
    return Status::Invalid("residual", "modes must lie in [0, 32]");
  // Bounded inputs keep every output finite: |r| phi (|phi| < 2) and w L^4 / EI (shape < 1).
  const double compliance = length * length * length * length / bending_stiffness;
  for (int n = 0; n < r.modes; ++n)
    if (!Bounded(r.coordinates[n], 1e12))
      return Status::InvalidElement("residual", n, "coordinates", "must be finite, at most 1e12");
  if (!Bounded(r.uniform_load, 1e12) || !Bounded(r.turning_load, 1e12) ||
      !(std::isfinite(compliance) && compliance * std::max(r.uniform_load.cwiseAbs().maxCoeff(),
                                                           r.turning_load.cwiseAbs().maxCoeff()) <=
                                         detail::kMaxDeflectionBound))
    return Status::Invalid("residual",
                           "loads must be finite, at most 1e12 N/m, and their "
                           "deflections bounded");
  if (Status s = detail::CheckSamples(samples); !s) return s;
  const std::size_t table = samples.size() * std::size_t(r.modes);
  if (mode_values.size() != table)
    return Status::Invalid("mode_values", "must hold samples x modes values (TabulateModes)");
  if (!slope.empty() && mode_slopes.size() != table)
    return Status::Invalid("mode_slopes", "must hold samples x modes values for the slope");
  if (Status s = detail::CheckOutput("displacement", displacement.size(), samples.size(), true); !s)
    return s;
  return detail::CheckOutput("slope", slope.size(), samples.size(), false);
}

Status ModalResidualJob::Run() const {
  if (Status s = Validate(); !s) return s;
  const ModalResidual& r = *residual;
  std::fill(displacement.begin(), displacement.end(), Vec3::Zero());
  std::fill(slope.begin(), slope.end(), Vec3::Zero());
  AddInertialShapes(boundary, length, bending_stiffness, r.uniform_load, r.turning_load, samples,
                    displacement, slope);
  if (r.modes > 0)
    AddResidual(nullptr, length, r.coordinates, r.modes, samples, mode_values, mode_slopes,
                displacement, slope);
  return Status::Ok();
}

Status EvaluateLoopMotion(const ModalResidual& residual, double length, double bending_stiffness,
                          std::span<const double> samples, std::span<const double> mode_values,
                          std::span<const double> weights, double reach,
                          std::span<Vec3> displacement) {
  ModalResidualJob job;
  job.boundary = BoundaryCondition::kClamped;
  job.length = length;
  job.bending_stiffness = bending_stiffness;
  job.residual = &residual;
  job.samples = samples;
  job.mode_values = mode_values;
  job.displacement = displacement;
  if (Status s = job.Run(); !s) return s;
  for (std::size_t q = 0; q < displacement.size(); ++q) {
    Vec3& d = displacement[q];
    d *= weights[q];
    const double n = d.norm();
    if (n > 1e-12 * reach) d *= reach * std::tanh(n / reach) / n;
  }
  return Status::Ok();
}

}  // namespace wirerig
