// ModalWireEvaluateJob: the static closed form (BendingJob, plus the supports' inertial loads)
// and the modal residual sum_n (q_n - q_n_static) phi_n(v).
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

// Adds the modal residual, from the tables or evaluating the modes here.
template <bool kTables, bool kSlope>
void AddResidual(const ModalWireEvaluateJob& job,
                 const std::array<Vec3, ModalBasis::kMaxModes>& r) {
  const ModalBasis& basis = job.model->basis;
  const int modes = basis.modes;
  const double inv_length = 1.0 / job.model->length;
  for (std::size_t i = 0; i < job.samples.size(); ++i) {
    Vec3 x = Vec3::Zero(), dx = Vec3::Zero();
    if constexpr (kTables) {
      const double* phi = job.mode_values.data() + i * modes;
      const double* dphi = kSlope ? job.mode_slopes.data() + i * modes : nullptr;
      for (int n = 0; n < modes; ++n) {
        x += r[n] * phi[n];
        if constexpr (kSlope) dx += r[n] * dphi[n];
      }
    } else {
      const double v = job.samples[i];
      for (int n = 0; n < modes; ++n) {
        if constexpr (kSlope) {
          double phi = 0.0, dphi = 0.0;
          EvaluateMode(basis, n, v, &phi, &dphi);
          x += r[n] * phi;
          dx += r[n] * dphi;
        } else {
          x += r[n] * ModeValue(basis, n, v);
        }
      }
    }
    job.displacement[i] += x;
    if constexpr (kSlope) job.slope[i] += dx * inv_length;
  }
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
  // The inertial support load -rho A a over the whole wire, in closed form.
  if (!loads.support_acceleration.isZero(0.0)) {
    const double length = m.length;
    const Vec3 w = -m.mass_per_length * loads.support_acceleration;  // N/m
    const double l3 = length * length * length / m.bending_stiffness;
    const Vec3 x_scale = w * (l3 * length), s_scale = w * l3;  // w L^4/EI, w L^3/EI
    for (std::size_t i = 0; i < samples.size(); ++i) {
      double g = 0.0, dg = 0.0;
      UniformLoadShape(m.basis.boundary, samples[i], &g, &dg);
      displacement[i] += x_scale * g;
      if (!slope.empty()) slope[i] += s_scale * dg;
    }
  }
  // The turning support's inertial load, -rho A L r_support (N/m) at v = 1 falling linearly to
  // zero at v = 0, in closed form.
  const Vec3 turning = TurningAccelerationPerLength(loads.support_angular_velocity,
                                                    loads.support_angular_acceleration);
  if (!turning.isZero(0.0)) {
    const double length = m.length;
    const Vec3 w1 = -m.mass_per_length * length * turning;  // N/m at v = 1
    const double l3 = length * length * length / m.bending_stiffness;
    const Vec3 x_scale = w1 * (l3 * length), s_scale = w1 * l3;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      double g = 0.0, dg = 0.0;
      RampLoadShape(m.basis.boundary, samples[i], &g, &dg);
      displacement[i] += x_scale * g;
      if (!slope.empty()) slope[i] += s_scale * dg;
    }
  }
  // The modal residual.
  std::array<Vec3, ModalBasis::kMaxModes> r;
  for (int n = 0; n < m.basis.modes; ++n) r[n] = state->q[n] - state->q_static[n];
  const bool tables = !mode_values.empty(), with_slope = !slope.empty();
  if (tables && with_slope)
    AddResidual<true, true>(*this, r);
  else if (tables)
    AddResidual<true, false>(*this, r);
  else if (with_slope)
    AddResidual<false, true>(*this, r);
  else
    AddResidual<false, false>(*this, r);
  return Status::Ok();
}

}  // namespace wirerig
