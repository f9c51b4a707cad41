// AxialJob against the paper's candle (Figs. 5b, 5c; PHYSICS.md section 3) and against
// numerical integration of the internal force N(s), computed here independently.
#include "wirerig/runtime/axial_job.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

struct AxialResult {
  std::vector<double> x, n;
};

AxialResult Solve(double length, double ea, double v0, const std::vector<AxialPointLoad>& p,
                  const std::vector<AxialLineLoad>& q, const std::vector<double>& v) {
  AxialResult r{std::vector<double>(v.size()), std::vector<double>(v.size())};
  AxialJob job;
  job.length = length;
  job.axial_stiffness = ea;
  job.fixed_at = v0;
  job.point_loads = p;
  job.line_loads = q;
  job.samples = v;
  job.displacement = r.x;
  job.normal_force = r.n;
  const Status status = job.Run();
  EXPECT_TRUE(status.ok()) << ToString(status);
  return r;
}

// The candle: 101 nodes v_j = j/100 with a force at each node.
std::vector<AxialPointLoad> CandleLoads(double v0, double force_above, double force_below) {
  std::vector<AxialPointLoad> loads;
  for (int j = 0; j <= 100; ++j) {
    const double v = j / 100.0;
    if (v > v0) loads.push_back({v, force_above});
    if (v < v0) loads.push_back({v, force_below});
  }
  return loads;
}

constexpr double kF = 2.0, kEA = 50.0;

TEST(AxialJobCandle, Fig5cMiddleFixedOppositeForces) {
  const auto loads = CandleLoads(0.5, kF, -kF);
  const AxialResult r = Solve(1.0, kEA, 0.5, loads, {}, {0.0, 0.5, 1.0});
  EXPECT_NEAR(r.x[2], 12.75 * kF / kEA, 1e-13);
  EXPECT_NEAR(r.x[0], -12.75 * kF / kEA, 1e-13);
  EXPECT_EQ(r.x[1], 0.0);
}

TEST(AxialJobCandle, Fig5cBothHalvesAreInTensionLargestAtTheSupport) {
  const auto loads = CandleLoads(0.5, kF, -kF);
  std::vector<double> mid;  // midpoints of the segments (v_k, v_k+1)
  for (int k = 0; k < 100; ++k) mid.push_back((k + 0.5) / 100.0);
  const AxialResult r = Solve(1.0, kEA, 0.5, loads, {}, mid);
  for (int k = 0; k < 100; ++k) {
    const double expected = k >= 50 ? (100 - k) * kF : (k + 1) * kF;
    EXPECT_NEAR(r.n[k], expected, 1e-12) << "segment " << k;
  }
}

TEST(AxialJobCandle, Fig5bTopFixedDownwardForces) {
  const auto loads = CandleLoads(1.0, 0.0, -kF);
  const AxialResult r = Solve(1.0, kEA, 1.0, loads, {}, {0.0, 0.5, 1.0});
  // X(0) = -(F/EA) sum_{j<100} (1 - j/100) = -50.5 F/EA; X(0.5) = -(F/EA) sum (1 - max(.5, v_j)).
  EXPECT_NEAR(r.x[0], -50.5 * kF / kEA, 1e-12);
  double half = 0.0;
  for (int j = 0; j < 100; ++j) half += 1.0 - std::max(0.5, j / 100.0);
  EXPECT_NEAR(r.x[1], -half * kF / kEA, 1e-12);
  EXPECT_EQ(r.x[2], 0.0);
}

// Independent reference: N(s) from its definition, integrated by the midpoint rule from v0.
double IntegrateNormalForce(double length, double ea, double v0,
                            const std::vector<AxialPointLoad>& p,
                            const std::vector<AxialLineLoad>& q, double v) {
  const int steps = 200000;
  double x = 0.0;
  const double dv = (v - v0) / steps;
  for (int k = 0; k < steps; ++k) {
    const double s = v0 + (k + 0.5) * dv;
    double n = 0.0;
    for (const AxialPointLoad& load : p) {
      if (s > v0 && load.at > s) n += load.force;
      if (s < v0 && load.at < s) n -= load.force;
    }
    for (const AxialLineLoad& load : q) {
      const double f = load.force_per_length * length;
      if (s > v0) n += f * std::max(0.0, load.to - std::max(load.from, s));
      if (s < v0) n -= f * std::max(0.0, std::min(load.to, s) - load.from);
    }
    x += n / ea * dv * length;
  }
  return x;
}

TEST(AxialJob, MatchesIntegratedNormalForceWithLoadsOnBothSides) {
  const std::vector<AxialPointLoad> p = {{0.1, 3.0}, {0.35, -1.0}, {0.62, 2.5}, {0.9, -4.0}};
  const std::vector<AxialLineLoad> q = {{0.2, 0.7, 1.5}, {0.8, 1.0, -2.0}};
  const double length = 1.7, ea = 120.0, v0 = 0.45;
  const std::vector<double> v = {0.0, 0.15, 0.3, 0.45, 0.5, 0.66, 0.85, 1.0};
  const AxialResult r = Solve(length, ea, v0, p, q, v);
  for (std::size_t i = 0; i < v.size(); ++i)
    EXPECT_NEAR(r.x[i], IntegrateNormalForce(length, ea, v0, p, q, v[i]), 1e-6) << "v=" << v[i];
}

TEST(AxialJob, UniformLineLoadFromTheFixedEnd) {
  // f over the whole wire, v0 = 0: X(s) = f (L s - s^2/2) / EA.
  const double length = 2.0, ea = 80.0, f = 3.0;
  const std::vector<double> v = {0.25, 0.5, 1.0};
  const AxialResult r = Solve(length, ea, 0.0, {}, {{0.0, 1.0, f}}, v);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double s = v[i] * length;
    EXPECT_NEAR(r.x[i], f * (length * s - s * s / 2.0) / ea, 1e-14);
  }
}

TEST(AxialJob, PhysicalLengthScalesDisplacement) {
  // EA -> EA / L: doubling L doubles the displacement of the same point loads.
  const std::vector<AxialPointLoad> p = {{0.7, 5.0}};
  const AxialResult a = Solve(1.0, kEA, 0.2, p, {}, {1.0});
  const AxialResult b = Solve(2.0, kEA, 0.2, p, {}, {1.0});
  EXPECT_NEAR(a.x[0], 5.0 * 0.5 / kEA, 1e-15);
  EXPECT_NEAR(b.x[0], 2.0 * a.x[0], 1e-15);
}

TEST(AxialJobDegenerate, LoadAtTheFixedPointGoesIntoTheSupport) {
  const AxialResult r = Solve(1.0, kEA, 0.4, {{0.4, 100.0}}, {}, {0.0, 0.4, 1.0});
  for (double x : r.x) EXPECT_EQ(x, 0.0);
}

// A bar pulled by a force on an end face carries that force through its whole length, the
// loaded face included (its stress there is the traction F / A): N(1) = F fixed at 0, and
// N(0) = -(-F) = F for a push on the face at 0 of a bar fixed at 1; a free end carries nothing.
TEST(AxialJobDegenerate, AnEndFaceLoadIsCarriedAtThatEnd) {
  const AxialResult pulled = Solve(1.0, kEA, 0.0, {{1.0, 7.0}}, {}, {0.0, 0.5, 1.0});
  for (double n : pulled.n) EXPECT_EQ(n, 7.0);
  const AxialResult pushed = Solve(1.0, kEA, 1.0, {{0.0, -3.0}}, {}, {0.0, 0.5, 1.0});
  for (double n : pushed.n) EXPECT_EQ(n, 3.0);
  const AxialResult free = Solve(1.0, kEA, 0.0, {{0.5, 7.0}}, {}, {1.0});
  EXPECT_EQ(free.n[0], 0.0);
}

TEST(AxialJobDegenerate, LoadsOnOneSideNeverMoveTheOther) {
  const AxialResult r = Solve(1.0, kEA, 0.5, {{0.8, 7.0}}, {{0.6, 0.9, 2.0}}, {0.0, 0.2, 0.49});
  for (double x : r.x) EXPECT_EQ(x, 0.0);
}

TEST(AxialJobDegenerate, BeyondTheLastLoadTheWireTranslatesRigidly) {
  const AxialResult r = Solve(1.0, kEA, 0.0, {{0.6, 7.0}}, {}, {0.6, 0.8, 1.0});
  EXPECT_NEAR(r.x[0], 7.0 * 0.6 / kEA, 1e-15);
  EXPECT_EQ(r.x[1], r.x[0]);
  EXPECT_EQ(r.x[2], r.x[0]);
}

class AxialJobValidation : public ::testing::Test {
 protected:
  std::vector<AxialPointLoad> p{{0.5, 1.0}};
  std::vector<AxialLineLoad> q{{0.1, 0.3, 1.0}};
  std::vector<double> v{0.0, 1.0};
  std::vector<double> x = std::vector<double>(2), n = std::vector<double>(2);
  AxialJob job;
  void SetUp() override {
    job.length = 1.0;
    job.axial_stiffness = 1.0;
    job.point_loads = p;
    job.line_loads = q;
    job.samples = v;
    job.displacement = x;
    ASSERT_TRUE(job.Validate().ok());
  }
  void ExpectRefused(std::string_view field, int index = -1, std::string_view member = {}) {
    const Status status = job.Run();
    EXPECT_FALSE(status.ok());
    EXPECT_EQ(status.field, field) << ToString(status);
    EXPECT_EQ(status.index, index) << ToString(status);
    EXPECT_EQ(status.member, member) << ToString(status);
  }
};

TEST_F(AxialJobValidation, EachInvalidInputIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  job.length = -1.0;
  ExpectRefused("length");
  job.length = 1.0;
  job.axial_stiffness = nan;
  ExpectRefused("axial_stiffness");
  job.axial_stiffness = 1.0;
  job.fixed_at = 1.2;
  ExpectRefused("fixed_at");
  job.fixed_at = 0.0;
  p[0].at = nan;
  ExpectRefused("point_loads", 0, "at");
  p[0].at = 0.5;
  p[0].force = std::numeric_limits<double>::infinity();
  ExpectRefused("point_loads", 0, "force");
  p[0].force = 1e200;
  ExpectRefused("loads");
  p[0].force = 1.0;
  q[0].to = 0.05;
  ExpectRefused("line_loads", 0, "to");
  q[0].to = 0.3;
  q[0].force_per_length = nan;
  ExpectRefused("line_loads", 0, "force_per_length");
  q[0].force_per_length = 1.0;
  v[1] = -0.5;
  ExpectRefused("samples", 1);
  v[1] = 1.0;
  job.normal_force = std::span<double>(n).first(1);
  ExpectRefused("normal_force");
  job.normal_force = {};
  job.displacement = {};
  ExpectRefused("displacement");
  job.samples = {};
  ExpectRefused("samples");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
