// Modal wire dynamics against independent references: the textbook natural frequency, static
// deflection and logarithmic decrement of a cantilever, the paper's sine-series coefficients
// (PHYSICS.md section 1), BendingJob's exact static solution, the closed-form step responses
// of a damped oscillator, energy conservation and step-size independence of the exact step,
// and input validation.
#include "wirerig/runtime/modal_wire.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "wirerig/runtime/bending_job.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr BoundaryCondition kFamilies[] = {
    BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped,
    BoundaryCondition::kCantileverFree, BoundaryCondition::kCantileverGuided};

// A wire of L = 1.3 m, EI = 2 N m^2, rho A = 0.5 kg/m (omega_1 = 4.16 rad/s as a cantilever).
constexpr double kL = 1.3, kEI = 2.0, kRhoA = 0.5;

ModalWireModel MakeModel(BoundaryCondition bc, double zeta, int modes = 8) {
  ModalWireModel model;
  EXPECT_TRUE(BuildModalBasis(bc, modes, &model.basis).ok());
  model.length = kL;
  model.bending_stiffness = kEI;
  model.mass_per_length = kRhoA;
  model.damping_ratio = zeta;
  return model;
}

// The first natural frequency of a cantilever from the textbook constant, rad/s.
double TextbookCantileverOmega() {
  return 1.8751 * 1.8751 * std::sqrt(kEI / (kRhoA * std::pow(kL, 4)));
}

// Steps a wire under fixed loads and records the displacement at one parameter after each step.
struct Simulation {
  ModalWireModel model;
  ModalWireState state;
  ModalWireLoads loads;
  double dt = 0.0;
  ModalHold hold = ModalHold::kZeroOrder;

  Vec3 Evaluate(double v) const {
    Vec3 x;
    ModalWireEvaluateJob job;
    job.model = &model;
    job.state = &state;
    job.loads = loads;
    job.samples = std::span<const double>(&v, 1);
    job.displacement = std::span<Vec3>(&x, 1);
    const Status status = job.Run();
    EXPECT_TRUE(status.ok()) << ToString(status);
    return x;
  }
  void Step() {
    ModalWireStepJob job;
    job.model = &model;
    job.loads = loads;
    job.dt = dt;
    job.hold = hold;
    job.state = &state;
    const Status status = job.Run();
    ASSERT_TRUE(status.ok()) << ToString(status);
  }
  // y of the displacement at v after each of `steps` steps.
  std::vector<double> Record(int steps, double v) {
    std::vector<double> y;
    y.reserve(steps);
    for (int i = 0; i < steps; ++i) {
      Step();
      y.push_back(Evaluate(v).y());
    }
    return y;
  }
};

// Times (in steps, interpolated) where y - mean changes sign upwards.
std::vector<double> UpwardCrossings(const std::vector<double>& y, double mean) {
  std::vector<double> t;
  for (std::size_t i = 1; i < y.size(); ++i) {
    const double a = y[i - 1] - mean, b = y[i] - mean;
    if (a < 0.0 && b >= 0.0) t.push_back(double(i - 1) + a / (a - b));
  }
  return t;
}

TEST(ModalWireCantilever, SuddenTipForceOscillatesAtTheFirstNaturalFrequency) {
  Simulation sim;
  sim.model = MakeModel(BoundaryCondition::kCantileverFree, 0.0);
  ASSERT_TRUE(InitializeModalWireAtRest(sim.model, &sim.state).ok());
  sim.loads.tip_force = Vec3(0.0, -1.5, 0.0);
  const double omega = TextbookCantileverOmega(), period = 2.0 * std::numbers::pi / omega;
  sim.dt = period / 400.0;
  const double mean = -1.5 * kL * kL * kL / (3.0 * kEI);  // F L^3 / 3 EI
  const std::vector<double> y = sim.Record(400 * 20, 1.0);
  // Right after the load is applied the wire is still nearly straight (only the modes above
  // N = 8 respond at once, statically): the tip lags.
  EXPECT_LT(std::abs(y[0]), 0.01 * std::abs(mean));
  const std::vector<double> t = UpwardCrossings(y, mean);
  ASSERT_GE(t.size(), 18u);
  const double measured = (t.back() - t.front()) / double(t.size() - 1) * sim.dt;
  const double error = measured / period - 1.0;
  std::printf("[measure] cantilever period %.9f s, textbook %.9f s, relative error %.2e\n",
              measured, period, error);
  EXPECT_LT(std::abs(error), 0.005);
  // Undamped: the tip swings between ~0 and ~2 F L^3 / 3EI.
  const auto [lo, hi] = std::minmax_element(y.begin(), y.end());
  EXPECT_NEAR(*hi, 0.0, 0.05 * std::abs(mean));
  EXPECT_NEAR(*lo, 2.0 * mean, 0.05 * std::abs(mean));
}

TEST(ModalWireCantilever, DampedTipSettlesAtFL3Over3EI) {
  for (ModalHold hold : {ModalHold::kZeroOrder, ModalHold::kFirstOrder}) {
    Simulation sim;
    sim.model = MakeModel(BoundaryCondition::kCantileverFree, 0.05);
    sim.hold = hold;
    ASSERT_TRUE(InitializeModalWireAtRest(sim.model, &sim.state).ok());
    sim.loads.tip_force = Vec3(0.4, -1.5, 0.0);
    const double omega = TextbookCantileverOmega();
    sim.dt = 0.02;
    // exp(-zeta omega t) < 1e-13.
    const int steps = int(30.0 / (0.05 * omega) / sim.dt) + 1;
    for (int i = 0; i < steps; ++i) sim.Step();
    const Vec3 tip = sim.Evaluate(1.0);
    const Vec3 expected = sim.loads.tip_force * (kL * kL * kL / (3.0 * kEI));
    const double error = (tip - expected).norm() / expected.norm();
    std::printf("[measure] settled tip relative error %.2e (%s hold)\n", error,
                hold == ModalHold::kZeroOrder ? "zero-order" : "first-order");
    EXPECT_LT(error, 1e-9);
  }
}

// Peaks of |y - mean| (parabolic refinement) from step `from` on.
std::vector<double> PeakValues(const std::vector<double>& y, double mean, std::size_t from) {
  std::vector<double> peaks;
  for (std::size_t i = std::max<std::size_t>(from, 1); i + 1 < y.size(); ++i) {
    const double a = y[i - 1] - mean, b = y[i] - mean, c = y[i + 1] - mean;
    if (b > a && b >= c && b > 0.0) {
      const double denominator = a - 2.0 * b + c;
      peaks.push_back(b - 0.125 * (a - c) * (a - c) / denominator);
    }
  }
  return peaks;
}

TEST(ModalWireCantilever, LogarithmicDecrementMatchesTheDampingRatio) {
  for (double zeta : {0.05, 0.2}) {
    SCOPED_TRACE(zeta);
    Simulation sim;
    sim.model = MakeModel(BoundaryCondition::kCantileverFree, zeta);
    ASSERT_TRUE(InitializeModalWireAtRest(sim.model, &sim.state).ok());
    sim.loads.tip_force = Vec3(0.0, 1.0, 0.0);
    const double omega = TextbookCantileverOmega(), period = 2.0 * std::numbers::pi / omega;
    sim.dt = period / 4000.0;
    const double mean = kL * kL * kL / (3.0 * kEI);
    const int cycles = zeta < 0.1 ? 10 : 5;
    const std::vector<double> y = sim.Record(4000 * cycles, 1.0);
    // From the fifth cycle on the second mode (6.3x the frequency, same zeta) has decayed to
    // below 5e-5 of the first (relative to its start).
    const std::vector<double> peaks = PeakValues(y, mean, 4000 * (zeta < 0.1 ? 4 : 2));
    ASSERT_GE(peaks.size(), 2u);
    const double measured = std::log(peaks.front() / peaks.back()) / double(peaks.size() - 1);
    const double expected = 2.0 * std::numbers::pi * zeta / std::sqrt(1.0 - zeta * zeta);
    std::printf("[measure] zeta %.2f: decrement %.9f, expected %.9f, relative error %.2e\n", zeta,
                measured, expected, measured / expected - 1.0);
    EXPECT_NEAR(measured, expected, 1e-4 * expected);
  }
}

// A wire at rest at its static shape (`state`) evaluates to the reference shape and slope at
// the samples `v`: displacement to 1e-13 of `scale`, slope to 1e-12 of scale / L.
void ExpectEvaluationAt(const ModalWireModel& model, const ModalWireState& state,
                        const ModalWireLoads& loads, const std::vector<double>& v,
                        const std::vector<Vec3>& x_ref, const std::vector<Vec3>& slope_ref,
                        double scale) {
  std::vector<Vec3> x(v.size()), slope(v.size());
  ModalWireEvaluateJob job;
  job.model = &model;
  job.state = &state;
  job.loads = loads;
  job.samples = v;
  job.displacement = x;
  job.slope = slope;
  ASSERT_TRUE(job.Run().ok());
  for (std::size_t i = 0; i < v.size(); ++i) {
    EXPECT_LT((x[i] - x_ref[i]).norm(), 1e-13 * scale) << v[i];
    EXPECT_LT((slope[i] - slope_ref[i]).norm(), 1e-12 * scale / kL) << v[i];
  }
}

TEST(ModalWireStatics, SimplySupportedPointLoadGivesTheSineSeriesCoefficients) {
  const ModalWireModel model = MakeModel(BoundaryCondition::kSimplySupported, 0.1, 16);
  const double a = 0.3;
  const Vec3 p(0.5, -2.0, 1.0);
  const std::vector<PointLoad> point = {{a, p}};
  ModalWireLoads loads;
  loads.point_loads = point;
  ModalWireState state;
  ASSERT_TRUE(InitializeModalWireAtStatic(model, loads, &state).ok());
  std::vector<Vec3> coordinates(16);
  ASSERT_TRUE(ComputeStaticModalCoordinates(model, loads, coordinates).ok());
  const double a1 = 2.0 * p.norm() * std::sin(std::numbers::pi * a) * std::pow(kL, 3) /
                    (std::pow(std::numbers::pi, 4) * kEI);
  for (int n = 1; n <= 16; ++n) {
    // Paper Eq. (11)-(12) with EI -> EI/L^3: p_n = 2 P sin(n pi a), A_n = p_n L^3/(n^4 pi^4 EI),
    // X = sum A_n sin(n pi v) = sum (A_n / sqrt 2) phi_n.
    const double npi = n * std::numbers::pi;
    const Vec3 an = 2.0 * p * std::sin(npi * a) * (kL * kL * kL) / (std::pow(npi, 4) * kEI);
    const Vec3 expected = an / std::sqrt(2.0);
    // Relative to the coefficient itself, or to rounding of A_1 where sin(n pi a) = 0 (n = 10).
    const double tolerance = 1e-14 * an.norm() + 1e-16 * a1;
    EXPECT_LT((state.q[n - 1] - expected).norm(), tolerance) << n;
    EXPECT_LT((coordinates[n - 1] - expected).norm(), tolerance) << n;
    EXPECT_EQ(state.q_dot[n - 1], Vec3::Zero());
  }
}

// The lateral part of alpha x (s t) + omega x (omega x (s t)) at s = 1 m, t = local z: the
// rigid-body acceleration of a point 1 m along the wire beyond its support's (computed here
// with cross products, independently of the runtime's formula).
Vec3 TurningAccelerationReference(const ModalWireLoads& loads) {
  const Vec3 t = Vec3::UnitZ();
  const Vec3& w = loads.support_angular_velocity;
  const Vec3 a = loads.support_angular_acceleration.cross(t) + w.cross(w.cross(t));
  return Vec3(a.x(), a.y(), 0.0);
}

// BendingJob's exact answer for the same loads (the inertial support loads as a uniform and a
// linear line load).
std::vector<Vec3> StaticReference(const ModalWireModel& model, const ModalWireLoads& loads,
                                  const std::vector<double>& v, std::vector<Vec3>* slope) {
  std::vector<LineLoad> line(loads.line_loads.begin(), loads.line_loads.end());
  line.push_back({0.0, 1.0, -model.mass_per_length * loads.support_acceleration});
  std::vector<LinearLineLoad> linear(loads.linear_line_loads.begin(),
                                     loads.linear_line_loads.end());
  const Vec3 turning = TurningAccelerationReference(loads);
  if (!turning.isZero(0.0))
    linear.push_back({0.0, 1.0, Vec3::Zero(), -model.mass_per_length * model.length * turning});
  std::vector<Vec3> x(v.size());
  slope->resize(v.size());
  BendingJob job;
  job.boundary = model.basis.boundary;
  job.length = model.length;
  job.bending_stiffness = model.bending_stiffness;
  job.start_displacement = loads.start_displacement;
  job.end_displacement = loads.end_displacement;
  job.tip_force = loads.tip_force;
  job.tip_couple = loads.tip_couple;
  job.point_loads = loads.point_loads;
  job.line_loads = line;
  job.linear_line_loads = linear;
  job.samples = v;
  job.displacement = x;
  job.slope = *slope;
  EXPECT_TRUE(job.Run().ok());
  return x;
}

// integral_0^1 X(v) phi_n(v) dv by composite Simpson over the even number of equal intervals
// `v` spans (v[0] = 0, v.back() = 1), X given at every v.
Vec3 SimpsonProjection(const ModalBasis& basis, int n, const std::vector<double>& v,
                       const std::vector<Vec3>& x) {
  const int intervals = int(v.size()) - 1;
  Vec3 projection = Vec3::Zero();
  for (int i = 0; i <= intervals; ++i) {
    const double w =
        (i == 0 || i == intervals ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0)) / (3.0 * intervals);
    projection += x[i] * (w * ModeValue(basis, n, v[i]));
  }
  return projection;
}

TEST(ModalWireStatics, AWireAtRestUnderItsLoadsIsBendingJobsExactSolution) {
  const std::vector<PointLoad> point = {{0.2, Vec3(0, -1, 0.5)}, {0.75, Vec3(0.3, 2, 0)}};
  const std::vector<LineLoad> line = {{0.1, 0.6, Vec3(1, 0, -2)}};
  std::vector<double> v(33);
  for (int i = 0; i <= 32; ++i) v[i] = i / 32.0;
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const ModalWireModel model = MakeModel(bc, 0.1);
    ModalWireLoads loads;
    loads.point_loads = point;
    loads.line_loads = line;
    loads.start_displacement = Vec3(0.01, 0.02, 0.0);
    if (!IsCantilever(bc)) loads.end_displacement = Vec3(0.0, -0.03, 0.01);
    if (IsCantilever(bc)) loads.tip_force = Vec3(0, 0.7, -0.2);
    loads.support_acceleration = Vec3(0.0, -9.81, 3.0);
    std::vector<Vec3> slope_ref;
    const std::vector<Vec3> x_ref = StaticReference(model, loads, v, &slope_ref);
    const double scale = x_ref[16].norm() + x_ref[32].norm();

    ModalWireState state;
    ASSERT_TRUE(InitializeModalWireAtStatic(model, loads, &state).ok());
    ExpectEvaluationAt(model, state, loads, v, x_ref, slope_ref, scale);
    // Stepping under the same loads keeps it there (to rounding).
    Simulation sim{model, state, loads, 0.01};
    for (int i = 0; i < 100; ++i) sim.Step();
    for (double at : {0.25, 1.0}) {  // on the reference's grid
      const std::size_t i = std::size_t(at * 32);
      EXPECT_LT((sim.Evaluate(at) - x_ref[i]).norm(), 1e-13 * scale);
    }
  }
}

TEST(ModalWireStatics, LinearLoadsAndATurningSupportAtRestAreBendingJobsExactSolution) {
  const std::vector<LinearLineLoad> linear = {{0.15, 0.65, Vec3(1, -2, 0), Vec3(-0.5, 3, 1)},
                                              {0.0, 1.0, Vec3(0, 0.4, 0), Vec3(0.8, 0, 0)}};
  std::vector<double> v(33);
  for (int i = 0; i <= 32; ++i) v[i] = i / 32.0;
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const ModalWireModel model = MakeModel(bc, 0.1);
    ModalWireLoads loads;
    loads.linear_line_loads = linear;
    loads.support_acceleration = Vec3(0.5, -9.81, 0.0);
    loads.support_angular_velocity = Vec3(0.7, -1.1, 1.6);
    loads.support_angular_acceleration = Vec3(-2.0, 3.5, 4.0);
    std::vector<Vec3> slope_ref;
    const std::vector<Vec3> x_ref = StaticReference(model, loads, v, &slope_ref);
    double scale = 0.0;
    for (const Vec3& x : x_ref) scale = std::max(scale, x.norm());
    ModalWireState state;
    ASSERT_TRUE(InitializeModalWireAtStatic(model, loads, &state).ok());
    ExpectEvaluationAt(model, state, loads, v, x_ref, slope_ref, scale);
    // Stepping under the same loads keeps it there (to rounding).
    Simulation sim{model, state, loads, 0.01};
    for (int i = 0; i < 100; ++i) sim.Step();
    EXPECT_LT((sim.Evaluate(0.75) - x_ref[24]).norm(), 1e-13 * scale);
  }
}

TEST(ModalWireStatics, LinearLoadAndTurningCoordinatesAreTheProjectionOfTheStaticSolution) {
  // As StaticCoordinatesAreTheProjectionOfTheStaticSolution: BendingJob's X under the linear
  // loads and the turning support's ramp, integrated against the modes by composite Simpson.
  const std::vector<LinearLineLoad> linear = {{0.1, 0.6, Vec3(1, 0, -2), Vec3(0, 2, 1)},
                                              {0.5, 1.0, Vec3(0, 3, 0), Vec3(-1, 0, 0)}};
  const int intervals = 20000;
  std::vector<double> v(intervals + 1);
  for (int i = 0; i <= intervals; ++i) v[i] = double(i) / intervals;
  double worst = 0.0;
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const ModalWireModel model = MakeModel(bc, 0.1, 12);
    ModalWireLoads loads;
    loads.linear_line_loads = linear;
    loads.support_angular_velocity = Vec3(1.2, 0.3, -0.9);
    loads.support_angular_acceleration = Vec3(0.0, -5.0, 2.0);
    std::vector<Vec3> slope;
    const std::vector<Vec3> x = StaticReference(model, loads, v, &slope);
    std::vector<Vec3> q(12);
    ASSERT_TRUE(ComputeStaticModalCoordinates(model, loads, q).ok());
    double scale = 0.0;
    for (int n = 0; n < 12; ++n) scale = std::max(scale, q[n].norm());
    for (int n = 0; n < 12; ++n) {
      const Vec3 projection = SimpsonProjection(model.basis, n, v, x);
      worst = std::max(worst, (q[n] - projection).norm() / scale);
      EXPECT_LT((q[n] - projection).norm(), 1e-10 * scale) << "mode " << n + 1;
    }
  }
  std::printf("[measure] linear-load static coordinates vs Simpson projection: worst %.1e\n",
              worst);
}

TEST(ModalWireStep, ModeValuesAtTheLoadsGiveTheSameStep) {
  const ModalWireModel model = MakeModel(BoundaryCondition::kClamped, 0.2, 12);
  const std::vector<PointLoad> point = {{0.15, Vec3(1, 0, 0)}, {0.6, Vec3(0, -2, 1)}};
  const std::vector<double> at = {0.15, 0.6};
  std::vector<double> table(2 * 12);
  ASSERT_TRUE(TabulateModes(model.basis, at, table, {}).ok());
  Simulation a;
  a.model = model;
  ASSERT_TRUE(InitializeModalWireAtRest(model, &a.state).ok());
  a.loads.point_loads = point;
  a.dt = 0.01;
  Simulation b = a;
  ModalWireStepJob job;
  job.model = &model;
  job.loads = b.loads;
  job.dt = b.dt;
  job.state = &b.state;
  job.point_load_modes = table;
  for (int i = 0; i < 20; ++i) {
    a.Step();
    ASSERT_TRUE(job.Run().ok());
  }
  for (int n = 0; n < 12; ++n) {
    EXPECT_LT((a.state.q[n] - b.state.q[n]).norm(), 1e-15 * a.state.q[0].norm()) << n;
    EXPECT_LT((a.state.q_static[n] - b.state.q_static[n]).norm(), 1e-15 * a.state.q[0].norm());
  }
  job.point_load_modes = std::span<const double>(table).first(23);
  EXPECT_EQ(job.Validate().field, "point_load_modes");
}

TEST(ModalWireStatics, StaticCoordinatesAreTheProjectionOfTheStaticSolution) {
  // The modes are orthonormal eigenfunctions, so the static solution X (homogeneous ends) has
  // the modal coordinates integral_0^1 X phi_n dv: BendingJob's X (line load for the support)
  // integrated by composite Simpson against the modes, independent of the projection code.
  const std::vector<PointLoad> point = {{0.2, Vec3(0, -1, 0.5)}, {0.75, Vec3(0.3, 2, 0)}};
  const std::vector<LineLoad> line = {{0.1, 0.6, Vec3(1, 0, -2)}, {0.5, 1.0, Vec3(0, 3, 0)}};
  const int intervals = 20000;
  std::vector<double> v(intervals + 1);
  for (int i = 0; i <= intervals; ++i) v[i] = double(i) / intervals;
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const ModalWireModel model = MakeModel(bc, 0.1, 12);
    ModalWireLoads loads;
    loads.point_loads = point;
    loads.line_loads = line;
    if (IsCantilever(bc)) loads.tip_force = Vec3(0, 0.7, -0.2);
    if (bc == BoundaryCondition::kCantileverFree) loads.tip_couple = Vec3(0.4, -0.3, 0.0);
    loads.support_acceleration = Vec3(0.0, -9.81, 3.0);
    std::vector<Vec3> slope;
    const std::vector<Vec3> x = StaticReference(model, loads, v, &slope);
    std::vector<Vec3> q(12);
    ASSERT_TRUE(ComputeStaticModalCoordinates(model, loads, q).ok());
    double scale = 0.0;
    for (int n = 0; n < 12; ++n) scale = std::max(scale, q[n].norm());
    for (int n = 0; n < 12; ++n) {
      const Vec3 projection = SimpsonProjection(model.basis, n, v, x);
      EXPECT_LT((q[n] - projection).norm(), 1e-10 * scale) << "mode " << n + 1;
    }
  }
}

// Closed-form response of q'' + 2 zeta w q' + w^2 q = w^2 t (a unit ramp) from rest, zeta < 1.
double RampResponse(double w, double zeta, double t) {
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  return t - 2.0 * zeta / w +
         std::exp(-zeta * w * t) * (2.0 * zeta / w * std::cos(wd * t) +
                                    (2.0 * zeta * zeta - 1.0) / wd * std::sin(wd * t));
}

TEST(ModalWireStep, FirstOrderHoldFollowsARampingLoadExactly) {
  for (double zeta : {0.0, 0.3}) {
    SCOPED_TRACE(zeta);
    Simulation sim;
    sim.model = MakeModel(BoundaryCondition::kCantileverGuided, zeta, 4);
    sim.hold = ModalHold::kFirstOrder;
    ASSERT_TRUE(InitializeModalWireAtRest(sim.model, &sim.state).ok());
    const Vec3 rate(0.0, 2.0, 0.0);  // N/s: the tip force grows from 0 at t = 0
    sim.loads.tip_force = rate;      // the coordinates per unit force, for the reference
    std::vector<Vec3> per_newton(4);
    ASSERT_TRUE(ComputeStaticModalCoordinates(sim.model, sim.loads, per_newton).ok());
    sim.dt = 0.0123;
    for (int step = 1; step <= 400; ++step) {
      sim.loads.tip_force = rate * (step * sim.dt);
      sim.Step();
      if (step % 80 != 0) continue;
      for (int n = 0; n < 4; ++n) {
        const double beta = sim.model.basis.beta[n];
        const double w = beta * beta * std::sqrt(kEI / (kRhoA * std::pow(kL, 4)));
        const double expected = per_newton[n].y() * RampResponse(w, zeta, step * sim.dt);
        EXPECT_NEAR(sim.state.q[n].y(), expected, 1e-11 * std::abs(per_newton[n].y()))
            << "mode " << n << " step " << step;
      }
    }
  }
}

TEST(ModalWireEvaluate, TablesGiveTheSameAnswerAsEvaluatingTheModes) {
  const ModalWireModel model = MakeModel(BoundaryCondition::kCantileverGuided, 0.0, 12);
  std::vector<double> v = {0.0, 0.1, 0.33, 0.5, 0.77, 1.0};
  std::vector<double> values(v.size() * 12), slopes(v.size() * 12);
  ASSERT_TRUE(TabulateModes(model.basis, v, values, slopes).ok());
  Simulation sim;
  sim.model = model;
  ASSERT_TRUE(InitializeModalWireAtRest(model, &sim.state).ok());
  sim.loads.tip_force = Vec3(1.0, 2.0, -1.0);
  sim.dt = 0.013;
  for (int i = 0; i < 37; ++i) sim.Step();
  std::vector<Vec3> x1(v.size()), s1(v.size()), x2(v.size()), s2(v.size());
  ModalWireEvaluateJob job;
  job.model = &model;
  job.state = &sim.state;
  job.loads = sim.loads;
  job.samples = v;
  job.displacement = x1;
  job.slope = s1;
  ASSERT_TRUE(job.Run().ok());
  job.mode_values = values;
  job.mode_slopes = slopes;
  job.displacement = x2;
  job.slope = s2;
  ASSERT_TRUE(job.Run().ok());
  for (std::size_t i = 0; i < v.size(); ++i) {
    EXPECT_LT((x1[i] - x2[i]).norm(), 1e-14);
    EXPECT_LT((s1[i] - s2[i]).norm(), 1e-13);
  }
  // The slope is dX/ds: central differences of the displacement.
  const double h = 1e-6;
  for (double at : {0.2, 0.6}) {
    const Vec3 d = (sim.Evaluate(at + h) - sim.Evaluate(at - h)) / (2.0 * h * kL);
    std::vector<double> one = {at};
    Vec3 x, s;
    job.samples = one;
    job.mode_values = {};
    job.mode_slopes = {};
    job.displacement = std::span<Vec3>(&x, 1);
    job.slope = std::span<Vec3>(&s, 1);
    ASSERT_TRUE(job.Run().ok());
    EXPECT_LT((s - d).norm(), 1e-7);
  }
}

// A recorded residual (what a .wclip keeps per wire and frame) against its definition: BendingJob's
// exact solution for the uniform and the ramp load, plus sum_n r_n phi_n(v) with the modes
// evaluated one by one; the slope against central differences of that reference.
TEST(ModalResidual, IsTheClosedFormOfItsLoadsPlusItsModes) {
  const std::vector<double> v = {0.0, 0.15, 0.4, 0.5, 0.81, 1.0};
  for (BoundaryCondition bc : kFamilies) {
    const ModalWireModel model = MakeModel(bc, 0.0, 6);
    std::vector<double> values(v.size() * 6), slopes(v.size() * 6);
    ASSERT_TRUE(TabulateModes(model.basis, v, values, slopes).ok());
    ModalResidual r;
    r.modes = 6;
    for (int n = 0; n < 6; ++n) r.coordinates[n] = Vec3(0.01 * (n + 1), -0.004 * n, 0.002);
    r.uniform_load = Vec3(0.7, -1.2, 0.0);
    r.turning_load = Vec3(-0.5, 0.3, 0.0);
    // The reference at one v: BendingJob with the two loads, plus the modes.
    const auto reference = [&](double at) {
      const LineLoad uniform{0.0, 1.0, r.uniform_load};
      const LinearLineLoad ramp{0.0, 1.0, Vec3::Zero(), r.turning_load};
      std::vector<double> one = {at};
      Vec3 x = Vec3::Zero();
      BendingJob bending;
      bending.boundary = bc;
      bending.length = kL;
      bending.bending_stiffness = kEI;
      bending.line_loads = std::span<const LineLoad>(&uniform, 1);
      bending.linear_line_loads = std::span<const LinearLineLoad>(&ramp, 1);
      bending.samples = one;
      bending.displacement = std::span<Vec3>(&x, 1);
      EXPECT_TRUE(bending.Run().ok());
      for (int n = 0; n < 6; ++n) x += r.coordinates[n] * ModeValue(model.basis, n, at);
      return x;
    };
    std::vector<Vec3> x(v.size()), s(v.size());
    ModalResidualJob job;
    job.boundary = bc;
    job.length = kL;
    job.bending_stiffness = kEI;
    job.residual = &r;
    job.samples = v;
    job.mode_values = values;
    job.mode_slopes = slopes;
    job.displacement = x;
    job.slope = s;
    ASSERT_TRUE(job.Run().ok());
    const double h = 1e-6;
    for (std::size_t i = 0; i < v.size(); ++i) {
      EXPECT_LT((x[i] - reference(v[i])).norm(), 1e-13) << int(bc) << " v " << v[i];
      if (v[i] > 0.0 && v[i] < 1.0) {
        const Vec3 d = (reference(v[i] + h) - reference(v[i] - h)) / (2.0 * h * kL);
        EXPECT_LT((s[i] - d).norm(), 1e-7) << int(bc) << " v " << v[i];
      }
    }
  }
}

TEST(ModalResidual, InvalidInputsAreNamed) {
  const ModalWireModel model = MakeModel(BoundaryCondition::kCantileverFree, 0.0, 4);
  const std::vector<double> v = {0.0, 0.5, 1.0};
  std::vector<double> values(12), slopes(12);
  ASSERT_TRUE(TabulateModes(model.basis, v, values, slopes).ok());
  ModalResidual r;
  r.modes = 4;
  std::vector<Vec3> x(3), s(3);
  const auto run = [&](auto change) {
    ModalResidualJob job;
    job.length = kL;
    job.bending_stiffness = kEI;
    job.residual = &r;
    job.samples = v;
    job.mode_values = values;
    job.mode_slopes = slopes;
    job.displacement = x;
    job.slope = s;
    change(job);
    return ToString(job.Run());
  };
  EXPECT_EQ(run([](ModalResidualJob&) {}), "ok");
  EXPECT_EQ(run([](ModalResidualJob& j) { j.length = 0.0; }).rfind("length", 0), 0u);
  EXPECT_EQ(run([](ModalResidualJob& j) { j.residual = nullptr; }).rfind("residual", 0), 0u);
  EXPECT_EQ(run([](ModalResidualJob& j) { j.mode_values = {}; }).rfind("mode_values", 0), 0u);
  EXPECT_EQ(run([](ModalResidualJob& j) { j.mode_slopes = {}; }).rfind("mode_slopes", 0), 0u);
  EXPECT_EQ(run([](ModalResidualJob& j) { j.displacement = {}; }).rfind("displacement", 0), 0u);
  r.coordinates[2].x() = std::nan("");
  EXPECT_EQ(run([](ModalResidualJob&) {}).rfind("residual[2].coordinates", 0), 0u);
  r.coordinates[2].x() = 0.0;
  r.uniform_load.y() = 1e13;
  EXPECT_EQ(run([](ModalResidualJob&) {}).rfind("residual", 0), 0u);
  for (const Vec3& out : x) EXPECT_TRUE(out.allFinite());
}

// Closed-form response of q'' + 2 zeta w q' + w^2 q = w^2 qs from rest (a unit step).
double StepResponse(double w, double zeta, double t) {
  if (zeta < 1.0) {
    const double wd = w * std::sqrt(1.0 - zeta * zeta);
    return 1.0 - std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t));
  }
  if (zeta == 1.0) return 1.0 - (1.0 + w * t) * std::exp(-w * t);
  const double mu = w * std::sqrt(zeta * zeta - 1.0);
  const double r1 = -zeta * w + mu, r2 = -zeta * w - mu;
  return 1.0 - (r2 * std::exp(r1 * t) - r1 * std::exp(r2 * t)) / (r2 - r1);
}

TEST(ModalWireStep, ModesFollowTheDampedOscillatorsStepResponse) {
  // Every damping regime, including both sides of critical damping.
  for (double zeta : {0.0, 0.3, 1.0 - 1e-7, 1.0, 1.0 + 1e-7, 2.5, 40.0}) {
    SCOPED_TRACE(zeta);
    Simulation sim;
    sim.model = MakeModel(BoundaryCondition::kClamped, zeta, 4);
    ASSERT_TRUE(InitializeModalWireAtRest(sim.model, &sim.state).ok());
    const std::vector<PointLoad> point = {{0.4, Vec3(0.0, 3.0, 0.0)}};
    sim.loads.point_loads = point;
    sim.dt = 0.0037;
    std::vector<Vec3> qs(4);
    ASSERT_TRUE(ComputeStaticModalCoordinates(sim.model, sim.loads, qs).ok());
    for (int step = 1; step <= 300; ++step) {
      sim.Step();
      if (step % 50 != 0) continue;
      for (int n = 0; n < 4; ++n) {
        // omega_n from the (separately tested) eigenvalue and the textbook formula.
        const double beta = sim.model.basis.beta[n];
        const double w = beta * beta * std::sqrt(kEI / (kRhoA * std::pow(kL, 4)));
        const double expected = qs[n].y() * StepResponse(w, zeta, step * sim.dt);
        EXPECT_NEAR(sim.state.q[n].y(), expected, 1e-11 * std::abs(qs[n].y()))
            << "mode " << n << " step " << step;
      }
    }
  }
}

TEST(ModalWireStep, OneStepEqualsSevenSubsteps) {
  const std::vector<PointLoad> point = {{0.35, Vec3(0.2, -1.0, 0.4)}};
  for (double zeta : {0.0, 0.3, 1.0, 2.5}) {
    for (BoundaryCondition bc : kFamilies) {
      SCOPED_TRACE(::testing::Message() << ToString(bc) << " zeta " << zeta);
      const ModalWireModel model = MakeModel(bc, zeta, 16);
      // Zero-order hold, constant loads, from a moving state.
      Simulation a{model, ModalWireState(), ModalWireLoads(), 0.01};
      ASSERT_TRUE(InitializeModalWireAtRest(model, &a.state).ok());
      a.loads.point_loads = point;
      a.loads.support_acceleration = Vec3(1.0, 0.0, -2.0);
      for (int i = 0; i < 5; ++i) a.Step();
      Simulation b = a;
      a.dt = 0.07;
      a.Step();
      b.dt = 0.01;
      for (int i = 0; i < 7; ++i) b.Step();
      double scale = 0.0;
      for (int n = 0; n < 16; ++n) scale = std::max(scale, a.state.q[n].norm());
      for (int n = 0; n < 16; ++n) {
        EXPECT_LT((a.state.q[n] - b.state.q[n]).norm(), 1e-12 * scale) << n;
        const double w = ModalFrequency(model, n);
        EXPECT_LT((a.state.q_dot[n] - b.state.q_dot[n]).norm(), 1e-12 * scale * w) << n;
      }
      // First-order hold: a load ramping linearly over the step is exact, so one step of
      // 0.07 s equals seven of 0.01 s with the ramp sampled at each.
      const auto ramp = [](double t) -> Vec3 { return Vec3(0.2, -1.0, 0.4) * (1.0 + 30.0 * t); };
      Simulation c{model, b.state, ModalWireLoads(), 0.07, ModalHold::kFirstOrder};
      Simulation d = c;
      std::vector<PointLoad> pc = {{0.35, ramp(0.07)}};
      c.loads.point_loads = pc;
      c.loads.support_acceleration = a.loads.support_acceleration;
      c.Step();
      d.dt = 0.01;
      d.loads.support_acceleration = a.loads.support_acceleration;
      for (int i = 1; i <= 7; ++i) {
        std::vector<PointLoad> pd = {{0.35, ramp(0.01 * i)}};
        d.loads.point_loads = pd;
        d.Step();
      }
      for (int n = 0; n < 16; ++n) {
        EXPECT_LT((c.state.q[n] - d.state.q[n]).norm(), 1e-12 * scale) << n;
        const double w = ModalFrequency(model, n);
        EXPECT_LT((c.state.q_dot[n] - d.state.q_dot[n]).norm(), 1e-12 * scale * w) << n;
      }
    }
  }
}

// Kinetic plus strain energy of the modal motion about q_static, J.
double ModalEnergy(const ModalWireModel& model, const ModalWireState& state) {
  double energy = 0.0;
  for (int n = 0; n < state.modes; ++n) {
    const double beta = model.basis.beta[n];
    const double w2 = std::pow(beta, 4) * kEI / (kRhoA * std::pow(kL, 4));
    const Vec3 u = state.q[n] - state.q_static[n];
    energy += 0.5 * kRhoA * kL * (state.q_dot[n].squaredNorm() + w2 * u.squaredNorm());
  }
  return energy;
}

TEST(ModalWireStep, UndampedFreeOscillationKeepsItsEnergyOver1e5Steps) {
  for (BoundaryCondition bc : {BoundaryCondition::kCantileverFree, BoundaryCondition::kClamped}) {
    SCOPED_TRACE(ToString(bc));
    Simulation sim;
    sim.model = MakeModel(bc, 0.0);
    const std::vector<PointLoad> point = {{0.6, Vec3(0.5, -1.0, 0.0)}};
    ModalWireLoads loaded;
    loaded.point_loads = point;
    ASSERT_TRUE(InitializeModalWireAtStatic(sim.model, loaded, &sim.state).ok());
    sim.dt = 1.0 / 60.0;  // the load is released: free vibration about the straight wire
    sim.Step();
    const double start = ModalEnergy(sim.model, sim.state);
    ModalStepTable table;
    ASSERT_TRUE(PrecomputeModalStep(sim.model, sim.dt, &table).ok());
    ModalWireStepJob job;
    job.model = &sim.model;
    job.dt = sim.dt;
    job.step_table = &table;
    job.state = &sim.state;
    for (int i = 0; i < 100000; ++i) ASSERT_TRUE(job.Run().ok());
    const double end = ModalEnergy(sim.model, sim.state);
    std::printf("[measure] %s energy after 1e5 steps: relative change %.2e\n",
                std::string(ToString(bc)).c_str(), end / start - 1.0);
    EXPECT_GT(start, 0.0);
    EXPECT_NEAR(end, start, 1e-10 * start);
  }
}

TEST(ModalWireSupport, ConstantSupportAccelerationSettlesAtTheInertialLoadsDeflection) {
  Simulation sim;
  sim.model = MakeModel(BoundaryCondition::kCantileverFree, 0.1);
  ASSERT_TRUE(InitializeModalWireAtRest(sim.model, &sim.state).ok());
  const double a = 12.0;  // m/s^2 along +y, from t = 0
  sim.loads.support_acceleration = Vec3(0.0, a, 0.0);
  sim.dt = 0.005;
  const double w = -kRhoA * a;                                // N/m, the inertial load
  const double expected = w * std::pow(kL, 4) / (8.0 * kEI);  // tip, w L^4 / 8EI
  const std::vector<double> y = sim.Record(int(60.0 / sim.dt), 1.0);
  // The wire lags at first and overshoots: for the first mode alone the peak would be
  // 1 + exp(-pi zeta / sqrt(1 - zeta^2)) = 1.73 times the static deflection.
  EXPECT_LT(std::abs(y[0]), 0.02 * std::abs(expected));
  const double peak = *std::min_element(y.begin(), y.end()) / expected;
  std::printf("[measure] support acceleration: overshoot %.4f x static, settled error %.2e\n", peak,
              std::abs(y.back() / expected - 1.0));
  EXPECT_NEAR(peak, 1.0 + std::exp(-std::numbers::pi * 0.1 / std::sqrt(1.0 - 0.01)), 0.03);
  EXPECT_NEAR(y.back(), expected, 1e-9 * std::abs(expected));
  // The same with a precomputed table and the slope: zero at the clamp.
  std::vector<double> v = {0.0, 1.0};
  std::vector<Vec3> x(2), s(2);
  ModalWireEvaluateJob job;
  job.model = &sim.model;
  job.state = &sim.state;
  job.loads = sim.loads;
  job.samples = v;
  job.displacement = x;
  job.slope = s;
  ASSERT_TRUE(job.Run().ok());
  EXPECT_LT(x[0].norm(), 1e-15 * std::abs(expected));
  EXPECT_LT(s[0].norm(), 1e-12);
  EXPECT_NEAR(s[1].y(), w * std::pow(kL, 3) / (6.0 * kEI), 1e-9 * std::abs(expected));
}

// A cantilever whose support starts turning at constant angular acceleration alpha about local
// y (omega ~ 0): the point at s accelerates by alpha s along +x, so the wire feels the ramp
// -rho A alpha s and settles (damped) at its textbook static deflection, tip
// 11 w L^4 / 120 EI with w = rho A alpha L, i.e. 11 rho A alpha L^5 / (120 EI), against the turn.
TEST(ModalWireSupport, ConstantAngularAccelerationSettlesAtTheRampLoadsDeflection) {
  Simulation sim;
  sim.model = MakeModel(BoundaryCondition::kCantileverFree, 0.1);
  ASSERT_TRUE(InitializeModalWireAtRest(sim.model, &sim.state).ok());
  const double alpha = 7.0;  // rad/s^2 about +y: alpha x z = +x
  sim.loads.support_angular_acceleration = Vec3(0.0, alpha, 0.0);
  sim.dt = 0.005;
  const double expected = -11.0 * kRhoA * alpha * std::pow(kL, 5) / (120.0 * kEI);
  std::vector<double> x;
  for (int i = 0; i < int(60.0 / sim.dt); ++i) {
    sim.Step();
    x.push_back(sim.Evaluate(1.0).x());
  }
  // It lags at first and overshoots (about 1 + exp(-pi zeta / sqrt(1 - zeta^2)) = 1.73 for the
  // first mode alone), then settles.
  EXPECT_LT(std::abs(x[0]), 0.02 * std::abs(expected));
  const double peak = *std::min_element(x.begin(), x.end()) / expected;
  const Vec3 tip = sim.Evaluate(1.0);
  std::printf("[measure] turning support: overshoot %.4f x static, settled error %.2e\n", peak,
              std::abs(tip.x() / expected - 1.0));
  EXPECT_NEAR(peak, 1.73, 0.05);
  EXPECT_NEAR(tip.x(), expected, 1e-9 * std::abs(expected));
  EXPECT_EQ(tip.y(), 0.0);
  // The settled shape is the textbook curve w x^2 (20 L^3 - 10 L^2 x + x^3) / (120 L EI).
  for (double v : {0.25, 0.5, 0.75}) {
    const double s = v * kL;
    const double shape = -kRhoA * alpha * kL * s * s *
                         (20 * kL * kL * kL - 10 * kL * kL * s + s * s * s) / (120 * kL * kEI);
    EXPECT_NEAR(sim.Evaluate(v).x(), shape, 1e-9 * std::abs(expected)) << "v = " << v;
  }
}

// A support spinning steadily about a tilted axis (omega = (w_x, 0, w_z)): the centripetal
// acceleration of the point at s, omega x (omega x s t), has the lateral part s w_z w_x along
// x, so the wire settles at the ramp's deflection, tip -11 rho A w_z w_x L^5 / (120 EI).
TEST(ModalWireSupport, SteadySpinAboutATiltedAxisSettlesAtItsCentripetalRamp) {
  for (BoundaryCondition bc : {BoundaryCondition::kCantileverFree, BoundaryCondition::kClamped}) {
    SCOPED_TRACE(ToString(bc));
    Simulation sim;
    sim.model = MakeModel(bc, 0.3);
    ASSERT_TRUE(InitializeModalWireAtRest(sim.model, &sim.state).ok());
    sim.loads.support_angular_velocity = Vec3(1.5, 0.0, 2.0);
    sim.dt = 0.01;
    for (int i = 0; i < int(40.0 / sim.dt); ++i) sim.Step();
    const Vec3 lateral = TurningAccelerationReference(sim.loads);
    ASSERT_NEAR(lateral.x(), 3.0, 1e-15);
    const double w = -kRhoA * lateral.x() * kL;  // N/m at the far end
    const double l4 = std::pow(kL, 4) / kEI;
    if (bc == BoundaryCondition::kCantileverFree) {
      EXPECT_NEAR(sim.Evaluate(1.0).x(), 11.0 * w * l4 / 120.0, 1e-9 * std::abs(w * l4));
    } else {
      // Clamped at both ends: w x^2 (L - x)^2 (2L + x) / (120 L EI) at midspan, 5/3840 w L^4/EI.
      EXPECT_NEAR(sim.Evaluate(0.5).x(), 5.0 * w * l4 / 3840.0, 1e-9 * std::abs(w * l4));
    }
    EXPECT_EQ(sim.Evaluate(0.5).y(), 0.0);
  }
}

TEST(ModalWireValidate, InvalidInputsAreNamed) {
  ModalWireModel model = MakeModel(BoundaryCondition::kCantileverFree, 0.05);
  ModalWireState state;
  ASSERT_TRUE(InitializeModalWireAtRest(model, &state).ok());
  ModalWireStepJob job;
  job.model = &model;
  job.dt = 0.01;
  job.state = &state;
  ASSERT_TRUE(job.Validate().ok());
  const auto field = [&](auto edit) {
    ModalWireModel m = model;
    ModalWireState st = state;
    ModalWireStepJob j = job;
    j.model = &m;
    j.state = &st;
    edit(m, st, j);
    const Status status = j.Run();
    // A refused Run leaves the state alone.
    if (!status.ok() && j.state == &st) {
      EXPECT_EQ(st.q[0], state.q[0]);
    }
    return std::string(status.field);
  };
  const double nan = std::nan(""), inf = HUGE_VAL;
  using M = ModalWireModel;
  using S = ModalWireState;
  using J = ModalWireStepJob;
  EXPECT_EQ(field([](M&, S&, J& j) { j.model = nullptr; }), "model");
  EXPECT_EQ(field([](M& m, S&, J&) { m.basis = ModalBasis(); }), "basis");
  EXPECT_EQ(field([](M& m, S&, J&) { m.basis.modes = 33; }), "basis");
  EXPECT_EQ(field([](M& m, S&, J&) { m.basis.boundary = static_cast<BoundaryCondition>(7); }),
            "basis");
  EXPECT_EQ(field([](M& m, S&, J&) { m.mass_per_length = -1.0; }), "mass_per_length");
  EXPECT_EQ(field([](M& m, S&, J&) { m.mass_per_length = 0.0; }), "mass_per_length");
  EXPECT_EQ(field([](M& m, S&, J&) { m.mass_per_length = 1e-40; }), "mass_per_length");
  EXPECT_EQ(field([](M& m, S&, J&) { m.mass_per_length = 1e40; }), "mass_per_length");
  EXPECT_EQ(field([](M& m, S&, J&) { m.length = 0.0; }), "length");
  EXPECT_EQ(field([&](M& m, S&, J&) { m.bending_stiffness = nan; }), "bending_stiffness");
  EXPECT_EQ(field([](M& m, S&, J&) { m.damping_ratio = -0.01; }), "damping_ratio");
  EXPECT_EQ(field([&](M& m, S&, J&) { m.damping_ratio = nan; }), "damping_ratio");
  EXPECT_EQ(field([](M& m, S&, J&) { m.damping_ratio = 101.0; }), "damping_ratio");
  EXPECT_EQ(field([](M&, S&, J& j) { j.dt = 0.0; }), "dt");
  EXPECT_EQ(field([](M&, S&, J& j) { j.dt = -0.01; }), "dt");
  EXPECT_EQ(field([&](M&, S&, J& j) { j.dt = nan; }), "dt");
  EXPECT_EQ(field([&](M&, S&, J& j) { j.dt = inf; }), "dt");
  EXPECT_EQ(field([](M&, S&, J& j) { j.hold = static_cast<ModalHold>(5); }), "hold");
  EXPECT_EQ(field([](M&, S&, J& j) { j.state = nullptr; }), "state");
  EXPECT_EQ(field([](M&, S& s, J&) { s.modes = 7; }), "state");
  EXPECT_EQ(field([&](M&, S& s, J&) { s.q[3].x() = nan; }), "state");
  EXPECT_EQ(field([&](M&, S& s, J&) { s.q_dot[0].y() = inf; }), "state");
  EXPECT_EQ(field([&](M&, S&, J& j) { j.loads.support_acceleration.z() = nan; }),
            "support_acceleration");
  EXPECT_EQ(field([](M&, S&, J& j) { j.loads.support_acceleration.z() = 1e200; }),
            "support_acceleration");
  EXPECT_EQ(field([&](M&, S&, J& j) { j.loads.support_angular_velocity.x() = nan; }),
            "support_angular_velocity");
  EXPECT_EQ(field([&](M&, S&, J& j) { j.loads.support_angular_velocity.z() = -inf; }),
            "support_angular_velocity");
  EXPECT_EQ(field([](M&, S&, J& j) { j.loads.support_angular_velocity.y() = 1e100; }),
            "support_angular_velocity");
  EXPECT_EQ(field([&](M&, S&, J& j) { j.loads.support_angular_acceleration.y() = nan; }),
            "support_angular_acceleration");
  EXPECT_EQ(field([](M&, S&, J& j) { j.loads.support_angular_acceleration.x() = -1e200; }),
            "support_angular_acceleration");
  EXPECT_EQ(field([](M&, S&, J& j) { j.loads.support_angular_acceleration.x() = 1e3; }), "");
  const std::vector<LinearLineLoad> reversed = {{0.6, 0.2, Vec3::UnitY(), Vec3::UnitX()}};
  EXPECT_EQ(field([&](M&, S&, J& j) { j.loads.linear_line_loads = reversed; }),
            "linear_line_loads");
  const std::vector<LinearLineLoad> nan_load = {{0.2, 0.6, Vec3(0, nan, 0), Vec3::UnitX()}};
  EXPECT_EQ(field([&](M&, S&, J& j) { j.loads.linear_line_loads = nan_load; }),
            "linear_line_loads");
  EXPECT_EQ(field([&](M&, S&, J& j) { j.loads.tip_force.x() = inf; }), "tip_force");
  const std::vector<PointLoad> outside = {{1.2, Vec3::UnitY()}};
  EXPECT_EQ(field([&](M&, S&, J& j) { j.loads.point_loads = outside; }), "point_loads");
  ModalStepTable table;
  ASSERT_TRUE(PrecomputeModalStep(model, 0.02, &table).ok());
  EXPECT_EQ(field([&](M&, S&, J& j) { j.step_table = &table; }), "step_table");
  EXPECT_EQ(field([&](M&, S&, J& j) { j.step_table = &table, j.dt = 0.02; }), "");
  EXPECT_EQ(
      field([&](M& m, S&, J& j) { j.step_table = &table, j.dt = 0.02, m.damping_ratio = 0.1; }),
      "step_table");

  // A tip force on a simply supported wire: the supports would take it.
  ModalWireModel ss = MakeModel(BoundaryCondition::kSimplySupported, 0.05);
  ModalWireLoads tip;
  tip.tip_force = Vec3::UnitY();
  EXPECT_EQ(InitializeModalWireAtStatic(ss, tip, &state).field, "tip_force");
  EXPECT_EQ(PrecomputeModalStep(model, 0.0, &table).field, "dt");
  EXPECT_EQ(PrecomputeModalStep(model, 0.01, nullptr).field, "out");
  std::vector<Vec3> few(3);
  EXPECT_EQ(ComputeStaticModalCoordinates(model, ModalWireLoads(), few).field, "out");

  // The evaluation job.
  ASSERT_TRUE(InitializeModalWireAtRest(model, &state).ok());
  std::vector<double> v = {0.0, 0.5, 1.0};
  std::vector<Vec3> x(3), s(3), short_out(2);
  std::vector<double> values(3 * 8), slopes(3 * 8), short_table(7);
  ASSERT_TRUE(TabulateModes(model.basis, v, values, slopes).ok());
  ModalWireEvaluateJob eval;
  eval.model = &model;
  eval.state = &state;
  eval.samples = v;
  eval.displacement = x;
  ASSERT_TRUE(eval.Validate().ok());
  const auto eval_field = [&](auto edit) {
    ModalWireEvaluateJob e = eval;
    edit(e);
    return std::string(e.Run().field);
  };
  using E = ModalWireEvaluateJob;
  EXPECT_EQ(eval_field([](E& e) { e.model = nullptr; }), "model");
  EXPECT_EQ(eval_field([](E& e) { e.state = nullptr; }), "state");
  EXPECT_EQ(eval_field([&](E& e) { e.samples = {}; }), "samples");
  EXPECT_EQ(eval_field([&](E& e) { e.displacement = short_out; }), "displacement");
  EXPECT_EQ(eval_field([&](E& e) { e.slope = short_out; }), "slope");
  EXPECT_EQ(eval_field([&](E& e) { e.mode_values = short_table; }), "mode_values");
  EXPECT_EQ(eval_field([&](E& e) { e.mode_slopes = slopes; }), "mode_slopes");
  EXPECT_EQ(eval_field([&](E& e) { e.mode_values = values, e.slope = s; }), "mode_slopes");
  EXPECT_EQ(eval_field([&](E& e) { e.mode_values = values, e.mode_slopes = slopes, e.slope = s; }),
            "");
  EXPECT_EQ(eval_field([&](E& e) { e.loads.support_angular_velocity.x() = nan; }),
            "support_angular_velocity");
  EXPECT_EQ(eval_field([&](E& e) { e.loads.support_angular_acceleration.x() = inf; }),
            "support_angular_acceleration");
  const std::vector<LinearLineLoad> beyond = {{0.2, 1.5, Vec3::UnitY(), Vec3::UnitX()}};
  EXPECT_EQ(eval_field([&](E& e) { e.loads.linear_line_loads = beyond; }), "linear_line_loads");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
