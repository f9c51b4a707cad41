#include "wirerig/runtime/modal_wire.h"

#include <cmath>

#include "modal_wire_internal.h"
#include "validation.h"
#include "wirerig/runtime/bending_job.h"

namespace wirerig {
namespace {

// Elementwise: Eigen's allFinite() computes x - x, which raises FE_INVALID on infinities.
bool AllFinite(const Vec3& x) {
  return std::isfinite(x.x()) && std::isfinite(x.y()) && std::isfinite(x.z());
}

// Bounds on a state's values (see ValidateModalState): q stays below the deflection bound of
// the loads; velocities are at most omega_max (<= 1e12 rad/s) times that.
constexpr double kMaxCoordinate = 1e150;
constexpr double kMaxVelocity = 1e165;

bool Bounded(const Vec3& x, double bound) {
  return AllFinite(x) && x.lpNorm<Eigen::Infinity>() < bound;
}

// The exact transition of the free oscillator q'' + 2 zeta w q' + w^2 q = 0 over h:
// (q, q')(t + h) = [m0 m1; m2 m3] (q, q')(t). With e the decay and S, C as below,
//   m0 = e (C + zeta w S),  m1 = e S,  m2 = -w^2 e S,  m3 = e (C - zeta w S),
//   zeta < 1: C = cos(wd h), S = sin(wd h) / wd, wd = w sqrt(1 - zeta^2), e = exp(-zeta w h);
//   zeta = 1: C = 1, S = h, e = exp(-w h);
//   zeta > 1: e C = (e1 + e2) / 2, e S = (e1 - e2) / (2 mu), mu = w sqrt(zeta^2 - 1),
//             e1 = exp(-(zeta w - mu) h), e2 = exp(-(zeta w + mu) h),
// the over-damped case written with the slow rate w / (zeta + sqrt(zeta^2 - 1)) and expm1, so
// no term overflows and S is accurate as zeta -> 1 (every branch tends to S = h there).
std::array<double, 4> Transition(double w, double zeta, double h) {
  double ec = 0.0, es = 0.0;  // e C and e S
  if (zeta < 1.0) {
    const double wd = w * std::sqrt((1.0 - zeta) * (1.0 + zeta));
    const double e = std::exp(-zeta * w * h);
    ec = e * std::cos(wd * h);
    es = e * std::sin(wd * h) / wd;
  } else if (zeta == 1.0) {
    const double e = std::exp(-w * h);
    ec = e;
    es = e * h;
  } else {
    const double root = std::sqrt((zeta - 1.0) * (zeta + 1.0));
    const double mu = w * root;
    const double slow = w / (zeta + root);  // zeta w - mu, without cancellation
    const double e1 = std::exp(-slow * h);
    ec = 0.5 * e1 * (1.0 + std::exp(-2.0 * mu * h));
    es = -e1 * std::expm1(-2.0 * mu * h) / (2.0 * mu);
  }
  return {ec + zeta * w * es, es, -w * w * es, ec - zeta * w * es};
}

}  // namespace

namespace detail {

double NaturalFrequency(const ModalWireModel& model) {
  return std::sqrt(model.bending_stiffness / model.mass_per_length) / (model.length * model.length);
}

Status ValidateModalLoads(const ModalWireModel& model, const ModalWireLoads& loads) {
  // BendingJob's own checks (positions, finiteness, tip force on cantilevers only, the
  // deflection bound), run on a one-sample job.
  const double sample = 0.0;
  Vec3 ignored;
  BendingJob job;
  job.boundary = model.basis.boundary;
  job.length = model.length;
  job.bending_stiffness = model.bending_stiffness;
  job.start_displacement = loads.start_displacement;
  job.end_displacement = loads.end_displacement;
  job.tip_force = loads.tip_force;
  job.tip_couple = loads.tip_couple;
  job.point_loads = loads.point_loads;
  job.line_loads = loads.line_loads;
  job.linear_line_loads = loads.linear_line_loads;
  job.samples = std::span<const double>(&sample, 1);
  job.displacement = std::span<Vec3>(&ignored, 1);
  if (Status s = job.Validate(); !s) return s;
  return ValidateSupportMotion(model, loads);
}

Status ValidateSupportMotion(const ModalWireModel& model, const ModalWireLoads& loads) {
  const Vec3& acceleration = loads.support_acceleration;
  if (!AllFinite(acceleration))
    return Status::Invalid("support_acceleration", "must be finite (m/s^2)");
  // The inertial load rho A |a| over the whole length, bounded like BendingJob's loads.
  const double compliance = model.length * model.length * model.length / model.bending_stiffness;
  const double bound =
      compliance * model.length * model.mass_per_length * acceleration.lpNorm<Eigen::Infinity>();
  if (!(bound < kMaxDeflectionBound))
    return Status::Invalid("support_acceleration",
                           "too large for the stiffness: the deflection would overflow");
  // The turning load is at most rho A L (|alpha| + |omega|^2) per length at the far end; its
  // bound L^4 rho A (...) / EI is compared in logarithms, so no product can overflow.
  const double log_scale = 5.0 * std::log(model.length) - std::log(model.bending_stiffness) +
                           std::log(model.mass_per_length);
  const double log_bound = std::log(kMaxDeflectionBound);
  const Vec3& omega = loads.support_angular_velocity;
  if (!AllFinite(omega))
    return Status::Invalid("support_angular_velocity", "must be finite (rad/s)");
  const double w = omega.lpNorm<Eigen::Infinity>();
  if (w > 0.0 && !(log_scale + 2.0 * std::log(w) < log_bound))
    return Status::Invalid("support_angular_velocity",
                           "too large for the stiffness: the deflection would overflow");
  const Vec3& alpha = loads.support_angular_acceleration;
  if (!AllFinite(alpha))
    return Status::Invalid("support_angular_acceleration", "must be finite (rad/s^2)");
  const double a = alpha.lpNorm<Eigen::Infinity>();
  if (a > 0.0 && !(log_scale + std::log(a) < log_bound))
    return Status::Invalid("support_angular_acceleration",
                           "too large for the stiffness: the deflection would overflow");
  return Status::Ok();
}

Status ValidateModalState(const ModalWireModel& model, const ModalWireState* state) {
  if (state == nullptr) return Status::Invalid("state", "must not be null");
  if (state->modes != model.basis.modes)
    return Status::Invalid("state", "has another mode count than the model (initialise it)");
  for (int n = 0; n < state->modes; ++n) {
    if (!Bounded(state->q[n], kMaxCoordinate) || !Bounded(state->q_static[n], kMaxCoordinate))
      return Status::InvalidElement("state", n, "q", "must be finite and below 1e150 m");
    if (!Bounded(state->q_dot[n], kMaxVelocity))
      return Status::InvalidElement("state", n, "q_dot", "must be finite and below 1e165 m/s");
  }
  return Status::Ok();
}

void StaticModalCoordinates(const ModalWireModel& model, const ModalWireLoads& loads,
                            std::span<const double> point_load_modes, std::span<Vec3> out) {
  const ModalBasis& basis = model.basis;
  const double length = model.length;
  const double compliance = length * length * length / model.bending_stiffness;  // L^3 / EI
  // The inertial support load per unit v: -rho A a L.
  const Vec3 inertial = -model.mass_per_length * length * loads.support_acceleration;
  const bool tip = !loads.tip_force.isZero(0.0);
  const bool couple = !loads.tip_couple.isZero(0.0);
  const bool support = !inertial.isZero(0.0);
  // The turning support's load per unit v at v = 1 (it is zero at v = 0): -rho A L^2 r_support.
  const Vec3 turning = -model.mass_per_length * length * length *
                       TurningAccelerationPerLength(loads.support_angular_velocity,
                                                    loads.support_angular_acceleration);
  const bool turns = !turning.isZero(0.0);
  for (int n = 0; n < basis.modes; ++n) {
    // L f_n: the projection of the loads, N.
    Vec3 force = Vec3::Zero();
    if (point_load_modes.empty()) {
      for (const PointLoad& load : loads.point_loads)
        force += load.force * ModeValue(basis, n, load.at);
    } else {
      for (std::size_t j = 0; j < loads.point_loads.size(); ++j)
        force += loads.point_loads[j].force * point_load_modes[j * basis.modes + n];
    }
    if (tip) force += loads.tip_force * basis.end_value[n];
    // A couple's work is C dphi/ds at the tip: C phi_n'(1) / L.
    if (couple) force += loads.tip_couple * (ModeSlope(basis, n, 1.0) / length);
    for (const LineLoad& load : loads.line_loads)
      force += (load.force_per_length * length) * ModeIntegral(basis, n, load.from, load.to);
    for (const LinearLineLoad& load : loads.linear_line_loads) {
      const double ramp = ModeRampIntegral(basis, n, load.from, load.to);
      const double whole = ModeIntegral(basis, n, load.from, load.to);
      force += (load.start_force_per_length * (whole - ramp) + load.end_force_per_length * ramp) *
               length;
    }
    if (support) force += inertial * basis.integral[n];
    if (turns) force += turning * basis.moment[n];
    // q_static = f_n / (rho A omega_n^2) = L^3 (L f_n) / (EI beta_n^4).
    const double beta2 = basis.beta[n] * basis.beta[n];
    out[n] = force * (compliance / (beta2 * beta2));
  }
}

}  // namespace detail

ModalWireState::ModalWireState() {
  q.fill(Vec3::Zero());
  q_dot.fill(Vec3::Zero());
  q_static.fill(Vec3::Zero());
}

Status ValidateModalWireModel(const ModalWireModel& model) {
  const ModalBasis& basis = model.basis;
  if (basis.modes < 1 || basis.modes > ModalBasis::kMaxModes || !(basis.beta[0] > 0.0))
    return Status::Invalid("basis", "is not built (BuildModalBasis; modes in [1, 32])");
  if (Status s = detail::CheckBoundary("basis", basis.boundary); !s) return s;
  if (Status s = detail::CheckPositive("length", model.length, "must be positive and finite (m)");
      !s)
    return s;
  if (Status s = detail::CheckPositive("bending_stiffness", model.bending_stiffness,
                                       "must be positive and finite (N m^2)");
      !s)
    return s;
  if (Status s = detail::CheckPositive("mass_per_length", model.mass_per_length,
                                       "must be positive and finite (kg/m)");
      !s)
    return s;
  if (!std::isfinite(model.damping_ratio) || model.damping_ratio < 0.0 ||
      model.damping_ratio > ModalWireModel::kMaxDampingRatio)
    return Status::Invalid("damping_ratio", "must lie in [0, 100]");
  // log of omega_1 and omega_N, so extreme ratios cannot overflow while checking.
  const double log_natural =
      0.5 * (std::log(model.bending_stiffness) - std::log(model.mass_per_length)) -
      2.0 * std::log(model.length);
  const double log_highest = log_natural + 2.0 * std::log(basis.beta[basis.modes - 1]);
  const double log_lowest = log_natural + 2.0 * std::log(basis.beta[0]);
  if (!(log_highest <= std::log(ModalWireModel::kMaxFrequency)))
    return Status::Invalid("mass_per_length",
                           "too small for the stiffness: the highest mode exceeds 1e12 rad/s");
  if (!(log_lowest >= std::log(1e-12)))
    return Status::Invalid("mass_per_length",
                           "too large for the stiffness: the lowest mode is below 1e-12 rad/s");
  return Status::Ok();
}

Vec3 TurningAccelerationPerLength(const Vec3& angular_velocity, const Vec3& angular_acceleration) {
  const Vec3& w = angular_velocity;
  const Vec3& a = angular_acceleration;
  return Vec3(a.y() + w.z() * w.x(), -a.x() + w.z() * w.y(), 0.0);
}

double ModalFrequency(const ModalWireModel& model, int n) {
  const double beta = model.basis.beta[n];
  return beta * beta * detail::NaturalFrequency(model);
}

Status ComputeStaticModalCoordinates(const ModalWireModel& model, const ModalWireLoads& loads,
                                     std::span<Vec3> out) {
  if (Status s = ValidateModalWireModel(model); !s) return s;
  if (Status s = detail::ValidateModalLoads(model, loads); !s) return s;
  if (out.size() < std::size_t(model.basis.modes))
    return Status::Invalid("out", "must hold one element per mode");
  detail::StaticModalCoordinates(model, loads, {}, out);
  return Status::Ok();
}

Status InitializeModalWireAtRest(const ModalWireModel& model, ModalWireState* state) {
  if (Status s = ValidateModalWireModel(model); !s) return s;
  if (state == nullptr) return Status::Invalid("state", "must not be null");
  *state = ModalWireState();
  state->modes = model.basis.modes;
  return Status::Ok();
}

Status InitializeModalWireAtStatic(const ModalWireModel& model, const ModalWireLoads& loads,
                                   ModalWireState* state) {
  if (Status s = ValidateModalWireModel(model); !s) return s;
  if (Status s = detail::ValidateModalLoads(model, loads); !s) return s;
  if (state == nullptr) return Status::Invalid("state", "must not be null");
  *state = ModalWireState();
  state->modes = model.basis.modes;
  detail::StaticModalCoordinates(model, loads, {}, state->q_static);
  state->q = state->q_static;
  return Status::Ok();
}

namespace {

Status CheckTimeStep(double dt) {
  // omega <= 1e12 rad/s, so omega dt <= 1e21: every exp, sin and cos stays finite.
  if (!std::isfinite(dt) || dt < ModalWireStepJob::kMinTimeStep ||
      dt > ModalWireStepJob::kMaxTimeStep)
    return Status::Invalid("dt", "must lie in [1e-9, 1e9] s");
  return Status::Ok();
}

}  // namespace

Status PrecomputeModalStep(const ModalWireModel& model, double dt, ModalStepTable* out) {
  if (Status s = ValidateModalWireModel(model); !s) return s;
  if (Status s = CheckTimeStep(dt); !s) return s;
  if (out == nullptr) return Status::Invalid("out", "must not be null");
  ModalStepTable table;
  table.modes = model.basis.modes;
  table.dt = dt;
  table.damping_ratio = model.damping_ratio;
  table.natural_frequency = detail::NaturalFrequency(model);
  for (int n = 0; n < table.modes; ++n)
    table.transition[n] = Transition(ModalFrequency(model, n), model.damping_ratio, dt);
  *out = table;
  return Status::Ok();
}

Status ModalWireStepJob::Validate() const {
  if (model == nullptr) return Status::Invalid("model", "must not be null");
  if (Status s = ValidateModalWireModel(*model); !s) return s;
  if (Status s = detail::ValidateModalLoads(*model, loads); !s) return s;
  if (Status s = CheckTimeStep(dt); !s) return s;
  if (hold != ModalHold::kZeroOrder && hold != ModalHold::kFirstOrder)
    return Status::Invalid("hold", "unknown hold");
  if (!point_load_modes.empty() &&
      point_load_modes.size() != loads.point_loads.size() * std::size_t(model->basis.modes))
    return Status::Invalid("point_load_modes", "must be empty or hold point_loads x modes values");
  if (step_table != nullptr && (step_table->modes != model->basis.modes || step_table->dt != dt ||
                                step_table->damping_ratio != model->damping_ratio ||
                                step_table->natural_frequency != detail::NaturalFrequency(*model)))
    return Status::Invalid("step_table", "was made for another model or dt");
  return detail::ValidateModalState(*model, state);
}

Status ModalWireStepJob::Run() const {
  if (Status s = Validate(); !s) return s;
  const ModalWireModel& m = *model;
  const int modes = m.basis.modes;
  const double zeta = m.damping_ratio;
  const double natural = detail::NaturalFrequency(m);
  std::array<Vec3, ModalBasis::kMaxModes> target;
  detail::StaticModalCoordinates(m, loads, point_load_modes, std::span<Vec3>(target.data(), modes));
  ModalWireState& s = *state;
  for (int n = 0; n < modes; ++n) {
    const double beta = m.basis.beta[n];
    const double w = beta * beta * natural;
    const std::array<double, 4> t =
        step_table != nullptr ? step_table->transition[n] : Transition(w, zeta, dt);
    if (hold == ModalHold::kZeroOrder) {
      // Deviation from the held equilibrium oscillates freely.
      const Vec3 u = s.q[n] - target[n];
      const Vec3 v = s.q_dot[n];
      s.q[n] = target[n] + t[0] * u + t[1] * v;
      s.q_dot[n] = t[2] * u + t[3] * v;
    } else {
      // A load ramping at rate r (in q_static per second) has the particular solution
      // q_p(t) = q_static(t) - 2 zeta r / w, q_p' = r; the rest oscillates freely.
      const Vec3 rate = (target[n] - s.q_static[n]) / dt;
      const Vec3 lag = (2.0 * zeta / w) * rate;
      const Vec3 u = s.q[n] - (s.q_static[n] - lag);
      const Vec3 v = s.q_dot[n] - rate;
      s.q[n] = target[n] - lag + t[0] * u + t[1] * v;
      s.q_dot[n] = rate + t[2] * u + t[3] * v;
    }
    s.q_static[n] = target[n];
  }
  return Status::Ok();
}

}  // namespace wirerig
