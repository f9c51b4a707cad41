// Modal wire dynamics: a wire with inertia, EI X'''' + rho A X_tt + damping = p(t), advanced in
// closed form mode by mode (issue 17).
//
// Model. A wire of length L (m), bending stiffness EI (N m^2), mass per length rho A (kg/m) and
// one of BendingJob's boundary families. Its deflection relative to the supports is the sum of
// the family's modes (modal_basis.h) with coordinates q_n (m; phi_n is dimensionless with
// integral_0^1 phi_n^2 dv = 1). Each mode, for each of the three components of Vec3 (lateral
// components solved independently, as BendingJob does), is a damped oscillator
//   q_n'' + 2 zeta omega_n q_n' + omega_n^2 q_n = f_n(t) / (rho A),
//   omega_n = beta_n^2 sqrt(EI / (rho A L^4)),
//   f_n = [ sum_j F_j phi_n(a_j) + F_tip phi_n(1) ] / L + sum_k w_k integral_{a_k}^{b_k} phi_n dv
//         + sum_l integral_{a_l}^{b_l} w_l(v) phi_n dv
//         - rho A a_support integral_0^1 phi_n dv - rho A L r_support integral_0^1 v phi_n dv
//         (N/m),
// for point loads F_j at v = a_j, uniform line loads w_k (N/m) over [a_k, b_k], linearly
// varying ones w_l(v) (ModeIntegral and ModeRampIntegral, exact), the tip force, the support
// acceleration and the support's turning r_support (below), with the same modal damping ratio
// zeta for every mode.
//
// Mode-acceleration form. The wire is evaluated as
//   X(v, t) = X_static(v; loads(t)) + sum_n (q_n(t) - q_n_static(t)) phi_n(v),
// where X_static is BendingJob's exact closed form for the current loads and end displacements
// (plus the closed forms of the supports' inertial loads) and q_n_static = f_n / (rho A omega_n^2)
// is the modal coordinate of that static solution. The modes above N respond statically, so
// the static closed form is the exact limit: a wire at rest under constant loads is exactly
// BendingJob's answer, and a damped wire tends to it.
//
// Support motion. The wire lives in its supports' frame. When the supports accelerate (a rigid
// parent turning, a character landing), pass their lateral acceleration a_support (m/s^2, in
// the wire's local axes): it acts as the inertial uniform line load -rho A a_support over the
// whole wire, in the static part and in the modal forces alike. End displacements X0, X1 enter
// the static part only (quasi-statically, as in BendingJob); their own accelerations are not
// inertial loads unless they are passed as support acceleration.
//
// Turning supports. When the supports also turn, with angular velocity omega and angular
// acceleration alpha (local axes; the wire's tangent t is local z), the point at s = L v from
// the v = 0 end accelerates by a further alpha x (s t) + omega x (omega x (s t)). Its lateral
// part s r_support, r_support = [alpha x t + (omega . t) omega]_lateral
// = (alpha_y + omega_z omega_x, -alpha_x + omega_z omega_y, 0), gives the inertial line load
// -rho A s r_support, zero at the support and growing linearly to the free end: a turning body's
// tail or trunk lags and overshoots. Left out: the axial part -s |omega_lateral|^2 t (the
// centrifugal pull along the wire and the stiffening it would give), and the Coriolis load
// -2 rho A omega x X_t of the wire's own deflection velocity (and so any gyroscopic coupling of
// the lateral components); the wire is straight along t for these loads.
//
// Time stepping. Each oscillator is advanced by its exact solution over the step with the load
// held constant over the step (zero-order hold of the step's loads, which act from the step's
// start) or ramped linearly from the previous step's loads to this step's (first-order hold,
// exact for loads linear in time between frames): no stability limit, no energy drift,
// any zeta >= 0 (under-, critically and over-damped each in a cancellation-free form). When dt
// is fixed, PrecomputeModalStep makes the 2x2 transition matrices once.
//
// Workflow: BuildModalBasis once, fill a ModalWireModel, initialise a ModalWireState (at rest or
// at the static solution of given loads), then per frame Run a ModalWireStepJob with the
// frame's loads and a ModalWireEvaluateJob with the same loads. Neither Run() allocates; both
// validate first and name the bad field; neither writes NaN (given tables, if any, made by
// TabulateModes). A loaded wire reacts at once only through the modes above N (statically),
// so a sudden load first shows as a small jump, then the N modes swing towards it.
#pragma once

#include <array>
#include <span>

#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/loads.h"
#include "wirerig/runtime/modal_basis.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

struct ModalWireModel {
  // Largest accepted modal damping ratio (heavily over-damped beyond a few).
  static constexpr double kMaxDampingRatio = 100.0;
  // Largest accepted frequency of the highest mode, rad/s (keeps every product finite).
  static constexpr double kMaxFrequency = 1e12;

  ModalBasis basis;                // boundary family and mode count (BuildModalBasis)
  double length = 0.0;             // L > 0, m
  double bending_stiffness = 0.0;  // EI > 0, N m^2
  double mass_per_length = 0.0;    // rho A > 0, kg/m (density times section area)
  double damping_ratio = 0.0;      // zeta in [0, kMaxDampingRatio], every mode (material.h)
};

// Checks a model: "basis" (not built), "length", "bending_stiffness", "mass_per_length",
// "damping_ratio"; "mass_per_length" also when the highest frequency exceeds kMaxFrequency.
Status ValidateModalWireModel(const ModalWireModel& model);

// omega_n = beta_n^2 sqrt(EI / (rho A L^4)), rad/s, of mode index n in [0, basis.modes).
double ModalFrequency(const ModalWireModel& model, int n);

// The loads on a wire at one time; the fields mean what BendingJob's fields of the same name
// mean (m, N, N/m, v in [0, 1]); tip_force must be zero unless the wire is a cantilever.
struct ModalWireLoads {
  Vec3 start_displacement = Vec3::Zero();  // X0, m
  Vec3 end_displacement = Vec3::Zero();    // X1, m (ignored by cantilevers)
  Vec3 tip_force = Vec3::Zero();           // N at v = 1, cantilevers only
  Vec3 tip_couple = Vec3::Zero();          // N m at v = 1, free cantilevers only
  std::span<const PointLoad> point_loads;
  std::span<const LineLoad> line_loads;
  std::span<const LinearLineLoad> linear_line_loads;
  // Lateral acceleration of the wire's supports, m/s^2, local axes: the inertial line load
  // -rho A a_support acts on the whole wire.
  Vec3 support_acceleration = Vec3::Zero();
  // Angular velocity (rad/s) and angular acceleration (rad/s^2) of the wire's supports, local
  // axes (x, y lateral, z along the wire's tangent): the inertial line load
  // -rho A s [alpha x t + (omega . t) omega]_lateral at s = L v from the v = 0 end (see "Turning
  // supports" above: the axial part and the Coriolis load of the wire's own motion are not
  // modelled). Each finite, and its load bounded like BendingJob's loads.
  Vec3 support_angular_velocity = Vec3::Zero();
  Vec3 support_angular_acceleration = Vec3::Zero();
};

// r_support = [alpha x t + (omega . t) omega]_lateral with t = (0, 0, 1)
//           = (alpha_y + omega_z omega_x, -alpha_x + omega_z omega_y, 0), 1/s^2 (in m/s^2 per
// metre from the support): the lateral acceleration, beyond the support's own, of the point at
// s = 1 m along a wire whose support turns with angular velocity omega and angular acceleration
// alpha (local axes, rad/s and rad/s^2). The inertial load at s is -rho A s r_support.
Vec3 TurningAccelerationPerLength(const Vec3& angular_velocity, const Vec3& angular_acceleration);

// The modal coordinates of a wire, per mode and component, in fixed storage (no allocation).
// Made by InitializeModalWireAtRest or InitializeModalWireAtStatic; advanced by
// ModalWireStepJob. Plain data: copy it to keep a snapshot (e.g. to scrub back).
struct ModalWireState {
  int modes = 0;                                     // the model's basis.modes
  std::array<Vec3, ModalBasis::kMaxModes> q;         // q_n, m
  std::array<Vec3, ModalBasis::kMaxModes> q_dot;     // dq_n/dt, m/s
  std::array<Vec3, ModalBasis::kMaxModes> q_static;  // q_n_static of the last loads, m

  ModalWireState();
};

// q = q_dot = q_static = 0: the undeformed wire with no loads. Errors name the model's field.
Status InitializeModalWireAtRest(const ModalWireModel& model, ModalWireState* state);
// q = q_static of `loads`, q_dot = 0: the wire resting at its static shape under `loads`.
// Errors name the model's or the loads' field.
Status InitializeModalWireAtStatic(const ModalWireModel& model, const ModalWireLoads& loads,
                                   ModalWireState* state);

// q_n_static of `loads` for every mode (out[n], n < basis.modes; `out` holds at least
// basis.modes elements), m. Errors name the model's or the loads' field, or "out".
Status ComputeStaticModalCoordinates(const ModalWireModel& model, const ModalWireLoads& loads,
                                     std::span<Vec3> out);

enum class ModalHold : int {
  kZeroOrder = 0,   // the step's loads act unchanged over the whole step
  kFirstOrder = 1,  // the loads ramp linearly from the previous step's to this step's
};

// The exact transition matrices of one time step, per mode: made once when dt is fixed.
struct ModalStepTable {
  int modes = 0;
  double dt = 0.0;                 // s
  double damping_ratio = 0.0;      // zeta of the model it was made for
  double natural_frequency = 0.0;  // sqrt(EI / (rho A L^4)), rad/s, of the model
  // Per mode: (q, q_dot)(t + dt) = [m0 m1; m2 m3] (q, q_dot)(t) for the free oscillator.
  std::array<std::array<double, 4>, ModalBasis::kMaxModes> transition{};
};

// Errors name the model's field, "dt" (in [kMinTimeStep, kMaxTimeStep] of ModalWireStepJob)
// or "out".
Status PrecomputeModalStep(const ModalWireModel& model, double dt, ModalStepTable* out);

struct ModalWireStepJob {
  // Accepted steps, s: the smallest bounds the first-order hold's load rate, the largest
  // keeps omega dt finite.
  static constexpr double kMinTimeStep = 1e-9;
  static constexpr double kMaxTimeStep = 1e9;

  const ModalWireModel* model = nullptr;
  // The loads of the step (acting at its end, t + dt; see ModalHold).
  ModalWireLoads loads;
  double dt = 0.0;  // s, in [kMinTimeStep, kMaxTimeStep]
  ModalHold hold = ModalHold::kZeroOrder;
  // Optional: PrecomputeModalStep(*model, dt) (same model and dt, checked); otherwise the
  // transitions are computed in Run (a sin/cos/exp per mode).
  const ModalStepTable* step_table = nullptr;
  // Optional: phi_n at the point loads' positions, TabulateModes(model->basis, positions, ...)
  // (point_loads.size() x modes values), for wires whose loads stay where they are; otherwise
  // the modes are evaluated at the loads in Run (a sin/cos pair and two exp per load and mode).
  // Like every table here, its size is checked and its values are trusted: make it with
  // TabulateModes for the same basis and positions (a table of other values gives other
  // answers, and non-finite values would reach the state).
  std::span<const double> point_load_modes;
  // In: the state at t; out: at t + dt. Its q_static becomes the static coordinates of `loads`.
  ModalWireState* state = nullptr;

  // Names the first invalid input: "model" (null) or the model's field, the loads' field
  // (BendingJob's names, or "support_acceleration", "support_angular_velocity",
  // "support_angular_acceleration"), "dt", "hold", "point_load_modes" (size, or
  // not point_loads x modes), "step_table", "state"
  // (null, mode count not the model's, or values not finite / beyond 1e150).
  Status Validate() const;
  // Validates, then advances the state. Never allocates; never writes NaN.
  Status Run() const;
};

struct ModalWireEvaluateJob {
  const ModalWireModel* model = nullptr;
  const ModalWireState* state = nullptr;
  // The loads the state was last stepped (or initialised) with: the static part is evaluated
  // for them and the state's q_static is its modal projection.
  ModalWireLoads loads;

  // Sample parameters v_i in [0, 1], any order; at least one.
  std::span<const double> samples;
  // Optional tables from TabulateModes(model->basis, samples, ...): phi_n(v_i) and phi_n'(v_i).
  // Empty: the modes are evaluated here (10x slower). mode_slopes is needed for tabulated
  // slopes. Their sizes are checked, their values trusted (checking them would cost as much as
  // using them): "never writes NaN" holds for tables made by TabulateModes.
  std::span<const double> mode_values;
  std::span<const double> mode_slopes;

  // Outputs: displacement required, of samples.size(); slope empty or of samples.size().
  std::span<Vec3> displacement;  // X(v_i), m
  std::span<Vec3> slope;         // dX/ds at v_i, dimensionless (s = L v)

  // Names the first invalid input: "model", "state", the loads' or samples' field (BendingJob's
  // names, or the support's as ModalWireStepJob), "mode_values", "mode_slopes", "displacement",
  // "slope".
  Status Validate() const;
  // Validates, then fills the outputs. Never allocates; never writes NaN.
  Status Run() const;
};

// What a moving wire adds to the static closed form of its loads (SpineLoads::
// extra_displacement / extra_slope), from the few numbers a recorded clip keeps per wire and
// frame (.wclip): the modal residual sum_n r_n phi_n(v) and the closed forms of the support's
// inertial loads. Linear in all three: a residual scaled by k gives k times the shape.
struct ModalResidual {
  int modes = 0;                                        // how many coordinates are used
  std::array<Vec3, ModalBasis::kMaxModes> coordinates;  // r_n = q_n - q_n_static, m
  Vec3 uniform_load = Vec3::Zero();  // N/m over the whole wire, local axes: -rho A a_support
  Vec3 turning_load = Vec3::Zero();  // N/m at v = 1, falling linearly to 0 at v = 0:
                                     // -rho A L r_support (TurningAccelerationPerLength)
  ModalResidual();
};

struct ModalResidualJob {
  // The wire: the family of the inertial loads' closed forms (the modes' family is the
  // tables'), L (m) and EI (N m^2).
  BoundaryCondition boundary = BoundaryCondition::kCantileverFree;
  double length = 0.0;
  double bending_stiffness = 0.0;
  const ModalResidual* residual = nullptr;
  // Sample parameters v_i in [0, 1]; tables from TabulateModes for them: phi_n(v_i) and
  // phi_n'(v_i), samples x residual->modes each (sizes checked, values trusted).
  std::span<const double> samples;
  std::span<const double> mode_values;
  std::span<const double> mode_slopes;
  // Written (not added to): displacement (m) of samples.size(); slope dX/ds empty or as many.
  std::span<Vec3> displacement;
  std::span<Vec3> slope;

  // Names the first invalid input: "boundary", "length", "bending_stiffness", "residual" (null,
  // modes outside [0, kMaxModes], values not finite or beyond 1e12), "samples", "mode_values",
  // "mode_slopes", "displacement", "slope".
  Status Validate() const;
  // Validates, then writes the outputs. Never allocates; never writes NaN.
  Status Run() const;
};

// A profile wire's motion (anim's profile_dynamics.h; .wclip replays it): the residual on the
// whole loop as a clamped wire of length L (m) and EI (N m^2) at `samples` (ModalResidualJob
// with the clamped family's mode_values), then each point's displacement d times its weight w in
// [0, 1] (no motion where the part meets another) and eased into `reach` (m, > 0):
// d reach tanh(|d| / reach) / |d|, exact to first order for small motion and never beyond reach.
// weights and displacement have samples.size() elements. Never allocates.
Status EvaluateLoopMotion(const ModalResidual& residual, double length, double bending_stiffness,
                          std::span<const double> samples, std::span<const double> mode_values,
                          std::span<const double> weights, double reach,
                          std::span<Vec3> displacement);

}  // namespace wirerig
