// The articulated step: Featherstone's articulated-body algorithm (RBDA table 7.1) with joint
// forces (damping, PD tracking, limits), the two integrators and the momentum correction of
// floating trees. No allocation: everything lives in the ArticulatedWorkspace.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "articulated_internal.h"
#include "wirerig/runtime/articulated_body.h"

namespace wirerig {
namespace {

using detail::Coordinates;
using Body = ArticulatedWorkspace::Body;
using Tree = ArticulatedWorkspace::Tree;

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kMaxMagnitude = 1e150;
constexpr double kUnitTolerance = 1e-6;
// RK4 integrates limits explicitly: its stability interval on the negative real axis is about
// 2.78; a critically damped limit of frequency f needs 2 pi f dt below that.
constexpr double kRk4MaxLimitStep = 2.5;
// Likewise for any joint's damping and stiffness, checked as the step runs.
constexpr double kRk4MaxStiffStep = 2.5;
constexpr int kMaxCorrections = 4;

bool Finite(const Vec3& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}
bool Bounded(double x) { return std::isfinite(x) && std::abs(x) <= kMaxMagnitude; }
bool Bounded(const Vec3& v) { return Bounded(v.x()) && Bounded(v.y()) && Bounded(v.z()); }

// ---------------------------------------------------------------------------------------
// Joint forces. Each returns the generalised force tau and the implicit term dt C + dt^2 K that
// the semi-implicit step adds to the joint's D (h = dt; RK4 passes h = 0): C and K are the
// joint-space damping and stiffness of the forces, so that D qdd = u is solved with the forces
// taken at the end of the step to first order (backward Euler on the joint's own springs).

// The limit spring-damper of natural frequency f scaled by the joint's articulated inertia d:
// its stiffness and damping.
void LimitGains(const ArticulatedBodyDesc& body, double d, double* k, double* c) {
  const double w = kTwoPi * body.limit_frequency;
  *k = w * w * d;
  *c = 2.0 * body.limit_damping_ratio * w * d;
}

// A one-sided limit force on coordinate x with rate xdot against [lo, hi]: a spring-damper that
// only pushes back into the range (it never pulls, so a joint leaving its limit is not held).
// Returns whether it acts.
bool LimitForce(double x, double xdot, double lo, double hi, double k, double c, double* force) {
  if (x < lo) {
    *force = k * (lo - x) - c * xdot;
    return *force > 0.0;
  }
  if (x > hi) {
    *force = k * (hi - x) - c * xdot;
    return *force < 0.0;
  }
  return false;
}

// The largest |lambda| of x'' + c x' + k x = 0: (c + sqrt(c^2 - 4k)) / 2 when overdamped, else
// sqrt(k). RK4 is stable while dt |lambda| stays below about 2.8.
double OscillatorRate(double c, double k) {
  c = std::max(c, 0.0);
  k = std::max(k, 0.0);
  const double disc = 0.25 * c * c - k;
  return disc > 0.0 ? 0.5 * c + std::sqrt(disc) : std::sqrt(k);
}

void HingeForces(const ArticulatedModel& model, int i, double angle, double rate,
                 const JointTarget* target, double d, double h, bool check, double* tau,
                 double* implicit, double* explicit_rate) {
  const ArticulatedBodyDesc& body = model.body(i);
  double force = -body.damping * rate, stiffness = 0.0, damping = body.damping;
  if (target != nullptr) {
    force += target->stiffness * (target->angle - angle) - target->damping * rate;
    stiffness += target->stiffness;
    damping += target->damping;
  }
  if (model.limited(i)) {
    double k, c, limit;
    LimitGains(body, d, &k, &c);
    if (LimitForce(angle, rate, model.lower_limit(i).x(), model.upper_limit(i).x(), k, c, &limit)) {
      force += limit;
      stiffness += k;
      damping += c;
    }
  }
  *tau = force;
  *implicit = h * damping + h * h * stiffness;
  *explicit_rate = check ? OscillatorRate(damping / d, stiffness / d) : 0.0;
}

// Ball joint: omega in body axes. The PD error is log(rotation^-1 target) (the rotation vector of
// target rotation^-1 turned into body axes); its stiffness is linearised as kp 1. Limits act on
// the X-Y-Z Euler angles: with omega = E rates, a generalised force Q on the angles is the
// torque E^-T Q, and a stiffness K on the angles is E^-T K E^-1 on omega.
void BallForces(const ArticulatedModel& model, int i, const Eigen::Vector4d& q, const Vec3& omega,
                const JointTarget* target, const Mat3& d, double h, bool check, Vec3* tau,
                Mat3* implicit, double* explicit_rate) {
  const ArticulatedBodyDesc& body = model.body(i);
  Vec3 force = -body.damping * omega;
  Mat3 stiffness = Mat3::Zero();
  Mat3 damping = body.damping * Mat3::Identity();
  if (target != nullptr) {
    Quat rotation;
    rotation.coeffs() = q;
    rotation.normalize();
    const Vec3 error = detail::LogMap(rotation.conjugate() * target->rotation);
    force += target->stiffness * error - target->damping * omega;
    stiffness.diagonal().array() += target->stiffness;
    damping.diagonal().array() += target->damping;
  }
  if (model.limited(i)) {
    const Vec3 angles = detail::EulerXyz(detail::RotationOf(q));
    const Mat3 e = detail::EulerRateMatrix(angles);
    const Mat3 e_inv = e.inverse();
    const Vec3 rates = e_inv * omega;
    // The inertia angle k sees with the parent held and the other two angles free:
    // 1 / (E^-1 D^-1 E^-T)_kk. (Not (E^T D E)_kk: for a slender limb that couples the stiff
    // direction with the long axis' small inertia and multiplies the frequency.)
    const Mat3 mobility = e_inv * d.inverse() * e_inv.transpose();
    Vec3 generalised = Vec3::Zero(), k_angles = Vec3::Zero(), c_angles = Vec3::Zero();
    bool any = false;
    for (int k = 0; k < 3; ++k) {
      double kk, ck, limit;
      LimitGains(body, 1.0 / mobility(k, k), &kk, &ck);
      if (LimitForce(angles[k], rates[k], model.lower_limit(i)[k], model.upper_limit(i)[k], kk, ck,
                     &limit)) {
        generalised[k] = limit;
        k_angles[k] = kk;
        c_angles[k] = ck;
        any = true;
      }
    }
    if (any) {
      force += e_inv.transpose() * generalised;
      stiffness += e_inv.transpose() * k_angles.asDiagonal() * e_inv;
      damping += e_inv.transpose() * c_angles.asDiagonal() * e_inv;
    }
  }
  *tau = force;
  *implicit = h * damping + h * h * stiffness;
  // The fastest explicit rate, from the largest eigenvalues of D^-1 C and D^-1 K.
  *explicit_rate = 0.0;
  if (check && (damping.squaredNorm() > 0.0 || stiffness.squaredNorm() > 0.0)) {
    const double c =
        Eigen::GeneralizedSelfAdjointEigenSolver<Mat3>(damping, d, Eigen::EigenvaluesOnly)
            .eigenvalues()(2);
    const double k =
        Eigen::GeneralizedSelfAdjointEigenSolver<Mat3>(stiffness, d, Eigen::EigenvaluesOnly)
            .eigenvalues()(2);
    *explicit_rate = OscillatorRate(c, k);
  }
}

// ---------------------------------------------------------------------------------------
// The articulated-body algorithm.

// Pass 2 for a joint of N degrees of freedom (S = the first N unit columns): U = I^A S,
// D = S^T I^A S + implicit, u = tau - S^T p^A, and the articulated inertia and bias force the
// body hands its parent.
template <int N>
void Reduce(Body& b, Body* parent, const Vec6& tau, const Mat6& implicit) {
  using MatN = Eigen::Matrix<double, N, N>;
  using Mat6N = Eigen::Matrix<double, 6, N>;
  const Mat6N u_matrix = b.inertia.template leftCols<N>();
  const MatN d = b.inertia.template topLeftCorner<N, N>() + implicit.template topLeftCorner<N, N>();
  // Closed-form inverses up to 3 x 3 (cofactors); Cholesky for the floating base's 6 x 6.
  MatN d_inv;
  if constexpr (N <= 3)
    d_inv = d.inverse();
  else
    d_inv = d.llt().solve(MatN::Identity());
  b.inverse_d.template topLeftCorner<N, N>() = d_inv;
  b.u.template head<N>() = tau.template head<N>() - b.bias_force.template head<N>();
  if (parent == nullptr) return;
  const Mat6N ud = u_matrix * d_inv;
  b.reduced_inertia = b.inertia - ud * u_matrix.transpose();
  const Vec6 pa =
      b.bias_force + b.reduced_inertia * b.bias_acceleration + ud * b.u.template head<N>();
  parent->inertia += detail::InertiaToParent(b.rotation, b.position, b.reduced_inertia);
  parent->bias_force += detail::ForceToParent(b.rotation, b.position, pa);
}

// Pass 3 for a joint of N degrees of freedom: the joint's acceleration and the body's.
template <int N>
void Accelerate(Body& b, Vec6* a, Vec6* qdd) {
  const Eigen::Matrix<double, N, 1> rhs =
      b.u.template head<N>() - b.inertia.template topRows<N>() * (*a);
  qdd->template head<N>() = b.inverse_d.template topLeftCorner<N, N>() * rhs;
  a->template head<N>() += qdd->template head<N>();
}

struct Evaluation {
  const ArticulatedStepJob& job;
  double implicit_dt;  // dt: semi-implicit joint forces; 0: explicit (RK4)
  bool check_rates;    // RK4's first stage: check the joints' explicit rates against dt
  // Same configuration and joint forces as the previous evaluation, other velocities: only the
  // velocity-dependent terms are recomputed (transforms, articulated inertias, D^-1 and the
  // joint forces are reused from the workspace).
  bool velocity_only = false;
};

// Forward dynamics at (q, nu): the generalised accelerations into qdd. For floating trees,
// adds `weight` times the external wrench at this configuration (gravity included) to each
// tree's impulse and, at the step's start, records its momentum about the world origin.
void ForwardDynamics(const Evaluation& e, std::span<const Coordinates> q, std::span<const Vec6> nu,
                     std::span<Vec6> qdd, bool start, double weight) {
  const ArticulatedStepJob& job = e.job;
  const ArticulatedModel& model = *job.model;
  ArticulatedWorkspace& ws = *job.workspace;
  const int n = model.body_count();
  const bool track = job.conserve_momentum;

  // Pass 1, root to leaves: transforms, velocities, velocity-product terms, bias forces.
  for (int i = 0; i < n; ++i) {
    Body& b = ws.bodies[i];
    const ArticulatedBodyDesc& desc = model.body(i);
    const Vec6 joint = detail::JointVelocity(model.dofs(i), nu[i]);
    if (!e.velocity_only) {
      detail::JointTransform(model, i, q[i], &b.rotation, &b.position);
      if (desc.parent >= 0) {
        const Body& p = ws.bodies[desc.parent];
        b.world_rotation = p.world_rotation * b.rotation;
        b.world_position = p.world_position + p.world_rotation * b.position;
      } else {
        b.world_rotation = b.rotation;
        b.world_position = b.position;
      }
      b.inertia = model.spatial_inertia(i);
    }
    b.velocity =
        desc.parent >= 0
            ? Vec6(detail::MotionToBody(b.rotation, b.position, ws.bodies[desc.parent].velocity) +
                   joint)
            : joint;
    b.bias_acceleration = detail::CrossMotion(b.velocity, joint);
    const Vec6 momentum = model.spatial_inertia(i) * b.velocity;
    b.bias_force = detail::CrossForce(b.velocity, momentum) -
                   detail::ForceToBody(b.world_rotation, b.world_position, b.external);

    const int root = model.root(i);
    if (track && !e.velocity_only && model.body(root).joint == ArticulatedJointType::kFloating) {
      Tree& tree = ws.trees[root];
      if (i == root) {
        tree.mass = 0.0;
        tree.first_moment.setZero();
        tree.origin_momentum.setZero();
      }
      tree.mass += desc.mass;
      tree.first_moment += desc.mass * (b.world_position + b.world_rotation * desc.center_of_mass);
      if (start)
        tree.origin_momentum += detail::ForceToParent(b.world_rotation, b.world_position, momentum);
    }
  }
  // Each floating tree's external wrench about its centre of mass at this stage (gravity acts
  // at the centre of mass: force only), weighted into the impulse.
  if (track && !e.velocity_only) {
    for (int root = 0; root < n; ++root) {
      if (model.root(root) != root || model.body(root).joint != ArticulatedJointType::kFloating)
        continue;
      Tree& tree = ws.trees[root];
      const Vec3 center = tree.first_moment / tree.mass;
      const Vec3 force = tree.wrenches.tail<3>() + tree.mass * job.gravity;
      tree.impulse.tail<3>() += weight * force;
      tree.impulse.head<3>() +=
          weight * (tree.wrenches.head<3>() - center.cross(tree.wrenches.tail<3>()));
      if (start) {
        tree.start_center = center;
        tree.momentum.tail<3>() = tree.origin_momentum.tail<3>();
        tree.momentum.head<3>() =
            tree.origin_momentum.head<3>() - center.cross(tree.origin_momentum.tail<3>());
      }
    }
  }

  // Pass 2, leaves to root: articulated inertias and bias forces, joint forces.
  const JointTarget* targets = job.targets.empty() ? nullptr : job.targets.data();
  if (e.velocity_only) {
    for (int i = n - 1; i >= 0; --i) {
      Body& b = ws.bodies[i];
      const int dofs = model.dofs(i);
      b.u.head(dofs) = b.joint_force.head(dofs) - b.bias_force.head(dofs);
      const int parent = model.body(i).parent;
      if (parent < 0) continue;
      Vec6 pa = b.bias_force + b.reduced_inertia * b.bias_acceleration;
      if (dofs > 0)
        pa += b.inertia.leftCols(dofs) *
              (b.inverse_d.topLeftCorner(dofs, dofs) * b.u.head(dofs)).eval();
      ws.bodies[parent].bias_force += detail::ForceToParent(b.rotation, b.position, pa);
    }
  }
  for (int i = n - 1; i >= 0 && !e.velocity_only; --i) {
    Body& b = ws.bodies[i];
    const ArticulatedBodyDesc& desc = model.body(i);
    Body* parent = desc.parent >= 0 ? &ws.bodies[desc.parent] : nullptr;
    const JointTarget* target = targets != nullptr ? targets + i : nullptr;
    Vec6 tau = Vec6::Zero();
    Mat6 implicit = Mat6::Zero();
    double rate = 0.0;  // the joint forces' fastest explicit rate, 1/s (RK4)
    switch (desc.joint) {
      case ArticulatedJointType::kHinge:
        HingeForces(model, i, q[i].angle, nu[i](0), target, b.inertia(0, 0), e.implicit_dt,
                    e.check_rates, &tau(0), &implicit(0, 0), &rate);
        Reduce<1>(b, parent, tau, implicit);
        break;
      case ArticulatedJointType::kBall: {
        Vec3 t;
        Mat3 m;
        BallForces(model, i, q[i].quaternion, nu[i].head<3>(), target,
                   b.inertia.topLeftCorner<3, 3>(), e.implicit_dt, e.check_rates, &t, &m, &rate);
        tau.head<3>() = t;
        implicit.topLeftCorner<3, 3>() = m;
        Reduce<3>(b, parent, tau, implicit);
        break;
      }
      case ArticulatedJointType::kFloating:
        Reduce<6>(b, parent, tau, implicit);
        break;
      case ArticulatedJointType::kFixed:
      default:
        b.reduced_inertia = b.inertia;
        if (parent != nullptr) {  // c = 0: a fixed joint adds no velocity
          parent->inertia += detail::InertiaToParent(b.rotation, b.position, b.inertia);
          parent->bias_force += detail::ForceToParent(b.rotation, b.position, b.bias_force);
        }
        break;
    }
    b.joint_force = tau;
    if (job.dt * rate > kRk4MaxStiffStep) ws.too_stiff = true;
  }

  // Pass 3, root to leaves: accelerations. The world's acceleration is -gravity, so every
  // body's spatial acceleration is offset by it and gravity needs no forces of its own.
  Vec6 world = Vec6::Zero();
  world.tail<3>() = -job.gravity;
  for (int i = 0; i < n; ++i) {
    Body& b = ws.bodies[i];
    const int parent = model.body(i).parent;
    Vec6 a = detail::MotionToBody(b.rotation, b.position,
                                  parent >= 0 ? ws.bodies[parent].acceleration : world) +
             b.bias_acceleration;
    Vec6& qddi = qdd[i];
    qddi.setZero();
    switch (model.dofs(i)) {
      case 1:
        Accelerate<1>(b, &a, &qddi);
        break;
      case 3:
        Accelerate<3>(b, &a, &qddi);
        break;
      case 6:
        Accelerate<6>(b, &a, &qddi);
        break;
      default:
        break;
    }
    b.acceleration = a;
  }
}

// ---------------------------------------------------------------------------------------
// Integrators.

Eigen::Vector4d QuaternionRate(const Eigen::Vector4d& q, const Vec3& omega) {
  Quat r;
  r.coeffs() = q;
  return 0.5 * (r * Quat(0.0, omega.x(), omega.y(), omega.z())).coeffs();
}

// Time derivative of a joint's coordinates at generalised velocity nu.
void CoordinateRate(ArticulatedJointType type, const Coordinates& c, const Vec6& nu,
                    Coordinates* rate) {
  rate->angle = 0.0;
  rate->quaternion.setZero();
  rate->translation.setZero();
  switch (type) {
    case ArticulatedJointType::kHinge:
      rate->angle = nu(0);
      break;
    case ArticulatedJointType::kBall:
      rate->quaternion = QuaternionRate(c.quaternion, nu.head<3>());
      break;
    case ArticulatedJointType::kFloating:
      rate->quaternion = QuaternionRate(c.quaternion, nu.head<3>());
      rate->translation = detail::RotationOf(c.quaternion) * nu.tail<3>();
      break;
    case ArticulatedJointType::kFixed:
    default:
      break;
  }
}

// out = a + s * rate, coordinate-wise (RK4 stages).
void Combine(const Coordinates& a, double s, const Coordinates& rate, Coordinates* out) {
  out->angle = a.angle + s * rate.angle;
  out->quaternion = a.quaternion + s * rate.quaternion;
  out->translation = a.translation + s * rate.translation;
}

void StepSemiImplicitEuler(const ArticulatedStepJob& job) {
  const ArticulatedModel& model = *job.model;
  ArticulatedWorkspace& ws = *job.workspace;
  const double dt = job.dt;
  const int n = model.body_count();
  ForwardDynamics({job, dt, false}, ws.q0, ws.v0, ws.dv[0], true, dt);
  for (int i = 0; i < n; ++i) ws.v[i] = ws.v0[i] + dt * ws.dv[0][i];
  // Corrections: the velocity-product (gyroscopic, Coriolis) terms at the midpoint velocity,
  // the joint forces still at the start (their implicit terms already look ahead).
  for (int pass = 0; pass < job.corrections; ++pass) {
    for (int i = 0; i < n; ++i) ws.dv[1][i] = 0.5 * (ws.v0[i] + ws.v[i]);
    ForwardDynamics({job, dt, false, true}, ws.q0, ws.dv[1], ws.dv[0], false, 0.0);
    for (int i = 0; i < n; ++i) ws.v[i] = ws.v0[i] + dt * ws.dv[0][i];
  }
  for (int i = 0; i < n; ++i) {
    const Coordinates& c0 = ws.q0[i];
    Coordinates& c = ws.q[i];
    const Vec6& v = ws.v[i];
    c = c0;
    switch (model.body(i).joint) {
      case ArticulatedJointType::kHinge:
        c.angle = c0.angle + dt * v(0);
        break;
      case ArticulatedJointType::kBall: {
        Quat r;
        r.coeffs() = c0.quaternion;
        c.quaternion = (r * detail::ExpMap(dt * v.head<3>())).normalized().coeffs();
        break;
      }
      case ArticulatedJointType::kFloating: {
        // T1 = T0 exp(dt (omega, v)) on SE(3): a screw motion at the body twist.
        Quat r;
        r.coeffs() = c0.quaternion;
        const Vec3 phi = dt * v.head<3>();
        c.quaternion = (r * detail::ExpMap(phi)).normalized().coeffs();
        c.translation = c0.translation + detail::RotationOf(c0.quaternion) *
                                             (detail::LeftJacobian(phi) * (dt * v.tail<3>()));
        break;
      }
      case ArticulatedJointType::kFixed:
      default:
        break;
    }
  }
}

void StepRk4(const ArticulatedStepJob& job) {
  const ArticulatedModel& model = *job.model;
  ArticulatedWorkspace& ws = *job.workspace;
  const int n = model.body_count();
  const double dt = job.dt;

  constexpr double kStageStep[4] = {0.0, 0.5, 0.5, 1.0};
  constexpr double kWeight[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
  for (int stage = 0; stage < 4; ++stage) {
    if (stage == 0) {
      for (int i = 0; i < n; ++i) {
        ws.q[i] = ws.q0[i];
        ws.v[i] = ws.v0[i];
      }
    } else {
      const double s = kStageStep[stage] * dt;
      for (int i = 0; i < n; ++i) {
        Combine(ws.q0[i], s, ws.dq[stage - 1][i], &ws.q[i]);
        ws.v[i] = ws.v0[i] + s * ws.dv[stage - 1][i];
      }
    }
    for (int i = 0; i < n; ++i)
      CoordinateRate(model.body(i).joint, ws.q[i], ws.v[i], &ws.dq[stage][i]);
    ForwardDynamics({job, 0.0, stage == 0}, ws.q, ws.v, ws.dv[stage], stage == 0,
                    kWeight[stage] * dt);
  }
  for (int i = 0; i < n; ++i) {
    Coordinates rate;
    rate.angle =
        ws.dq[0][i].angle + 2.0 * (ws.dq[1][i].angle + ws.dq[2][i].angle) + ws.dq[3][i].angle;
    rate.quaternion = ws.dq[0][i].quaternion +
                      2.0 * (ws.dq[1][i].quaternion + ws.dq[2][i].quaternion) +
                      ws.dq[3][i].quaternion;
    rate.translation = ws.dq[0][i].translation +
                       2.0 * (ws.dq[1][i].translation + ws.dq[2][i].translation) +
                       ws.dq[3][i].translation;
    Combine(ws.q0[i], dt / 6.0, rate, &ws.q[i]);
    const double norm = ws.q[i].quaternion.norm();
    if (norm > 1e-15) ws.q[i].quaternion /= norm;
    ws.v[i] =
        ws.v0[i] + (dt / 6.0) * (ws.dv[0][i] + 2.0 * (ws.dv[1][i] + ws.dv[2][i]) + ws.dv[3][i]);
  }
}

// The bodies' world motion at the end of the step into state->bodies, their world frames also
// into the workspace (for the momentum correction): the matrices chained, one quaternion each.
void EvaluateEnd(const ArticulatedStepJob& job) {
  const ArticulatedModel& model = *job.model;
  ArticulatedWorkspace& ws = *job.workspace;
  std::span<BodyMotion> out = job.state->bodies;
  for (int i = 0; i < model.body_count(); ++i) {
    Body& b = ws.bodies[i];
    detail::JointTransform(model, i, ws.q[i], &b.rotation, &b.position);
    const Vec6 joint = detail::JointVelocity(model.dofs(i), ws.v[i]);
    const int parent = model.body(i).parent;
    BodyMotion& m = out[i];
    if (parent >= 0) {
      const Body& p = ws.bodies[parent];
      const BodyMotion& pm = out[parent];
      b.world_rotation = p.world_rotation * b.rotation;
      b.world_position = p.world_position + p.world_rotation * b.position;
      m.angular_velocity = pm.angular_velocity + b.world_rotation * joint.head<3>();
      m.linear_velocity = pm.linear_velocity +
                          pm.angular_velocity.cross(b.world_position - p.world_position) +
                          b.world_rotation * joint.tail<3>();
    } else {
      b.world_rotation = b.rotation;
      b.world_position = b.position;
      m.angular_velocity = b.world_rotation * joint.head<3>();
      m.linear_velocity = b.world_rotation * joint.tail<3>();
    }
    m.rotation = Quat(b.world_rotation).normalized();
    m.translation = b.world_position;
  }
}

// After the step: every floating tree moved rigidly to its momentum and centre-of-mass targets.
// A twist (dw, dv at the tree's centre of mass c) changes the linear momentum by M dv and the
// angular momentum about c by I_c dw (I_c the tree's inertia about c); a translation moves c.
void ConserveMomentum(const ArticulatedStepJob& job) {
  const ArticulatedModel& model = *job.model;
  ArticulatedWorkspace& ws = *job.workspace;
  std::span<BodyMotion> bodies = job.state->bodies;
  const int n = model.body_count();
  const auto floating = [&](int i) {
    return model.body(model.root(i)).joint == ArticulatedJointType::kFloating;
  };
  for (int i = 0; i < n; ++i) {
    if (!floating(i)) continue;
    Tree& tree = ws.trees[model.root(i)];
    if (i == model.root(i)) {
      tree.origin_momentum.setZero();
      tree.mass = 0.0;
      tree.first_moment.setZero();
      tree.inertia.setZero();
    }
    const ArticulatedBodyDesc& desc = model.body(i);
    const BodyMotion& m = bodies[i];
    const Mat3& r = ws.bodies[i].world_rotation;
    const Vec3 arm = r * desc.center_of_mass;
    const Vec3 x = m.translation + arm;
    const Vec3 v = m.linear_velocity + m.angular_velocity.cross(arm);
    tree.origin_momentum.tail<3>() += desc.mass * v;
    tree.origin_momentum.head<3>() +=
        r * (desc.inertia * (r.transpose() * m.angular_velocity)) + x.cross(desc.mass * v);
    tree.mass += desc.mass;
    tree.first_moment += desc.mass * x;
  }
  for (int i = 0; i < n; ++i) {
    if (!floating(i)) continue;
    const ArticulatedBodyDesc& desc = model.body(i);
    const BodyMotion& m = bodies[i];
    Tree& tree = ws.trees[model.root(i)];
    const Vec3 c = tree.first_moment / tree.mass;
    const Mat3& r = ws.bodies[i].world_rotation;
    const Vec3 d = m.translation + r * desc.center_of_mass - c;
    tree.inertia += r * desc.inertia * r.transpose() +
                    desc.mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  }
  for (int root = 0; root < n; ++root) {
    if (model.root(root) != root || !floating(root)) continue;
    const Tree& tree = ws.trees[root];
    const Vec3 c = tree.first_moment / tree.mass;
    const Vec3 p = tree.origin_momentum.tail<3>();
    const Vec3 l = tree.origin_momentum.head<3>() - c.cross(p);  // about c
    const Vec3 p_target = tree.momentum.tail<3>() + tree.impulse.tail<3>();
    const Vec3 l_target = tree.momentum.head<3>() + tree.impulse.head<3>();
    const Vec3 dv = (p_target - p) / tree.mass;  // of the point at c
    const Vec3 dw = tree.inertia.llt().solve(l_target - l);
    const Vec3 shift =
        tree.start_center + (0.5 * job.dt / tree.mass) * (tree.momentum.tail<3>() + p_target) - c;
    const Mat3& r = ws.bodies[root].world_rotation;
    ws.v[root].head<3>() += r.transpose() * dw;
    ws.v[root].tail<3>() += r.transpose() * (dv + dw.cross(bodies[root].translation - c));
    ws.q[root].translation += model.joint_axes(root).transpose() * shift;
    for (int i = root; i < n; ++i) {
      if (model.root(i) != root) continue;
      bodies[i].angular_velocity += dw;
      bodies[i].linear_velocity += dv + dw.cross(bodies[i].translation - c);
      bodies[i].translation += shift;
    }
  }
}

}  // namespace

Status ArticulatedStepJob::Validate() const {
  if (model == nullptr) return Status::Invalid("model", "is required");
  const int n = model->body_count();
  if (workspace == nullptr || static_cast<int>(workspace->bodies.size()) != n ||
      static_cast<int>(workspace->trees.size()) != n ||
      static_cast<int>(workspace->q0.size()) != n || static_cast<int>(workspace->q.size()) != n ||
      static_cast<int>(workspace->v0.size()) != n || static_cast<int>(workspace->v.size()) != n)
    return Status::Invalid("workspace", "is required, made for this model");
  for (int k = 0; k < 4; ++k)
    if (static_cast<int>(workspace->dq[k].size()) != n ||
        static_cast<int>(workspace->dv[k].size()) != n)
      return Status::Invalid("workspace", "is required, made for this model");
  if (state == nullptr) return Status::Invalid("state", "is required");
  switch (integrator) {
    case ArticulatedIntegrator::kSemiImplicitEuler:
    case ArticulatedIntegrator::kRk4:
      break;
    default:
      return Status::Invalid("integrator", "unknown integrator");
  }
  if (!(std::isfinite(dt) && dt > 0.0 && dt <= 1e6))
    return Status::Invalid("dt", "must be positive and finite, within 1e6 (s)");
  if (!(corrections >= 0 && corrections <= kMaxCorrections))
    return Status::Invalid("corrections", "must lie in [0, 4]");
  if (integrator == ArticulatedIntegrator::kRk4)
    for (int i = 0; i < n; ++i)
      if (model->limited(i) && kTwoPi * model->body(i).limit_frequency * dt > kRk4MaxLimitStep)
        return Status::Invalid("dt", "too long for a joint limit under RK4 (2 pi f dt > 2.5)");
  if (!Bounded(gravity)) return Status::Invalid("gravity", "must be finite, within 1e150 (m/s^2)");
  for (std::size_t k = 0; k < wrenches.size(); ++k) {
    const ExternalWrench& w = wrenches[k];
    const int index = static_cast<int>(k);
    if (!(w.body >= 0 && w.body < n))
      return Status::InvalidElement("wrenches", index, "body", "must be a body of the model");
    if (!Bounded(w.force))
      return Status::InvalidElement("wrenches", index, "force", "must be finite, within 1e150 (N)");
    if (!Bounded(w.point))
      return Status::InvalidElement("wrenches", index, "point", "must be finite, within 1e150 (m)");
    if (!Bounded(w.torque))
      return Status::InvalidElement("wrenches", index, "torque",
                                    "must be finite, within 1e150 (N m)");
  }
  if (!targets.empty() && static_cast<int>(targets.size()) != n)
    return Status::Invalid("targets", "must be empty or have one target per body");
  for (int i = 0; i < static_cast<int>(targets.size()); ++i) {
    const JointTarget& t = targets[i];
    const Quat& q = t.rotation;
    if (!(std::isfinite(q.w()) && Finite(q.vec()) && std::abs(q.w()) <= 2.0 &&
          q.vec().cwiseAbs().maxCoeff() <= 2.0 &&
          std::abs(q.squaredNorm() - 1.0) <= kUnitTolerance))
      return Status::InvalidElement("targets", i, "rotation", "must be a unit quaternion");
    if (!Bounded(t.angle))
      return Status::InvalidElement("targets", i, "angle", "must be finite, within 1e150 (rad)");
    if (!(Bounded(t.stiffness) && t.stiffness >= 0.0))
      return Status::InvalidElement("targets", i, "stiffness", "must be finite and >= 0 (N m/rad)");
    if (!(Bounded(t.damping) && t.damping >= 0.0))
      return Status::InvalidElement("targets", i, "damping", "must be finite and >= 0 (N m s/rad)");
  }
  return detail::CheckArticulatedState(*model, *state);
}

Status ArticulatedStepJob::Run() const {
  if (Status s = Validate(); !s) return s;
  const ArticulatedModel& m = *model;
  ArticulatedWorkspace& ws = *workspace;
  const int n = m.body_count();

  for (int i = 0; i < n; ++i) {
    detail::LoadJoint(m.body(i).joint, state->joints[i], &ws.q0[i], &ws.v0[i]);
    ws.q0[i].quaternion.normalize();
    ws.bodies[i].external.setZero();
    ws.trees[i] = Tree{};
  }
  for (const ExternalWrench& w : wrenches) {
    Vec6 f;
    f.tail<3>() = w.force;
    f.head<3>() = w.torque + w.point.cross(w.force);
    ws.bodies[w.body].external += f;
    ws.trees[m.root(w.body)].wrenches += f;
  }

  ws.too_stiff = false;
  if (integrator == ArticulatedIntegrator::kRk4)
    StepRk4(*this);
  else
    StepSemiImplicitEuler(*this);
  if (ws.too_stiff)
    return Status::Invalid("dt",
                           "too long for a joint's damping or stiffness under RK4 (use the "
                           "semi-implicit integrator or a shorter step)");

  for (int i = 0; i < n; ++i) {
    const Coordinates& c = ws.q[i];
    const Vec6& v = ws.v[i];
    bool ok =
        Bounded(c.angle) && Bounded(c.translation) && Bounded(v.head<3>()) && Bounded(v.tail<3>());
    for (int k = 0; k < 4; ++k) ok = ok && std::isfinite(c.quaternion(k));
    if (!ok) return Status::Invalid("dt", "diverged: the step is far too long for the motion");
  }

  // Committed: the bodies at the end of the step, the momentum correction, the joints.
  EvaluateEnd(*this);
  if (conserve_momentum) ConserveMomentum(*this);
  for (int i = 0; i < n; ++i)
    detail::StoreJoint(m.body(i).joint, ws.q[i], ws.v[i], &state->joints[i]);
  state->time += dt;
  return Status::Ok();
}

}  // namespace wirerig
