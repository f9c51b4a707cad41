// Articulated rigid-body dynamics (articulated_body.h) against independent references written
// here, never against the solver's own output:
//   1. a planar double pendulum against its textbook Lagrangian equations integrated by RK4 at a
//      tiny step: errors shrink at the integrators' orders (1 and 4);
//   2. a free-floating branched chain: momentum conserved, energy drift bounded and shrinking;
//      its momentum and centre of mass under gravity and a wrench; a hanging ball chain's energy
//      and vertical angular momentum; two floating trees in one model;
//   3. PD tracking with critical damping against theta(t) = target (1 - (1 + w t) e^{-w t}), for
//      a hinge and a ball joint;
//   4. limits hold, damping dissipates, a fixed joint is rigid (and its pair of bodies moves as
//      the one composite rigid body, computed here by the parallel-axis theorem);
//   5. a torque-free asymmetric top: its conserved energy and angular momentum, its body angular
//      velocity against Euler's equations integrated here, and rigid_body.h as a cross-check;
// then kinematics by hand, angle read/write, determinism and input validation.
// Lines starting "[ measure ]" print the numbers docs/articulated-dynamics.md quotes.
#include "wirerig/runtime/articulated_body.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <string_view>
#include <vector>

#include <Eigen/Eigenvalues>

#include "wirerig/runtime/rigid_body.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
using Integrator = ArticulatedIntegrator;
constexpr std::array kIntegrators = {Integrator::kSemiImplicitEuler, Integrator::kRk4};

const char* Name(Integrator integrator) {
  return integrator == Integrator::kRk4 ? "rk4" : "semi-implicit Euler";
}

// A solid cylinder of mass m, radius r and length l along the body's Y axis, about its centre.
Mat3 CylinderInertia(double m, double r, double l) {
  const double across = m * (3.0 * r * r + l * l) / 12.0;
  return Vec3(across, 0.5 * m * r * r, across).asDiagonal();
}

ArticulatedModel MustBuild(const std::vector<ArticulatedBodyDesc>& bodies) {
  ArticulatedModel model;
  const Status status = ArticulatedModel::Build(bodies, &model);
  EXPECT_TRUE(status.ok()) << ToString(status);
  return model;
}

ArticulatedMeasures Measure(const ArticulatedModel& model, const ArticulatedState& state,
                            const Vec3& gravity) {
  ArticulatedMeasures m;
  EXPECT_TRUE(MeasureArticulated(model, state, gravity, &m).ok());
  return m;
}

// Runs `steps` steps of the job, checking each.
void Advance(const ArticulatedStepJob& job, int steps) {
  for (int k = 0; k < steps; ++k) {
    const Status status = job.Run();
    ASSERT_TRUE(status.ok()) << ToString(status) << " at step " << k;
  }
}

double Order(double coarse, double fine, double ratio) {
  return std::log(coarse / fine) / std::log(ratio);
}

// ---------------------------------------------------------------------------------------
// 1. The planar double pendulum.
//
// Two links swinging in the world's XY plane under gravity -Y, hinged about +Z. Link k has mass
// m_k, its centre a_k from its joint, inertia J_k about its centre (about Z); link 1 is l1 long.
// With absolute angles t1, t2 from the downward vertical the textbook Lagrangian
//   T = 1/2 (m1 a1^2 + J1) t1'^2 + 1/2 m2 (l1^2 t1'^2 + a2^2 t2'^2 + 2 l1 a2 t1' t2' cos(t1 - t2))
//       + 1/2 J2 t2'^2,   V = -(m1 a1 + m2 l1) g cos t1 - m2 a2 g cos t2
// gives M(t) t'' = f(t, t') with
//   M = [[m1 a1^2 + J1 + m2 l1^2, m2 l1 a2 cos(t1 - t2)], [m2 l1 a2 cos(t1 - t2), m2 a2^2 + J2]]
//   f = [-m2 l1 a2 sin(t1 - t2) t2'^2 - (m1 a1 + m2 l1) g sin t1,
//         m2 l1 a2 sin(t1 - t2) t1'^2 - m2 a2 g sin t2].
// The solver's hinge angles are t1 and t2 - t1.

struct Pendulum {
  double m1 = 1.0, l1 = 1.0, a1 = 0.5, r1 = 0.03;
  double m2 = 0.7, l2 = 0.8, a2 = 0.4, r2 = 0.025;
  double g = 9.81;
  double J1() const { return m1 * (3.0 * r1 * r1 + l1 * l1) / 12.0; }
  double J2() const { return m2 * (3.0 * r2 * r2 + l2 * l2) / 12.0; }
};

using State4 = Eigen::Vector4d;  // t1, t2, t1', t2'

State4 PendulumRates(const Pendulum& p, const State4& y) {
  const double c = std::cos(y(0) - y(1)), s = std::sin(y(0) - y(1));
  Eigen::Matrix2d m;
  m << p.m1 * p.a1 * p.a1 + p.J1() + p.m2 * p.l1 * p.l1, p.m2 * p.l1 * p.a2 * c,
      p.m2 * p.l1 * p.a2 * c, p.m2 * p.a2 * p.a2 + p.J2();
  const Eigen::Vector2d f(
      -p.m2 * p.l1 * p.a2 * s * y(3) * y(3) - (p.m1 * p.a1 + p.m2 * p.l1) * p.g * std::sin(y(0)),
      p.m2 * p.l1 * p.a2 * s * y(2) * y(2) - p.m2 * p.a2 * p.g * std::sin(y(1)));
  const Eigen::Vector2d acc = m.inverse() * f;
  return State4(y(2), y(3), acc(0), acc(1));
}

// Classic RK4 at step h from y0, sampled every `every` steps.
std::vector<State4> PendulumReference(const Pendulum& p, const State4& y0, double h, int steps,
                                      int every) {
  std::vector<State4> out;
  State4 y = y0;
  for (int k = 1; k <= steps; ++k) {
    const State4 k1 = PendulumRates(p, y);
    const State4 k2 = PendulumRates(p, y + 0.5 * h * k1);
    const State4 k3 = PendulumRates(p, y + 0.5 * h * k2);
    const State4 k4 = PendulumRates(p, y + h * k3);
    y += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    if (k % every == 0) out.push_back(y);
  }
  return out;
}

// Hinges about world +Z: the joint's X axis turned onto Z.
Quat HingeAboutZ() { return Quat(Eigen::AngleAxisd(-0.5 * kPi, Vec3::UnitY())); }

std::vector<ArticulatedBodyDesc> PendulumBodies(const Pendulum& p, double damping = 0.0) {
  std::vector<ArticulatedBodyDesc> bodies(2);
  bodies[0].parent = -1;
  bodies[0].joint = ArticulatedJointType::kHinge;
  bodies[0].joint_rotation = HingeAboutZ();
  bodies[0].mass = p.m1;
  bodies[0].center_of_mass = Vec3(0.0, -p.a1, 0.0);
  // Body axes: X = world Z (the hinge), Y along the link, Z = -world X.
  bodies[0].inertia = CylinderInertia(p.m1, p.r1, p.l1);
  bodies[0].damping = damping;
  bodies[1].parent = 0;
  bodies[1].joint = ArticulatedJointType::kHinge;
  bodies[1].joint_position = Vec3(0.0, -p.l1, 0.0);
  bodies[1].mass = p.m2;
  bodies[1].center_of_mass = Vec3(0.0, -p.a2, 0.0);
  bodies[1].inertia = CylinderInertia(p.m2, p.r2, p.l2);
  bodies[1].damping = damping;
  return bodies;
}

// The largest angle error against the reference at its sample times (every 0.1 s for 2 s).
double PendulumError(Integrator integrator, double dt, const Pendulum& p, const State4& y0,
                     const std::vector<State4>& reference, double sample_every) {
  const ArticulatedModel model = MustBuild(PendulumBodies(p));
  ArticulatedState state = MakeArticulatedState(model);
  ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
  state.joints[0].angle = y0(0);
  state.joints[1].angle = y0(1) - y0(0);
  state.joints[0].angular_velocity.x() = y0(2);
  state.joints[1].angular_velocity.x() = y0(3) - y0(2);
  ArticulatedStepJob job;
  job.model = &model;
  job.integrator = integrator;
  job.dt = dt;
  job.gravity = Vec3(0.0, -p.g, 0.0);
  job.workspace = &ws;
  job.state = &state;
  const int per_sample = static_cast<int>(std::lround(sample_every / dt));
  double worst = 0.0;
  for (const State4& ref : reference) {
    Advance(job, per_sample);
    const double t1 = state.joints[0].angle, t2 = t1 + state.joints[1].angle;
    worst = std::max({worst, std::abs(t1 - ref(0)), std::abs(t2 - ref(1))});
  }
  return worst;
}

TEST(ArticulatedDoublePendulum, ReferenceIsConverged) {
  // The reference itself: RK4 at h and 2h agree to far below the errors measured against it.
  const Pendulum p;
  const State4 y0(0.6, 0.3, 0.0, 0.5);
  const auto fine = PendulumReference(p, y0, 1e-5, 200000, 10000);
  const auto coarse = PendulumReference(p, y0, 2e-5, 100000, 5000);
  double worst = 0.0;
  for (std::size_t k = 0; k < fine.size(); ++k)
    worst = std::max(worst, (fine[k] - coarse[k]).head<2>().cwiseAbs().maxCoeff());
  std::printf("[ measure ] double pendulum reference: RK4 h = 1e-5 vs 2e-5 differ by %.2e rad\n",
              worst);
  EXPECT_LT(worst, 1e-11);
}

TEST(ArticulatedDoublePendulum, AnglesConvergeToTheLagrangianReferenceAtTheIntegratorsOrder) {
  const Pendulum p;
  const State4 y0(0.6, 0.3, 0.0, 0.5);                                   // t1, t2 (absolute), rates
  const auto reference = PendulumReference(p, y0, 1e-5, 200000, 10000);  // every 0.1 s to 2 s
  ASSERT_EQ(reference.size(), 20u);
  struct Case {
    Integrator integrator;
    std::array<double, 4> steps;
    double min_order, max_order, finest_tolerance;
  };
  const std::array cases = {
      Case{Integrator::kSemiImplicitEuler, {4e-3, 2e-3, 1e-3, 5e-4}, 0.85, 1.15, 3e-2},
      Case{Integrator::kRk4, {2e-2, 1e-2, 5e-3, 2.5e-3}, 3.6, 4.4, 1e-7},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(Name(c.integrator));
    std::array<double, 4> errors{};
    for (int k = 0; k < 4; ++k)
      errors[k] = PendulumError(c.integrator, c.steps[k], p, y0, reference, 0.1);
    for (int k = 0; k < 4; ++k) {
      std::printf("[ measure ] double pendulum %s dt = %.4g: max angle error over 2 s = %.3e rad",
                  Name(c.integrator), c.steps[k], errors[k]);
      if (k > 0) std::printf(", order %.2f", Order(errors[k - 1], errors[k], 2.0));
      std::printf("\n");
    }
    for (int k = 1; k < 4; ++k) {
      const double order = Order(errors[k - 1], errors[k], 2.0);
      EXPECT_GT(order, c.min_order) << "dt = " << c.steps[k];
      EXPECT_LT(order, c.max_order) << "dt = " << c.steps[k];
    }
    EXPECT_LT(errors[3], c.finest_tolerance);
  }
}

TEST(ArticulatedDoublePendulum, KinematicsMatchTheHandFormulas) {
  // Body positions and velocities of the evaluated state against the textbook kinematics.
  const Pendulum p;
  const ArticulatedModel model = MustBuild(PendulumBodies(p));
  ArticulatedState state = MakeArticulatedState(model);
  const double t1 = 0.7, t2 = -0.3, w1 = 1.3, w2 = -0.8;
  state.joints[0].angle = t1;
  state.joints[1].angle = t2 - t1;
  state.joints[0].angular_velocity = Vec3(w1, 0, 0);
  state.joints[1].angular_velocity = Vec3(w2 - w1, 0, 0);
  ASSERT_TRUE(EvaluateArticulatedBodies(model, &state).ok());
  const Vec3 elbow(p.l1 * std::sin(t1), -p.l1 * std::cos(t1), 0.0);
  EXPECT_NEAR((state.bodies[0].translation - Vec3::Zero()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((state.bodies[1].translation - elbow).norm(), 0.0, 1e-15);
  EXPECT_NEAR((state.bodies[1].angular_velocity - Vec3(0, 0, w2)).norm(), 0.0, 1e-15);
  const Vec3 elbow_velocity(p.l1 * std::cos(t1) * w1, p.l1 * std::sin(t1) * w1, 0.0);
  EXPECT_NEAR((state.bodies[1].linear_velocity - elbow_velocity).norm(), 0.0, 1e-15);
  // The second link's centre of mass in the world.
  const Vec3 com2 =
      state.bodies[1].translation + state.bodies[1].rotation * model.body(1).center_of_mass;
  EXPECT_NEAR((com2 - elbow - Vec3(p.a2 * std::sin(t2), -p.a2 * std::cos(t2), 0)).norm(), 0.0,
              1e-15);
  // Energies: T and V of the Lagrangian above.
  const ArticulatedMeasures m = Measure(model, state, Vec3(0, -p.g, 0));
  const double T = 0.5 * (p.m1 * p.a1 * p.a1 + p.J1()) * w1 * w1 +
                   0.5 * p.m2 *
                       (p.l1 * p.l1 * w1 * w1 + p.a2 * p.a2 * w2 * w2 +
                        2.0 * p.l1 * p.a2 * w1 * w2 * std::cos(t1 - t2)) +
                   0.5 * p.J2() * w2 * w2;
  const double V =
      -(p.m1 * p.a1 + p.m2 * p.l1) * p.g * std::cos(t1) - p.m2 * p.a2 * p.g * std::cos(t2);
  EXPECT_NEAR(m.kinetic_energy, T, 1e-14);
  EXPECT_NEAR(m.potential_energy, V, 1e-14);
}

// ---------------------------------------------------------------------------------------
// 2. A free-floating branched chain: a torso with two two-link arms on ball joints.

std::vector<ArticulatedBodyDesc> FreeChainBodies() {
  std::vector<ArticulatedBodyDesc> bodies;
  ArticulatedBodyDesc torso;
  torso.joint = ArticulatedJointType::kFloating;
  torso.mass = 3.0;
  torso.center_of_mass = Vec3(0.01, 0.05, -0.02);
  torso.inertia = Vec3(0.06, 0.03, 0.05).asDiagonal();
  bodies.push_back(torso);
  for (double side : {-1.0, 1.0}) {
    ArticulatedBodyDesc upper;
    upper.parent = 0;
    upper.joint = ArticulatedJointType::kBall;
    upper.joint_position = Vec3(0.2 * side, 0.25, 0.0);
    upper.joint_rotation = Quat(Eigen::AngleAxisd(side * 0.5 * kPi, Vec3::UnitZ()));
    upper.mass = 0.8;
    upper.center_of_mass = Vec3(0.0, -0.15, 0.0);
    upper.inertia = CylinderInertia(0.8, 0.04, 0.3);
    bodies.push_back(upper);
    ArticulatedBodyDesc lower = upper;
    lower.parent = static_cast<int>(bodies.size()) - 1;
    lower.joint_position = Vec3(0.0, -0.3, 0.0);
    lower.joint_rotation = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 1, 0).normalized()));
    lower.mass = 0.5;
    lower.center_of_mass = Vec3(0.01, -0.12, 0.0);
    lower.inertia = CylinderInertia(0.5, 0.03, 0.25);
    bodies.push_back(lower);
  }
  return bodies;
}

void RandomVelocities(const ArticulatedModel& model, ArticulatedState* state, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  // The order of a call's arguments is unspecified: every draw is its own statement, so that
  // every compiler makes the same state. The order is GCC's (right to left: z first, the axis
  // before the angle), with which these tests' tolerances were set.
  const auto vector = [&] {
    const double z = u(rng), y = u(rng), x = u(rng);
    return Vec3(x, y, z);
  };
  const auto rotation = [&](double scale) {
    const Vec3 axis = vector().normalized();
    const double angle = scale * u(rng);
    return Quat(Eigen::AngleAxisd(angle, axis));
  };
  for (int i = 0; i < model.body_count(); ++i) {
    JointState& j = state->joints[i];
    j.angular_velocity = vector();
    if (model.body(i).joint == ArticulatedJointType::kFloating) {
      j.linear_velocity = vector();
      j.translation = vector();
      j.rotation = rotation(1.0);
    } else {
      j.rotation = rotation(0.3);
    }
  }
  ASSERT_TRUE(EvaluateArticulatedBodies(model, state).ok());
}

struct Drift {
  double linear = 0.0, angular = 0.0, energy = 0.0;  // largest deviations over the run
  double momentum_scale = 0.0, energy_scale = 0.0;
};

Drift FreeChainDrift(Integrator integrator, double dt, double duration, bool conserve) {
  const ArticulatedModel model = MustBuild(FreeChainBodies());
  ArticulatedState state = MakeArticulatedState(model);
  RandomVelocities(model, &state, 7);
  ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
  ArticulatedStepJob job;
  job.model = &model;
  job.integrator = integrator;
  job.dt = dt;
  job.gravity = Vec3::Zero();
  job.conserve_momentum = conserve;
  job.workspace = &ws;
  job.state = &state;
  const ArticulatedMeasures m0 = Measure(model, state, Vec3::Zero());
  Drift d;
  // Scales: the momentum of the bodies' speeds, the energy.
  for (int i = 0; i < model.body_count(); ++i)
    d.momentum_scale += model.body(i).mass * (state.bodies[i].linear_velocity.norm() +
                                              state.bodies[i].angular_velocity.norm() * 0.5);
  d.momentum_scale = std::max(d.momentum_scale, m0.angular_momentum.norm());
  d.energy_scale = m0.kinetic_energy;
  const int steps = static_cast<int>(std::lround(duration / dt));
  for (int k = 0; k < steps; ++k) {
    EXPECT_TRUE(job.Run().ok());
    const ArticulatedMeasures m = Measure(model, state, Vec3::Zero());
    d.linear = std::max(d.linear, (m.linear_momentum - m0.linear_momentum).norm());
    d.angular = std::max(d.angular, (m.angular_momentum - m0.angular_momentum).norm());
    d.energy = std::max(d.energy, std::abs(m.kinetic_energy - m0.kinetic_energy));
  }
  return d;
}

TEST(ArticulatedFreeChain, MomentumIsConservedToRoundOffAndEnergyDriftIsBounded) {
  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    std::array<Drift, 2> drift;
    const std::array<double, 2> steps = {2e-3, 1e-3};
    for (int k = 0; k < 2; ++k) {
      drift[k] = FreeChainDrift(integrator, steps[k], 2.0, true);
      std::printf(
          "[ measure ] free chain %s dt = %g, 2 s, momentum kept: |dp|/scale %.1e, |dL|/scale "
          "%.1e, |dE|/E %.1e\n",
          Name(integrator), steps[k], drift[k].linear / drift[k].momentum_scale,
          drift[k].angular / drift[k].momentum_scale, drift[k].energy / drift[k].energy_scale);
      // Round-off: a few ulps per step, accumulated over the steps.
      const double roundoff = 10.0 * (2.0 / steps[k]) * std::numeric_limits<double>::epsilon();
      EXPECT_LT(drift[k].linear, roundoff * drift[k].momentum_scale);
      EXPECT_LT(drift[k].angular, roundoff * drift[k].momentum_scale);
    }
    // Energy drift bounded and shrinking at the integrator's order.
    const double order = Order(drift[0].energy, drift[1].energy, 2.0);
    std::printf("[ measure ] free chain %s energy drift order %.2f\n", Name(integrator), order);
    if (integrator == Integrator::kRk4) {
      EXPECT_LT(drift[1].energy, 1e-8 * drift[1].energy_scale);
    } else {
      EXPECT_LT(drift[1].energy, 2e-2 * drift[1].energy_scale);
      EXPECT_GT(order, 0.8);
    }
  }
}

TEST(ArticulatedFreeChain, WithoutTheCorrectionMomentumErrorsShrinkWithTheStep) {
  // The raw integrators: linear momentum is still exact to round-off in neither, but the
  // errors of both momenta shrink at the integrators' orders.
  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    const double coarse_dt = integrator == Integrator::kRk4 ? 1e-2 : 2e-3;
    const Drift coarse = FreeChainDrift(integrator, coarse_dt, 2.0, false);
    const Drift fine = FreeChainDrift(integrator, 0.5 * coarse_dt, 2.0, false);
    const double linear_order = Order(coarse.linear, fine.linear, 2.0);
    const double angular_order = Order(coarse.angular, fine.angular, 2.0);
    std::printf(
        "[ measure ] free chain %s, no correction, dt = %g -> %g: |dp|/scale %.2e -> %.2e "
        "(order %.2f), |dL|/scale %.2e -> %.2e (order %.2f)\n",
        Name(integrator), coarse_dt, 0.5 * coarse_dt, coarse.linear / coarse.momentum_scale,
        fine.linear / fine.momentum_scale, linear_order, coarse.angular / coarse.momentum_scale,
        fine.angular / fine.momentum_scale, angular_order);
    const double expected = integrator == Integrator::kRk4 ? 4.0 : 1.0;
    EXPECT_NEAR(angular_order, expected, 0.5);
    EXPECT_NEAR(linear_order, expected, 0.5);
  }
}

TEST(ArticulatedFreeChain, ExternalForcesChangeMomentumByTheirImpulse) {
  // Gravity and a wrench at a fixed world point: p(t) = p0 + (M g + F) t and
  // L(t) = L0 + t (tau + point x F) + the moment of gravity integrated along the centre of mass
  // path, which for the parabola x_c(t) = x0 + v0 t + (g + F/M) t^2 / 2 is
  // integral of x_c x M g = M (x0 t + v0 t^2/2 + a t^3/6) x g.
  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    const ArticulatedModel model = MustBuild(FreeChainBodies());
    ArticulatedState state = MakeArticulatedState(model);
    RandomVelocities(model, &state, 11);
    ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
    // On the torso, near its centre: the moment arm grows as the chain falls away from the
    // (world-fixed) point, but stays short enough for the torso not to spin up.
    const std::array wrench = {
        ExternalWrench{0, Vec3(0.2, 0.4, -0.1), Vec3(0.05, 0.1, 0.0), Vec3(0.02, 0.0, -0.01)}};
    ArticulatedStepJob job;
    job.model = &model;
    job.integrator = integrator;
    job.dt = 1e-3;
    job.gravity = Vec3(0.0, -9.81, 0.0);
    job.wrenches = wrench;
    job.workspace = &ws;
    job.state = &state;
    const ArticulatedMeasures m0 = Measure(model, state, job.gravity);
    const double t = 0.5;
    Advance(job, 500);
    const ArticulatedMeasures m = Measure(model, state, job.gravity);
    const double mass = model.total_mass();
    const Vec3 v0 = m0.linear_momentum / mass;
    const Vec3 a = job.gravity + wrench[0].force / mass;
    const Vec3 p = m0.linear_momentum + t * (mass * job.gravity + wrench[0].force);
    const Vec3 x = m0.center_of_mass + t * v0 + 0.5 * t * t * a;
    EXPECT_LT((m.linear_momentum - p).norm(), 1e-12 * p.norm());
    // The centre of mass follows the parabola: exactly for RK4 (its stages integrate a quadratic
    // exactly), to O(dt) for the semi-implicit step.
    const double com_tolerance = integrator == Integrator::kRk4 ? 1e-9 : 1e-2;
    EXPECT_LT((m.center_of_mass - x).norm(), com_tolerance);
    const Vec3 gravity_moment =
        mass * (m0.center_of_mass * t + v0 * t * t / 2.0 + a * t * t * t / 6.0).cross(job.gravity);
    const Vec3 l = m0.angular_momentum +
                   t * (wrench[0].torque + wrench[0].point.cross(wrench[0].force)) + gravity_moment;
    const double l_tolerance = integrator == Integrator::kRk4 ? 1e-9 : 2e-2;
    std::printf(
        "[ measure ] free chain with forces, %s: |p - p_exact| %.1e, |x_c - x_exact| %.1e, "
        "|L - L_exact| %.1e (|L| %.2f)\n",
        Name(integrator), (m.linear_momentum - p).norm(), (m.center_of_mass - x).norm(),
        (m.angular_momentum - l).norm(), l.norm());
    EXPECT_LT((m.angular_momentum - l).norm(), l_tolerance * l.norm());
  }
}

TEST(ArticulatedBallChain, HangingChainKeepsEnergyAndVerticalAngularMomentum) {
  // Two rods on ball joints hanging from a world pivot at the origin, under gravity, undamped.
  // Gravity's moment about the pivot is horizontal and the pivot's reaction has none, so the
  // vertical component of the angular momentum about the origin is conserved, as is the energy.
  std::vector<ArticulatedBodyDesc> bodies(2);
  const Mat3 rod = CylinderInertia(1.0, 0.03, 0.5);  // along Y: swap Y and Z for a Z bone
  for (int i = 0; i < 2; ++i) {
    bodies[i].parent = i - 1;
    bodies[i].joint = ArticulatedJointType::kBall;
    bodies[i].mass = 1.0 - 0.3 * i;
    bodies[i].center_of_mass = Vec3(0.0, 0.01, 0.25);
    bodies[i].inertia = (1.0 - 0.3 * i) * Vec3(rod(0, 0), rod(2, 2), rod(1, 1)).asDiagonal();
  }
  bodies[0].joint_rotation = Quat(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitX()));  // Z -> -Y
  bodies[1].joint_position = Vec3(0.0, 0.0, 0.5);
  const ArticulatedModel model = MustBuild(bodies);
  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    // Passes: dt = 2e-3, 1e-3, and (semi-implicit) 1e-3 without the midpoint correction.
    std::array<double, 3> energy{}, spin{};
    const int passes = integrator == Integrator::kRk4 ? 2 : 3;
    for (int pass = 0; pass < passes; ++pass) {
      const double dt = pass == 0 ? 2e-3 : 1e-3;
      ArticulatedState state = MakeArticulatedState(model);
      SetJointAnglesDegrees(ArticulatedJointType::kBall, Vec3(40.0, -20.0, 10.0), &state.joints[0]);
      SetJointAnglesDegrees(ArticulatedJointType::kBall, Vec3(-30.0, 35.0, 0.0), &state.joints[1]);
      state.joints[0].angular_velocity = Vec3(0.5, 2.0, 1.0);
      state.joints[1].angular_velocity = Vec3(-1.0, 0.5, 3.0);
      ASSERT_TRUE(EvaluateArticulatedBodies(model, &state).ok());
      ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
      ArticulatedStepJob job;
      job.model = &model;
      job.integrator = integrator;
      job.dt = dt;
      job.corrections = pass == 2 ? 0 : 1;
      job.workspace = &ws;
      job.state = &state;
      const ArticulatedMeasures m0 = Measure(model, state, job.gravity);
      const double e0 = m0.kinetic_energy + m0.potential_energy;
      const double scale = m0.kinetic_energy + std::abs(m0.potential_energy);
      const int steps = static_cast<int>(std::lround(3.0 / dt));
      for (int k = 0; k < steps; ++k) {
        ASSERT_TRUE(job.Run().ok());
        const ArticulatedMeasures m = Measure(model, state, job.gravity);
        energy[pass] =
            std::max(energy[pass], std::abs(m.kinetic_energy + m.potential_energy - e0) / scale);
        spin[pass] =
            std::max(spin[pass], std::abs(m.angular_momentum.y() - m0.angular_momentum.y()));
      }
      std::printf(
          "[ measure ] hanging ball chain %s%s dt = %g, 3 s: rel. energy drift %.2e, "
          "|dL_y| %.2e (L_y %.3f)\n",
          Name(integrator), pass == 2 ? " without correction" : "", dt, energy[pass], spin[pass],
          m0.angular_momentum.y());
    }
    if (integrator == Integrator::kRk4) {
      EXPECT_LT(energy[1], 2e-8);
      EXPECT_LT(spin[1], 2e-8);
    } else {
      EXPECT_LT(energy[1], 2e-2);
      EXPECT_LT(spin[1], 2e-2);
      EXPECT_GT(Order(energy[0], energy[1], 2.0), 0.8);
      EXPECT_GT(Order(spin[0], spin[1], 2.0), 0.8);
      // Explicit velocity-product terms pump energy into the slender, twisting rods.
      EXPECT_GT(energy[2], 10.0 * energy[1]);
    }
  }
}

TEST(ArticulatedForest, EachFloatingTreeKeepsItsOwnMomentum) {
  // Two floating trees in one model: a torso with an arm, and a lone ball pushed by a wrench.
  // The first's momentum is untouched by the second's push; the second's changes by the push.
  std::vector<ArticulatedBodyDesc> bodies = FreeChainBodies();
  bodies.resize(2);
  ArticulatedBodyDesc ball;
  ball.joint = ArticulatedJointType::kFloating;
  ball.mass = 0.5;
  ball.inertia = 0.002 * Mat3::Identity();
  ball.joint_position = Vec3(1.0, 0.0, 0.0);
  bodies.push_back(ball);
  const ArticulatedModel model = MustBuild(bodies);
  EXPECT_EQ(model.root(1), 0);
  EXPECT_EQ(model.root(2), 2);
  ArticulatedState state = MakeArticulatedState(model);
  RandomVelocities(model, &state, 13);
  ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
  const std::array push = {
      ExternalWrench{2, Vec3(0.0, 3.0, 0.0), Vec3(1.0, 0.0, 0.05), Vec3::Zero()}};
  ArticulatedStepJob job;
  job.model = &model;
  job.dt = 1e-3;
  job.gravity = Vec3::Zero();
  job.wrenches = push;
  job.workspace = &ws;
  job.state = &state;
  // Momenta of a set of bodies, from their world motion (computed here).
  const auto momentum = [&](int first, int last) {
    Vec3 p = Vec3::Zero();
    for (int i = first; i <= last; ++i) {
      const Vec3 arm = state.bodies[i].rotation * model.body(i).center_of_mass;
      p += model.body(i).mass *
           (state.bodies[i].linear_velocity + state.bodies[i].angular_velocity.cross(arm));
    }
    return p;
  };
  const Vec3 a0 = momentum(0, 1), b0 = momentum(2, 2);
  Advance(job, 500);
  EXPECT_LT((momentum(0, 1) - a0).norm(), 1e-12);
  EXPECT_LT((momentum(2, 2) - b0 - 0.5 * push[0].force).norm(), 1e-12);
}

// ---------------------------------------------------------------------------------------
// 3. PD tracking, critically damped.

double CriticallyDamped(double target, double w, double t) {
  return target * (1.0 - (1.0 + w * t) * std::exp(-w * t));
}

TEST(ArticulatedPdTracking, CriticallyDampedHingeFollowsTheClosedFormStepResponse) {
  // One rod on a hinge, no gravity: I = J + m a^2 about the axis, kd = 2 sqrt(kp I).
  const double m = 1.2, l = 0.6, r = 0.03, a = 0.3;
  std::vector<ArticulatedBodyDesc> bodies(1);
  bodies[0].joint = ArticulatedJointType::kHinge;
  bodies[0].joint_rotation = HingeAboutZ();
  bodies[0].mass = m;
  bodies[0].center_of_mass = Vec3(0.0, -a, 0.0);
  bodies[0].inertia = CylinderInertia(m, r, l);
  const double inertia = m * (3.0 * r * r + l * l) / 12.0 + m * a * a;
  const double kp = 40.0, kd = 2.0 * std::sqrt(kp * inertia), w = std::sqrt(kp / inertia);
  const double target = 0.8;
  const ArticulatedModel model = MustBuild(bodies);
  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    for (double dt : {2e-3, 1e-3}) {
      ArticulatedState state = MakeArticulatedState(model);
      ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
      const std::array targets = {JointTarget{Quat::Identity(), target, kp, kd}};
      ArticulatedStepJob job;
      job.model = &model;
      job.integrator = integrator;
      job.dt = dt;
      job.gravity = Vec3::Zero();
      job.targets = targets;
      job.workspace = &ws;
      job.state = &state;
      double worst = 0.0, peak = 0.0;
      const int steps = static_cast<int>(std::lround(3.0 / dt));
      for (int k = 1; k <= steps; ++k) {
        ASSERT_TRUE(job.Run().ok());
        const double angle = state.joints[0].angle;
        worst = std::max(worst, std::abs(angle - CriticallyDamped(target, w, k * dt)));
        peak = std::max(peak, angle);
      }
      const double overshoot = std::max(0.0, peak - target) / target;
      std::printf(
          "[ measure ] PD hinge %s dt = %g (w = %.2f rad/s): max error %.2e rad (%.3f%% "
          "of the target), overshoot %.2e%%\n",
          Name(integrator), dt, w, worst, 100.0 * worst / target, 100.0 * overshoot);
      EXPECT_LT(overshoot, 0.01);
      if (integrator == Integrator::kRk4)
        EXPECT_LT(worst, 1e-7 * target);
      else
        EXPECT_LT(worst, 0.01 * target);
    }
  }
}

TEST(ArticulatedPdTracking, CriticallyDampedBallJointTurnsAboutTheTargetAxis) {
  // A body with isotropic inertia about its joint (a sphere centred on it): the PD torque
  // stays along the target's axis, and the angle follows the same closed form.
  std::vector<ArticulatedBodyDesc> bodies(1);
  bodies[0].joint = ArticulatedJointType::kBall;
  bodies[0].joint_position = Vec3(0.1, 1.0, -0.3);
  bodies[0].joint_rotation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 2).normalized()));
  bodies[0].mass = 2.0;
  const double inertia = 0.4 * 2.0 * 0.1 * 0.1;
  bodies[0].inertia = inertia * Mat3::Identity();
  const ArticulatedModel model = MustBuild(bodies);
  const Vec3 axis = Vec3(1.0, -2.0, 3.0).normalized();
  const double target = 1.2, kp = 5.0, kd = 2.0 * std::sqrt(kp * inertia);
  const double w = std::sqrt(kp / inertia);
  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    ArticulatedState state = MakeArticulatedState(model);
    ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
    const std::array targets = {JointTarget{Quat(Eigen::AngleAxisd(target, axis)), 0.0, kp, kd}};
    ArticulatedStepJob job;
    job.model = &model;
    job.integrator = integrator;
    job.dt = 1e-3;
    job.targets = targets;  // gravity on: the joint is at the centre of mass
    job.workspace = &ws;
    job.state = &state;
    double worst = 0.0, off_axis = 0.0;
    for (int k = 1; k <= 2000; ++k) {
      ASSERT_TRUE(job.Run().ok());
      const Eigen::AngleAxisd aa(state.joints[0].rotation);
      const double angle = aa.angle() * (aa.axis().dot(axis) < 0.0 ? -1.0 : 1.0);
      worst = std::max(worst, std::abs(angle - CriticallyDamped(target, w, k * 1e-3)));
      if (std::abs(angle) > 1e-3) off_axis = std::max(off_axis, aa.axis().cross(axis).norm());
    }
    std::printf("[ measure ] PD ball joint %s dt = 1e-3: max angle error %.2e rad, off-axis %.1e\n",
                Name(integrator), worst, off_axis);
    EXPECT_LT(off_axis, 1e-12);
    EXPECT_LT(worst, integrator == Integrator::kRk4 ? 1e-7 * target : 0.01 * target);
  }
}

TEST(ArticulatedPdTracking, StiffGainsStayStableWithTheSemiImplicitStepAndRk4RefusesThem) {
  // Gains far beyond an explicit step (the forearm's twist inertia is ~3e-4 kg m^2: kp = 500
  // rings at ~1300 rad/s, w dt ~ 22 at 60 Hz): the semi-implicit step, implicit in the joints'
  // own springs, settles on the targets; RK4 refuses the step instead of diverging.
  const ArticulatedModel model = MustBuild(FreeChainBodies());
  std::vector<JointTarget> targets(model.body_count());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (JointTarget& t : targets) {
    // One draw per statement, in GCC's order (z first), with which the tolerance was set: the
    // order of a call's arguments is unspecified, and clang's (x first) gave other targets that
    // settle to 1.06e-3 rad, not 5e-4.
    const double z = u(rng), y = u(rng), x = u(rng);
    t.rotation = Quat(Eigen::AngleAxisd(0.6, Vec3(x, y, z).normalized()));
    t.stiffness = 500.0;
    t.damping = 5.0;
  }
  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    ArticulatedState state = MakeArticulatedState(model);
    RandomVelocities(model, &state, 9);
    const ArticulatedMeasures m0 = Measure(model, state, Vec3::Zero());
    ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
    ArticulatedStepJob job;
    job.model = &model;
    job.integrator = integrator;
    job.dt = 1.0 / 60.0;
    job.gravity = Vec3::Zero();
    job.targets = targets;
    job.workspace = &ws;
    job.state = &state;
    if (integrator == Integrator::kRk4) {
      const JointState before = state.joints[2];
      EXPECT_EQ(job.Run().field, "dt");
      EXPECT_EQ(0, std::memcmp(&before, &state.joints[2], sizeof(JointState)));
      EXPECT_EQ(state.time, 0.0);
      continue;
    }
    Advance(job, 180);  // 3 s
    double worst = 0.0;
    for (int i = 1; i < model.body_count(); ++i)
      worst = std::max(worst, state.joints[i].rotation.angularDistance(targets[i].rotation));
    const ArticulatedMeasures m = Measure(model, state, Vec3::Zero());
    std::printf(
        "[ measure ] stiff PD (kp 500, kd 5) at 60 Hz, semi-implicit Euler: largest "
        "joint error after 3 s %.1e rad\n",
        worst);
    EXPECT_LT(worst, 1e-3);
    EXPECT_LT((m.linear_momentum - m0.linear_momentum).norm(), 1e-12);
    EXPECT_LT((m.angular_momentum - m0.angular_momentum).norm(), 1e-11);
  }
}

// ---------------------------------------------------------------------------------------
// 4. Limits, damping, fixed joints.

TEST(ArticulatedLimits, HingeFallingOntoItsLimitStaysWithinIt) {
  // A rod held horizontal falls under gravity onto a lower limit of 45 degrees and rests there.
  std::vector<ArticulatedBodyDesc> bodies(1);
  bodies[0].joint = ArticulatedJointType::kHinge;
  bodies[0].joint_rotation = HingeAboutZ();
  bodies[0].mass = 1.0;
  bodies[0].center_of_mass = Vec3(0.0, -0.25, 0.0);
  bodies[0].inertia = CylinderInertia(1.0, 0.02, 0.5);
  bodies[0].min_degrees.x() = 45.0;
  const ArticulatedModel model = MustBuild(bodies);
  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    ArticulatedState state = MakeArticulatedState(model);
    state.joints[0].angle = 90.0 * kDeg;
    ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
    ArticulatedStepJob job;
    job.model = &model;
    job.integrator = integrator;
    job.dt = 1e-3;
    job.workspace = &ws;
    job.state = &state;
    double lowest = 90.0;
    for (int k = 0; k < 3000; ++k) {
      ASSERT_TRUE(job.Run().ok());
      lowest = std::min(lowest, state.joints[0].angle / kDeg);
    }
    const double rest = state.joints[0].angle / kDeg;
    std::printf("[ measure ] hinge limit 45 deg, %s: lowest %.3f deg, at rest %.4f deg\n",
                Name(integrator), lowest, rest);
    EXPECT_GT(lowest, 45.0 - 1.0);
    EXPECT_NEAR(rest, 45.0, 0.1);  // static sag (m g a sin 45) / k, k = (2 pi 30)^2 I
    EXPECT_LT(std::abs(state.joints[0].angular_velocity.x()), 1e-3);
  }
}

TEST(ArticulatedLimits, BallJointSwingingIntoItsLimitsStaysWithinThem) {
  // A rod on a ball joint thrown sideways under gravity: its X-Y-Z angles stay within the
  // limits plus a small tolerance. As in JointModel, the bone runs along the joint's Z axis
  // (here hanging down): X and Y are its bends, Z its twist.
  std::vector<ArticulatedBodyDesc> bodies(1);
  bodies[0].joint = ArticulatedJointType::kBall;
  bodies[0].joint_rotation = Quat(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitX()));  // Z -> -Y
  bodies[0].mass = 1.5;
  bodies[0].center_of_mass = Vec3(0.0, 0.0, 0.3);
  const Mat3 rod = CylinderInertia(1.5, 0.03, 0.6);  // along Y: swap Y and Z
  bodies[0].inertia = Vec3(rod(0, 0), rod(2, 2), rod(1, 1)).asDiagonal();
  bodies[0].min_degrees = Vec3(-30.0, -20.0, -40.0);
  bodies[0].max_degrees = Vec3(25.0, 20.0, 35.0);
  const ArticulatedModel model = MustBuild(bodies);
  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    ArticulatedState state = MakeArticulatedState(model);
    SetJointAnglesDegrees(ArticulatedJointType::kBall, Vec3(10.0, 5.0, 20.0), &state.joints[0]);
    state.joints[0].angular_velocity = Vec3(-4.0, 6.0, 5.0);
    ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
    ArticulatedStepJob job;
    job.model = &model;
    job.integrator = integrator;
    job.dt = 1e-3;
    job.workspace = &ws;
    job.state = &state;
    Vec3 beyond = Vec3::Zero();  // largest excursion past each axis's limits, degrees
    for (int k = 0; k < 3000; ++k) {
      ASSERT_TRUE(job.Run().ok());
      const Vec3 a = JointAnglesDegrees(ArticulatedJointType::kBall, state.joints[0]);
      beyond = beyond.cwiseMax((bodies[0].min_degrees - a).cwiseMax(a - bodies[0].max_degrees));
    }
    std::printf(
        "[ measure ] ball limits, %s: largest excursion beyond the limits (%.2f, %.2f, "
        "%.2f) deg\n",
        Name(integrator), beyond.x(), beyond.y(), beyond.z());
    EXPECT_LT(beyond.maxCoeff(), 1.0);
  }
}

TEST(ArticulatedDamping, DampedDoublePendulumLosesEnergyMonotonically) {
  const Pendulum p;
  const ArticulatedModel model = MustBuild(PendulumBodies(p, 0.05));
  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    ArticulatedState state = MakeArticulatedState(model);
    state.joints[0].angle = 1.2;
    state.joints[1].angle = -0.8;
    ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
    ArticulatedStepJob job;
    job.model = &model;
    job.integrator = integrator;
    job.dt = 1e-3;
    job.gravity = Vec3(0.0, -p.g, 0.0);
    job.workspace = &ws;
    job.state = &state;
    ASSERT_TRUE(EvaluateArticulatedBodies(model, &state).ok());
    const ArticulatedMeasures m0 = Measure(model, state, job.gravity);
    double previous = m0.kinetic_energy + m0.potential_energy, worst_rise = 0.0;
    const double scale = std::abs(previous) + m0.kinetic_energy;
    for (int k = 0; k < 5000; ++k) {
      ASSERT_TRUE(job.Run().ok());
      const ArticulatedMeasures m = Measure(model, state, job.gravity);
      const double e = m.kinetic_energy + m.potential_energy;
      worst_rise = std::max(worst_rise, e - previous);
      previous = e;
    }
    const double lost = m0.kinetic_energy + m0.potential_energy - previous;
    std::printf(
        "[ measure ] damped double pendulum %s: energy lost over 5 s %.4f J, largest "
        "one-step rise %.2e J\n",
        Name(integrator), lost, worst_rise);
    EXPECT_GT(lost, 0.0);
    EXPECT_LE(worst_rise, 1e-12 * scale);
  }
}

TEST(ArticulatedFixedJoint, ChildMovesRigidlyAndThePairMovesAsOneRigidBody) {
  // A floating box with a rod welded to it. (a) The rod's world transform is the box's composed
  // with the weld, to round-off. (b) Torque-free, the pair is one rigid body: its composite mass
  // properties (parallel-axis theorem, here) stepped by rigid_body.h's RK4 give the same motion.
  std::vector<ArticulatedBodyDesc> bodies(2);
  bodies[0].joint = ArticulatedJointType::kFloating;
  bodies[0].mass = 2.0;
  bodies[0].center_of_mass = Vec3(0.02, -0.01, 0.03);
  bodies[0].inertia = Vec3(0.05, 0.08, 0.1).asDiagonal();
  bodies[1].parent = 0;
  bodies[1].joint = ArticulatedJointType::kFixed;
  bodies[1].joint_position = Vec3(0.3, 0.1, -0.2);
  bodies[1].joint_rotation = Quat(Eigen::AngleAxisd(0.7, Vec3(0.2, 1.0, 0.4).normalized()));
  bodies[1].mass = 0.9;
  bodies[1].center_of_mass = Vec3(0.0, -0.2, 0.05);
  bodies[1].inertia = CylinderInertia(0.9, 0.03, 0.4);
  const ArticulatedModel model = MustBuild(bodies);

  // Composite mass properties in the box's frame.
  const Mat3 weld = bodies[1].joint_rotation.toRotationMatrix();
  const double mass = bodies[0].mass + bodies[1].mass;
  const Vec3 c1 = bodies[1].joint_position + weld * bodies[1].center_of_mass;
  const Vec3 c = (bodies[0].mass * bodies[0].center_of_mass + bodies[1].mass * c1) / mass;
  const auto shifted = [](double m, const Vec3& d) {
    return m * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  };
  const Mat3 inertia = bodies[0].inertia + shifted(bodies[0].mass, bodies[0].center_of_mass - c) +
                       weld * bodies[1].inertia * weld.transpose() +
                       shifted(bodies[1].mass, c1 - c);
  Eigen::SelfAdjointEigenSolver<Mat3> eig(inertia);
  Mat3 axes = eig.eigenvectors();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);

  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    ArticulatedState state = MakeArticulatedState(model);
    state.joints[0].rotation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 0, 1).normalized()));
    state.joints[0].translation = Vec3(0.1, 1.0, -0.5);
    state.joints[0].angular_velocity = Vec3(1.5, -2.0, 0.7);
    state.joints[0].linear_velocity = Vec3(0.3, 0.5, -0.2);
    ASSERT_TRUE(EvaluateArticulatedBodies(model, &state).ok());

    RigidBodyState rigid;
    const Mat3 r0 = state.joints[0].rotation.toRotationMatrix();
    rigid.position = state.joints[0].translation + r0 * c;
    rigid.velocity =
        state.joints[0].linear_velocity + (r0 * state.joints[0].angular_velocity).cross(r0 * c);
    rigid.orientation = Quat(r0 * axes);
    rigid.angular_velocity = axes.transpose() * state.joints[0].angular_velocity;
    RigidBodyStepJob reference;
    reference.integrator = RigidIntegrator::kRk4;
    reference.mass = mass;
    reference.principal_moments = eig.eigenvalues();
    reference.dt = 1e-3;
    reference.state = &rigid;

    ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
    ArticulatedStepJob job;
    job.model = &model;
    job.integrator = integrator;
    job.dt = 1e-3;
    job.gravity = Vec3::Zero();
    job.workspace = &ws;
    job.state = &state;
    double weld_error = 0.0, position_error = 0.0, rotation_error = 0.0;
    for (int k = 0; k < 2000; ++k) {
      ASSERT_TRUE(job.Run().ok());
      ASSERT_TRUE(reference.Run().ok());
      const BodyMotion& box = state.bodies[0];
      const BodyMotion& rod = state.bodies[1];
      const Mat3 rb = box.rotation.toRotationMatrix();
      weld_error = std::max(
          {weld_error, (rod.translation - box.translation - rb * bodies[1].joint_position).norm(),
           (rod.rotation.toRotationMatrix() - rb * weld).norm()});
      position_error = std::max(position_error, (box.translation + rb * c - rigid.position).norm());
      rotation_error = std::max(
          rotation_error, (rb * axes - rigid.orientation.toRotationMatrix()).cwiseAbs().maxCoeff());
    }
    std::printf(
        "[ measure ] fixed joint %s: weld error %.1e, vs the composite rigid body over 2 s: "
        "centre %.1e m, axes %.1e\n",
        Name(integrator), weld_error, position_error, rotation_error);
    EXPECT_LT(weld_error, 1e-13);
    const double tolerance = integrator == Integrator::kRk4 ? 1e-9 : 5e-2;
    EXPECT_LT(position_error, tolerance);
    EXPECT_LT(rotation_error, tolerance);
  }
}

// ---------------------------------------------------------------------------------------
// 5. A torque-free asymmetric top on a floating base.

using Vec3d = Eigen::Vector3d;

Vec3d EulerRates(const Vec3d& moments, const Vec3d& w) {
  return Vec3d((moments.y() - moments.z()) * w.y() * w.z() / moments.x(),
               (moments.z() - moments.x()) * w.z() * w.x() / moments.y(),
               (moments.x() - moments.y()) * w.x() * w.y() / moments.z());
}

// Body angular velocity at time t from Euler's equations, RK4 at step h.
Vec3d EulerReference(const Vec3d& moments, Vec3d w, double t, double h) {
  const int steps = static_cast<int>(std::lround(t / h));
  for (int k = 0; k < steps; ++k) {
    const Vec3d k1 = EulerRates(moments, w);
    const Vec3d k2 = EulerRates(moments, w + 0.5 * h * k1);
    const Vec3d k3 = EulerRates(moments, w + 0.5 * h * k2);
    const Vec3d k4 = EulerRates(moments, w + h * k3);
    w += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return w;
}

TEST(ArticulatedFreeBody, TorqueFreeAsymmetricTopKeepsItsEnergyAndAngularMomentum) {
  // I = diag(1, 2, 3) in principal axes turned by Q from the body axes, the centre of mass off
  // the body origin; omega_0 = (0.1, 1, 0.1) in principal axes, near the unstable middle axis
  // (PHYSICS.md section 7's test). Reference: E = 1/2 w.I w and L = R I w stay at their initial
  // values; the principal angular velocity follows Euler's equations (RK4 at h = 1e-4 here).
  const Vec3 moments(1.0, 2.0, 3.0);
  const Mat3 q = Quat(Eigen::AngleAxisd(0.9, Vec3(1.0, -1.0, 2.0).normalized())).toRotationMatrix();
  std::vector<ArticulatedBodyDesc> bodies(1);
  bodies[0].joint = ArticulatedJointType::kFloating;
  bodies[0].mass = 3.0;
  bodies[0].center_of_mass = Vec3(0.1, -0.2, 0.3);
  bodies[0].inertia = q * moments.asDiagonal() * q.transpose();
  const ArticulatedModel model = MustBuild(bodies);
  const Vec3 w_principal(0.1, 1.0, 0.1);
  const double energy = 0.5 * w_principal.dot(moments.cwiseProduct(w_principal));
  const double duration = 20.0;
  const Vec3d w_reference = EulerReference(moments, w_principal, duration, 1e-4);
  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(Name(integrator));
    std::array<double, 2> drift{};
    for (int pass = 0; pass < 2; ++pass) {
      const double dt = pass == 0 ? 2e-3 : 1e-3;
      ArticulatedState state = MakeArticulatedState(model);
      state.joints[0].rotation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY()));
      state.joints[0].angular_velocity = q * w_principal;
      // The centre of mass at rest: the origin moves with -omega x arm.
      const Mat3 r0 = state.joints[0].rotation.toRotationMatrix();
      state.joints[0].linear_velocity =
          -(r0 * q * w_principal).cross(r0 * bodies[0].center_of_mass);
      ASSERT_TRUE(EvaluateArticulatedBodies(model, &state).ok());
      const ArticulatedMeasures m0 = Measure(model, state, Vec3::Zero());
      EXPECT_NEAR(m0.kinetic_energy, energy, 1e-14);
      EXPECT_LT(m0.linear_momentum.norm(), 1e-14);
      // L about the (resting) centre of mass = R Q I w.
      EXPECT_LT((m0.angular_momentum - m0.center_of_mass.cross(m0.linear_momentum) -
                 r0 * q * moments.cwiseProduct(w_principal))
                    .norm(),
                1e-14);
      ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
      ArticulatedStepJob job;
      job.model = &model;
      job.integrator = integrator;
      job.dt = dt;
      job.gravity = Vec3::Zero();
      job.workspace = &ws;
      job.state = &state;
      double energy_drift = 0.0, momentum_drift = 0.0, com_drift = 0.0;
      const int steps = static_cast<int>(std::lround(duration / dt));
      for (int k = 0; k < steps; ++k) {
        ASSERT_TRUE(job.Run().ok());
        const ArticulatedMeasures m = Measure(model, state, Vec3::Zero());
        energy_drift = std::max(energy_drift, std::abs(m.kinetic_energy - energy) / energy);
        momentum_drift =
            std::max(momentum_drift, (m.angular_momentum - m0.angular_momentum).norm() /
                                         m0.angular_momentum.norm());
        com_drift = std::max(com_drift, (m.center_of_mass - m0.center_of_mass).norm());
      }
      const Vec3 w_end = q.transpose() * state.joints[0].angular_velocity;
      const double w_error = (w_end - w_reference).norm() / w_reference.norm();
      drift[pass] = energy_drift;
      std::printf(
          "[ measure ] asymmetric top %s dt = %g, %g s: rel. energy drift %.2e, rel. |dL| "
          "%.1e, centre of mass drift %.1e m, rel. omega error vs Euler's equations %.2e\n",
          Name(integrator), dt, duration, energy_drift, momentum_drift, com_drift, w_error);
      EXPECT_LT(momentum_drift, 10.0 * steps * std::numeric_limits<double>::epsilon());
      if (integrator == Integrator::kRk4) {
        EXPECT_LT(energy_drift, 1e-9);
        EXPECT_LT(w_error, 1e-7);
      } else {
        EXPECT_LT(energy_drift, 0.05);
        EXPECT_LT(w_error, 0.3);
      }
    }
    std::printf("[ measure ] asymmetric top %s: energy drift order %.2f\n", Name(integrator),
                Order(drift[0], drift[1], 2.0));
  }
}

TEST(ArticulatedFreeBody, CrossCheckWithTheRigidBodyStep) {
  // Not a reference: rigid_body.h's RK4 and the articulated RK4 on the same free body agree.
  const Vec3 moments(1.0, 2.0, 3.0);
  std::vector<ArticulatedBodyDesc> bodies(1);
  bodies[0].joint = ArticulatedJointType::kFloating;
  bodies[0].mass = 2.0;
  bodies[0].inertia = moments.asDiagonal();
  const ArticulatedModel model = MustBuild(bodies);
  ArticulatedState state = MakeArticulatedState(model);
  state.joints[0].angular_velocity = Vec3(0.1, 1.0, 0.1);
  state.joints[0].linear_velocity = Vec3(0.5, 0.0, -0.25);
  RigidBodyState rigid;
  rigid.angular_velocity = state.joints[0].angular_velocity;
  rigid.velocity = state.joints[0].linear_velocity;
  RigidBodyStepJob reference;
  reference.integrator = RigidIntegrator::kRk4;
  reference.mass = 2.0;
  reference.principal_moments = moments;
  reference.dt = 1e-3;
  reference.state = &rigid;
  ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
  ArticulatedStepJob job;
  job.model = &model;
  job.integrator = Integrator::kRk4;
  job.dt = 1e-3;
  job.gravity = Vec3::Zero();
  job.conserve_momentum = false;
  job.workspace = &ws;
  job.state = &state;
  for (int k = 0; k < 10000; ++k) {
    ASSERT_TRUE(job.Run().ok());
    ASSERT_TRUE(reference.Run().ok());
  }
  const double rotation =
      (state.joints[0].rotation.toRotationMatrix() - rigid.orientation.toRotationMatrix())
          .cwiseAbs()
          .maxCoeff();
  const double omega = (state.joints[0].angular_velocity - rigid.angular_velocity).norm();
  const double position = (state.joints[0].translation - rigid.position).norm();
  std::printf(
      "[ measure ] free body vs rigid_body.h RK4, 10 s: rotation %.1e, omega %.1e, "
      "position %.1e\n",
      rotation, omega, position);
  EXPECT_LT(rotation, 1e-9);
  EXPECT_LT(omega, 1e-9);
  EXPECT_LT(position, 1e-9);
}

// ---------------------------------------------------------------------------------------
// Joint state read/write, determinism, validation.

TEST(ArticulatedJointState, AnglesRoundTripInJointModelsConvention) {
  JointState j;
  const Vec3 degrees(30.0, -50.0, 120.0);
  SetJointAnglesDegrees(ArticulatedJointType::kBall, degrees, &j);
  const Quat expected = Quat(Eigen::AngleAxisd(30.0 * kDeg, Vec3::UnitX())) *
                        Quat(Eigen::AngleAxisd(-50.0 * kDeg, Vec3::UnitY())) *
                        Quat(Eigen::AngleAxisd(120.0 * kDeg, Vec3::UnitZ()));
  EXPECT_LT(j.rotation.angularDistance(expected), 1e-15);
  EXPECT_LT((JointAnglesDegrees(ArticulatedJointType::kBall, j) - degrees).norm(), 1e-12);
  SetJointAnglesDegrees(ArticulatedJointType::kHinge, Vec3(-400.0, 0.0, 0.0), &j);
  EXPECT_NEAR(j.angle, -400.0 * kDeg, 1e-15);  // not wrapped
  EXPECT_NEAR(JointAnglesDegrees(ArticulatedJointType::kHinge, j).x(), -400.0, 1e-12);
  EXPECT_EQ(JointAnglesDegrees(ArticulatedJointType::kFixed, j), Vec3::Zero());
}

TEST(ArticulatedStep, IsDeterministicAndWritesConsistentBodies) {
  const ArticulatedModel model = MustBuild(FreeChainBodies());
  std::array<ArticulatedState, 2> states = {MakeArticulatedState(model),
                                            MakeArticulatedState(model)};
  for (ArticulatedState& s : states) RandomVelocities(model, &s, 3);
  std::vector<JointTarget> targets(model.body_count());
  for (JointTarget& t : targets) {
    t.rotation = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitX()));
    t.stiffness = 2.0;  // explicit (RK4): stable while dt (kd m + sqrt(kp m)) stays small
    t.damping = 0.01;
  }
  for (Integrator integrator : kIntegrators) {
    for (ArticulatedState& s : states) {
      ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
      ArticulatedStepJob job;
      job.model = &model;
      job.integrator = integrator;
      job.dt = 1e-3;
      job.targets = targets;
      job.workspace = &ws;
      job.state = &s;
      Advance(job, 200);
    }
    for (int i = 0; i < model.body_count(); ++i) {
      EXPECT_EQ(0, std::memcmp(&states[0].joints[i], &states[1].joints[i], sizeof(JointState)));
      EXPECT_EQ(0, std::memcmp(&states[0].bodies[i], &states[1].bodies[i], sizeof(BodyMotion)));
    }
    // The bodies written by Run are those the joints give.
    ArticulatedState copy = states[0];
    ASSERT_TRUE(EvaluateArticulatedBodies(model, &copy).ok());
    for (int i = 0; i < model.body_count(); ++i) {
      EXPECT_LT(copy.bodies[i].rotation.angularDistance(states[0].bodies[i].rotation), 1e-14);
      EXPECT_LT((copy.bodies[i].translation - states[0].bodies[i].translation).norm(), 1e-14);
      EXPECT_LT((copy.bodies[i].angular_velocity - states[0].bodies[i].angular_velocity).norm(),
                1e-12);
      EXPECT_LT((copy.bodies[i].linear_velocity - states[0].bodies[i].linear_velocity).norm(),
                1e-12);
    }
  }
  EXPECT_NEAR(states[0].time, 0.4, 1e-12);
}

double NaN() { return std::numeric_limits<double>::quiet_NaN(); }

TEST(ArticulatedModelBuild, RefusesEachInvalidFieldByName) {
  struct Case {
    std::string_view field;
    std::function<void(std::vector<ArticulatedBodyDesc>&)> spoil;
  };
  const std::vector<Case> cases = {
      {"parent", [](auto& b) { b[1].parent = 1; }},
      {"parent", [](auto& b) { b[1].parent = -2; }},
      {"joint", [](auto& b) { b[1].joint = static_cast<ArticulatedJointType>(9); }},
      {"joint", [](auto& b) { b[1].joint = ArticulatedJointType::kFloating; }},
      {"joint_position", [](auto& b) { b[1].joint_position.x() = NaN(); }},
      {"joint_rotation", [](auto& b) { b[1].joint_rotation = Quat(2.0, 0.0, 0.0, 0.0); }},
      {"mass", [](auto& b) { b[1].mass = 0.0; }},
      {"mass", [](auto& b) { b[1].mass = NaN(); }},
      {"center_of_mass", [](auto& b) { b[1].center_of_mass.y() = NaN(); }},
      {"inertia", [](auto& b) { b[1].inertia(0, 1) = 0.5; }},
      {"inertia", [](auto& b) { b[1].inertia = Vec3(1.0, 1.0, -0.1).asDiagonal(); }},
      {"inertia", [](auto& b) { b[1].inertia = Vec3(1.0, 1.0, 3.0).asDiagonal(); }},
      {"inertia", [](auto& b) { b[1].inertia(2, 2) = NaN(); }},
      {"damping", [](auto& b) { b[1].damping = -1.0; }},
      {"limits", [](auto& b) { b[1].min_degrees.y() = 10.0, b[1].max_degrees.y() = 5.0; }},
      {"limits", [](auto& b) { b[1].max_degrees.z() = NaN(); }},
      {"limit_frequency", [](auto& b) { b[1].limit_frequency = 0.0; }},
      {"limit_damping_ratio", [](auto& b) { b[1].limit_damping_ratio = -0.5; }},
  };
  ArticulatedModel model;
  std::vector<ArticulatedBodyDesc> bodies = FreeChainBodies();
  ASSERT_TRUE(ArticulatedModel::Build(bodies, &model).ok());
  EXPECT_EQ(model.body_count(), 5);
  EXPECT_EQ(model.dof_count(), 6 + 4 * 3);
  for (const Case& c : cases) {
    std::vector<ArticulatedBodyDesc> spoiled = bodies;
    c.spoil(spoiled);
    ArticulatedModel out = model;
    const Status status = ArticulatedModel::Build(spoiled, &out);
    EXPECT_EQ(status.field, c.field) << ToString(status);
    EXPECT_EQ(status.index, 1) << c.field;
    EXPECT_EQ(out.body_count(), 5) << "left untouched";
  }
  EXPECT_EQ(ArticulatedModel::Build({}, &model).field, "bodies");
  EXPECT_EQ(ArticulatedModel::Build(bodies, nullptr).field, "out");
}

TEST(ArticulatedStepJob, ValidateRefusesEachMissingOrInvalidInput) {
  const ArticulatedModel model = MustBuild(PendulumBodies(Pendulum{}));
  const ArticulatedModel other = MustBuild(FreeChainBodies());
  ArticulatedState state = MakeArticulatedState(model);
  ArticulatedWorkspace ws = MakeArticulatedWorkspace(model);
  ArticulatedWorkspace wrong_ws = MakeArticulatedWorkspace(other);
  ArticulatedState wrong_state = MakeArticulatedState(other);
  std::vector<JointTarget> targets(2);
  const auto good = [&] {
    ArticulatedStepJob job;
    job.model = &model;
    job.dt = 1e-3;
    job.targets = targets;
    job.workspace = &ws;
    job.state = &state;
    return job;
  };
  ASSERT_TRUE(good().Validate().ok());
  struct Case {
    std::string_view field, member;
    std::function<void(ArticulatedStepJob&)> spoil;
  };
  std::vector<JointTarget> one_target(1), bad_rotation(2), bad_gain(2);
  bad_rotation[1].rotation = Quat(0.5, 0.0, 0.0, 0.0);
  bad_gain[0].stiffness = -1.0;
  const std::array bad_wrench = {ExternalWrench{2, Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}};
  const std::array nan_wrench = {ExternalWrench{0, Vec3(NaN(), 0, 0), Vec3::Zero(), Vec3::Zero()}};
  const std::vector<Case> cases = {
      {"model", "", [](auto& j) { j.model = nullptr; }},
      {"workspace", "", [](auto& j) { j.workspace = nullptr; }},
      {"workspace", "", [&](auto& j) { j.workspace = &wrong_ws; }},
      {"state", "", [](auto& j) { j.state = nullptr; }},
      {"state", "", [&](auto& j) { j.state = &wrong_state; }},
      {"integrator", "", [](auto& j) { j.integrator = static_cast<ArticulatedIntegrator>(5); }},
      {"corrections", "", [](auto& j) { j.corrections = -1; }},
      {"corrections", "", [](auto& j) { j.corrections = 5; }},
      {"dt", "", [](auto& j) { j.dt = 0.0; }},
      {"dt", "", [](auto& j) { j.dt = NaN(); }},
      {"gravity", "", [](auto& j) { j.gravity.z() = NaN(); }},
      {"wrenches", "body", [&](auto& j) { j.wrenches = bad_wrench; }},
      {"wrenches", "force", [&](auto& j) { j.wrenches = nan_wrench; }},
      {"targets", "", [&](auto& j) { j.targets = one_target; }},
      {"targets", "rotation", [&](auto& j) { j.targets = bad_rotation; }},
      {"targets", "stiffness", [&](auto& j) { j.targets = bad_gain; }},
  };
  for (const Case& c : cases) {
    ArticulatedStepJob job = good();
    c.spoil(job);
    const Status status = job.Validate();
    EXPECT_EQ(status.field, c.field) << ToString(status);
    EXPECT_EQ(status.member, c.member) << ToString(status);
    EXPECT_EQ(job.Run().field, c.field);
  }
  // State members, and Run leaves a refused state untouched.
  {
    ArticulatedStepJob job = good();
    state.joints[1].angle = NaN();
    const Status status = job.Run();
    EXPECT_EQ(status.field, "state");
    EXPECT_EQ(status.index, 1);
    EXPECT_EQ(status.member, "angle");
    EXPECT_TRUE(std::isnan(state.joints[1].angle));
    EXPECT_EQ(state.time, 0.0);
    state.joints[1].angle = 0.0;
  }
  {
    const ArticulatedModel free = MustBuild(FreeChainBodies());
    ArticulatedState s = MakeArticulatedState(free);
    ArticulatedWorkspace w = MakeArticulatedWorkspace(free);
    s.joints[2].rotation = Quat(1.0, 0.1, 0.0, 0.0);
    ArticulatedStepJob job;
    job.model = &free;
    job.dt = 1e-3;
    job.workspace = &w;
    job.state = &s;
    EXPECT_EQ(job.Validate().member, "rotation");
    EXPECT_EQ(job.Validate().index, 2);
  }
  // The evaluation and the measures refuse what they cannot use.
  {
    ArticulatedMeasures m;
    EXPECT_EQ(MeasureArticulated(model, state, Vec3::Zero(), nullptr).field, "out");
    EXPECT_EQ(MeasureArticulated(model, wrong_state, Vec3::Zero(), &m).field, "state");
    EXPECT_EQ(MeasureArticulated(model, state, Vec3(NaN(), 0, 0), &m).field, "gravity");
    EXPECT_EQ(EvaluateArticulatedBodies(model, nullptr).field, "state");
    EXPECT_EQ(EvaluateArticulatedBodies(model, &wrong_state).field, "state");
  }
  // RK4 refuses a step too long for an active limit; the semi-implicit step takes it.
  {
    std::vector<ArticulatedBodyDesc> bodies = PendulumBodies(Pendulum{});
    bodies[1].max_degrees.x() = 90.0;
    const ArticulatedModel limited = MustBuild(bodies);
    ArticulatedState s = MakeArticulatedState(limited);
    ArticulatedWorkspace w = MakeArticulatedWorkspace(limited);
    ArticulatedStepJob job;
    job.model = &limited;
    job.dt = 1.0 / 60.0;
    job.workspace = &w;
    job.state = &s;
    EXPECT_TRUE(job.Validate().ok());
    job.integrator = Integrator::kRk4;
    EXPECT_EQ(job.Validate().field, "dt");
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
