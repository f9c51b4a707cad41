// WireIkJob: solved loads against textbook beam formulas (independent of the code), landing
// checked by running BendingJob forward with the solved loads, least-norm against influence
// coefficients from the textbook Green's function, the unreachable cases and validation.
#include "wirerig/runtime/wire_ik.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kL = 2.0;    // m
constexpr double kEI = 20.0;  // N m^2

// Displacement at v of the wire under the job's fixed loads plus the solved forces, by
// BendingJob run forward.
Vec3 Forward(const WireIkJob& ik, std::span<const Vec3> forces) {
  BendingJob wire;
  wire.boundary = ik.boundary;
  wire.length = ik.length;
  wire.bending_stiffness = ik.bending_stiffness;
  wire.start_displacement = ik.start_displacement;
  wire.end_displacement = ik.end_displacement;
  wire.tip_force = ik.fixed_tip_force;
  std::vector<PointLoad> points(ik.fixed_point_loads.begin(), ik.fixed_point_loads.end());
  if (ik.basis == WireIkBasis::kTipForce)
    wire.tip_force += forces[0];
  else
    for (std::size_t i = 0; i < forces.size(); ++i) points.push_back({ik.load_at[i], forces[i]});
  wire.point_loads = points;
  wire.line_loads = ik.fixed_line_loads;
  const double v = ik.target_at;
  Vec3 x = Vec3::Zero();
  wire.samples = std::span<const double>(&v, 1);
  wire.displacement = std::span<Vec3>(&x, 1);
  EXPECT_TRUE(wire.Run().ok());
  return x;
}

// Textbook simply supported beam (length L, load F at distance a from the left support),
// deflection at x: F b x (L^2 - b^2 - x^2) / (6 L EI) for x <= a, b = L - a; mirrored for x > a.
double SimplySupportedInfluence(double x, double a) {
  if (x > a) return SimplySupportedInfluence(kL - x, kL - a);
  const double b = kL - a;
  return b * x * (kL * kL - b * b - x * x) / (6.0 * kL * kEI);
}

WireIkJob Cantilever(std::span<Vec3> forces, WireIkResult* result) {
  WireIkJob ik;
  ik.boundary = BoundaryCondition::kCantileverFree;
  ik.length = kL;
  ik.bending_stiffness = kEI;
  ik.forces = forces;
  ik.result = result;
  return ik;
}

TEST(WireIkJob, CantileverTipForceIsFL3Over3EI) {
  std::array<Vec3, 1> force;
  WireIkResult result;
  WireIkJob ik = Cantilever(force, &result);
  ik.target = Vec3(0.0, -0.05, 0.03);
  ASSERT_TRUE(ik.Run().ok());
  const Vec3 expected = 3.0 * kEI / (kL * kL * kL) * ik.target;
  EXPECT_LT((force[0] - expected).norm(), 1e-12 * expected.norm());
  EXPECT_TRUE(result.reached_target);
  EXPECT_FALSE(result.axial_component || result.pinned || result.force_limited);
  EXPECT_LT(result.miss, 1e-9 * kL);
  EXPECT_LT((Forward(ik, force) - ik.target).norm(), 1e-9 * kL);
}

TEST(WireIkJob, CantileverInnerPointAndGuidedTip) {
  // Tip force placing the point x = 0.6 L: delta = F x^2 (3L - x) / 6EI.
  std::array<Vec3, 1> force;
  WireIkResult result;
  WireIkJob ik = Cantilever(force, &result);
  ik.target_at = 0.6;
  ik.target = Vec3(0.0, 0.02, 0.0);
  ASSERT_TRUE(ik.Run().ok());
  const double x = 0.6 * kL;
  EXPECT_NEAR(force[0].y(), 6.0 * kEI * 0.02 / (x * x * (3.0 * kL - x)), 1e-12);
  EXPECT_LT((Forward(ik, force) - ik.target).norm(), 1e-9 * kL);
  // Guided tip: delta = F L^3 / 12EI.
  ik.boundary = BoundaryCondition::kCantileverGuided;
  ik.target_at = 1.0;
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_NEAR(force[0].y(), 12.0 * kEI * 0.02 / (kL * kL * kL), 1e-12);
  EXPECT_TRUE(result.reached_target);
  EXPECT_LT((Forward(ik, force) - ik.target).norm(), 1e-9 * kL);
}

TEST(WireIkJob, SimplySupportedPointLoadMatchesTextbook) {
  std::array<Vec3, 1> force;
  const std::array<double, 1> at = {0.5};
  WireIkResult result;
  WireIkJob ik;
  ik.boundary = BoundaryCondition::kSimplySupported;
  ik.length = kL;
  ik.bending_stiffness = kEI;
  ik.basis = WireIkBasis::kPointLoads;
  ik.load_at = at;
  ik.forces = force;
  ik.result = &result;
  ik.target_at = 0.3;
  ik.target = Vec3(0.0, 0.0, -0.01);
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_NEAR(force[0].z(), -0.01 / SimplySupportedInfluence(0.3 * kL, 0.5 * kL), 1e-10);
  EXPECT_TRUE(result.reached_target);
  EXPECT_LT((Forward(ik, force) - ik.target).norm(), 1e-9 * kL);
}

TEST(WireIkJob, SeveralLoadsAreLeastNorm) {
  // Three loads, one target: the least-norm forces are proportional to the influence
  // coefficients g_i (textbook), F_i = g_i d / sum g^2.
  std::array<Vec3, 3> forces;
  const std::array<double, 3> at = {0.25, 0.5, 0.8};
  WireIkResult result;
  WireIkJob ik;
  ik.boundary = BoundaryCondition::kSimplySupported;
  ik.length = kL;
  ik.bending_stiffness = kEI;
  ik.basis = WireIkBasis::kPointLoads;
  ik.load_at = at;
  ik.forces = forces;
  ik.result = &result;
  ik.target_at = 0.4;
  ik.target = Vec3(0.0, 0.015, 0.004);
  ASSERT_TRUE(ik.Run().ok());
  std::array<double, 3> g{};
  double g2 = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    g[i] = SimplySupportedInfluence(0.4 * kL, at[i] * kL);
    g2 += g[i] * g[i];
  }
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_LT((forces[i] - g[i] / g2 * ik.target).norm(), 1e-9 * forces[i].norm()) << i;
  EXPECT_LT((Forward(ik, forces) - ik.target).norm(), 1e-9 * kL);
  // Any other solution (here: adding a null-space direction) has a larger norm.
  const Vec3 null_dir = Vec3(0.0, 1.0, 0.0);
  std::array<Vec3, 3> other = forces;
  other[0] += g[1] * null_dir;
  other[1] -= g[0] * null_dir;
  EXPECT_LT((Forward(ik, other) - ik.target).norm(), 1e-9 * kL);
  double n_solved = 0.0, n_other = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    n_solved += forces[i].squaredNorm();
    n_other += other[i].squaredNorm();
  }
  EXPECT_LT(n_solved, n_other);
}

TEST(WireIkJob, FixedLoadsAreCompensated) {
  // Gravity q on a cantilever droops the tip by q L^4 / 8EI; holding it level takes an upward
  // tip force with F L^3 / 3EI = q L^4 / 8EI, F = 3 q L / 8.
  const double q = 4.0;
  const std::array<LineLoad, 1> gravity = {LineLoad{0.0, 1.0, Vec3(0.0, -q, 0.0)}};
  std::array<Vec3, 1> force;
  WireIkResult result;
  WireIkJob ik = Cantilever(force, &result);
  ik.fixed_line_loads = gravity;
  ik.start_displacement = Vec3(0.0, 0.1, 0.0);
  ik.target = Vec3(0.0, 0.1, 0.0);  // level with the root
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_NEAR(force[0].y(), 3.0 * q * kL / 8.0, 1e-12);
  EXPECT_TRUE(result.reached_target);
  EXPECT_LT((Forward(ik, force) - ik.target).norm(), 1e-9 * kL);
}

TEST(WireIkJob, AxialComponentIsDroppedAndFlagged) {
  std::array<Vec3, 1> force;
  WireIkResult result;
  WireIkJob ik = Cantilever(force, &result);
  ik.target = Vec3(0.01, 0.02, 0.0);
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_TRUE(result.axial_component);
  EXPECT_FALSE(result.reached_target);
  EXPECT_EQ(force[0].x(), 0.0);
  EXPECT_LT((result.reached - Vec3(0.0, 0.02, 0.0)).norm(), 1e-12);
  EXPECT_NEAR(result.miss, 0.01, 1e-12);
  // A wire along Y: the Y component is axial, X and Z are lateral.
  ik.axis = Vec3::UnitY();
  ik.target = Vec3(0.02, 0.3, -0.01);
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_TRUE(result.axial_component);
  EXPECT_EQ(force[0].y(), 0.0);
  EXPECT_LT((result.reached - Vec3(0.02, 0.0, -0.01)).norm(), 1e-12);
  EXPECT_LT((Forward(ik, force) - result.reached).norm(), 1e-9 * kL);
}

TEST(WireIkJob, PinnedPointsAreFlagged) {
  std::array<Vec3, 1> force;
  const std::array<double, 1> at_middle = {0.5}, at_support = {1.0};
  WireIkResult result;
  WireIkJob ik;
  ik.boundary = BoundaryCondition::kSimplySupported;
  ik.length = kL;
  ik.bending_stiffness = kEI;
  ik.basis = WireIkBasis::kPointLoads;
  ik.load_at = at_middle;
  ik.forces = force;
  ik.result = &result;
  ik.start_displacement = Vec3(0.0, 0.05, 0.0);
  // The point at the support: it stays at X0 whatever the load.
  ik.target_at = 0.0;
  ik.target = Vec3(0.0, 0.2, 0.0);
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_TRUE(result.pinned);
  EXPECT_FALSE(result.reached_target);
  EXPECT_EQ(force[0], Vec3::Zero());
  EXPECT_LT((result.reached - ik.start_displacement).norm(), 1e-15);
  // A load placed on a support moves nothing.
  ik.target_at = 0.5;
  ik.load_at = at_support;
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_TRUE(result.pinned);
  EXPECT_EQ(force[0], Vec3::Zero());
  // A cantilever's root.
  WireIkJob c = Cantilever(force, &result);
  c.target_at = 0.0;
  c.target = Vec3(0.0, 0.01, 0.0);
  ASSERT_TRUE(c.Run().ok());
  EXPECT_TRUE(result.pinned);
  // Already there: nothing to do, reached.
  c.target = Vec3::Zero();
  ASSERT_TRUE(c.Run().ok());
  EXPECT_TRUE(result.reached_target);
  EXPECT_FALSE(result.pinned);
}

TEST(WireIkJob, ForceLimitGivesTheClosestPoint) {
  std::array<Vec3, 1> force;
  WireIkResult result;
  WireIkJob ik = Cantilever(force, &result);
  ik.target = Vec3(0.0, 0.3, 0.4);  // needs |F| = 3 EI 0.5 / L^3 = 3.75 N
  ik.max_force = 1.5;
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_TRUE(result.force_limited);
  EXPECT_FALSE(result.reached_target);
  EXPECT_NEAR(force[0].norm(), 1.5, 1e-12);
  // The reachable set is the disc of radius 1.5 L^3 / 3EI = 0.2 m: the closest point is on the
  // way to the target.
  EXPECT_LT((result.reached - 0.2 * ik.target.normalized()).norm(), 1e-12);
  EXPECT_NEAR(result.miss, 0.3, 1e-12);
  EXPECT_LT((Forward(ik, force) - result.reached).norm(), 1e-12);
}

TEST(WireIkJob, ValidateNamesTheFirstBadField) {
  std::array<Vec3, 1> one;
  std::array<Vec3, 2> two;
  const std::array<double, 1> at = {0.5};
  const std::array<double, 1> bad_at = {-0.1};
  const std::array<double, 9> many_at{};
  const std::array<PointLoad, 1> bad_point = {PointLoad{2.0, Vec3::UnitY()}};
  const std::array<LineLoad, 1> bad_line = {LineLoad{0.5, 0.5, Vec3::UnitY()}};
  WireIkResult result;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto base = [&] { return Cantilever(one, &result); };
  ASSERT_TRUE(base().Validate().ok());
  struct Case {
    const char* field;
    std::function<void(WireIkJob&)> edit;
  };
  const std::vector<Case> cases = {
      {"length", [](auto& j) { j.length = 0.0; }},
      {"bending_stiffness", [](auto& j) { j.bending_stiffness = -2.0; }},
      {"boundary", [](auto& j) { j.boundary = static_cast<BoundaryCondition>(9); }},
      {"start_displacement", [&](auto& j) { j.start_displacement.x() = nan; }},
      {"fixed_tip_force", [&](auto& j) { j.fixed_tip_force.y() = nan; }},
      {"fixed_tip_force",
       [](auto& j) {
         j.boundary = BoundaryCondition::kClamped, j.fixed_tip_force = Vec3::UnitY();
       }},
      {"fixed_point_loads", [&](auto& j) { j.fixed_point_loads = bad_point; }},
      {"fixed_line_loads", [&](auto& j) { j.fixed_line_loads = bad_line; }},
      {"axis", [](auto& j) { j.axis = Vec3::Zero(); }},
      {"target_at", [](auto& j) { j.target_at = 1.5; }},
      {"target", [&](auto& j) { j.target.z() = nan; }},
      {"basis", [](auto& j) { j.boundary = BoundaryCondition::kSimplySupported; }},
      {"basis", [](auto& j) { j.basis = static_cast<WireIkBasis>(7); }},
      {"forces", [&](auto& j) { j.forces = two; }},
      {"load_at", [](auto& j) { j.basis = WireIkBasis::kPointLoads; }},
      {"load_at", [&](auto& j) { j.basis = WireIkBasis::kPointLoads, j.load_at = bad_at; }},
      {"load_at", [&](auto& j) { j.basis = WireIkBasis::kPointLoads, j.load_at = many_at; }},
      {"forces",
       [&](auto& j) { j.basis = WireIkBasis::kPointLoads, j.load_at = at, j.forces = two; }},
      {"max_force", [](auto& j) { j.max_force = 0.0; }},
      {"max_force", [&](auto& j) { j.max_force = nan; }},
      {"result", [](auto& j) { j.result = nullptr; }},
  };
  for (const Case& c : cases) {
    WireIkJob job = base();
    c.edit(job);
    const Status status = job.Validate();
    EXPECT_EQ(status.field, c.field) << ToString(status);
    EXPECT_EQ(job.Run().field, c.field);
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
