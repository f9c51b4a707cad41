// CorotationalWireIkJob: reachable targets met to 1e-9 L (checked by running the chain forward
// with the solved force, and by the RK4 elastica under that force to the chain's discretisation
// error), the linear limit, unreachable targets (closest point, local optimality) and
// validation.
#include "wirerig/runtime/corotational_wire_ik.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include "support/elastica_reference.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kPi = std::numbers::pi;
constexpr double kL = 1.2;   // m
constexpr double kEI = 3.0;  // N m^2
constexpr double kMaxForce = 25.0 * kEI / (kL * kL);

CorotationalWireIkJob Ik(Vec3 target, CorotationalWireIkResult* result, int segments = 32) {
  CorotationalWireIkJob ik;
  ik.wire.length = kL;
  ik.wire.bending_stiffness = kEI;
  ik.wire.segments = segments;
  ik.target = target;
  ik.max_force = kMaxForce;
  ik.result = result;
  return ik;
}

// The chain's tip under a dead tip force, run forward.
Vec3 ChainTip(Vec3 force, int segments = 32) {
  CorotationalWireJob wire;
  wire.length = kL;
  wire.bending_stiffness = kEI;
  wire.segments = segments;
  wire.tip_force = force;
  CorotationalWireResult r;
  wire.result = &r;
  EXPECT_TRUE(wire.Run().ok());
  return r.tip_position;
}

TEST(CorotationalWireIkJob, ReachableTargetsAreMetToTheTolerance) {
  // Targets that a dead tip force reaches on the exact elastica (elliptic-integral closed form,
  // independent of the chain): the IK meets each to 1e-9 L on the chain, and its force is the
  // elastica's to within the chain's discretisation error. From a 30-degree bend to curls of
  // 120 degrees, forces pulling forwards, sideways and backwards, up and down.
  struct Case {
    double beta, rotation_degrees, mirror;
  };
  const std::vector<Case> cases = {{kPi / 2, 30, 1},  {kPi / 2, 60, 1},      {kPi / 2, 80, 1},
                                   {kPi / 4, 40, 1},  {3 * kPi / 4, 90, 1},  {3 * kPi / 4, 120, 1},
                                   {kPi / 2, 60, -1}, {3 * kPi / 4, 120, -1}};
  for (const Case& c : cases) {
    const testing::ElasticaTip exact =
        testing::ExactElasticaTip(c.beta, c.rotation_degrees * kPi / 180.0);
    const Vec3 target(exact.x * kL, c.mirror * exact.y * kL, 0.0);
    const Vec3 force =
        exact.alpha * kEI / (kL * kL) * Vec3(std::cos(c.beta), c.mirror * std::sin(c.beta), 0.0);
    SCOPED_TRACE(::testing::Message() << "target / L " << target.transpose() / kL);
    CorotationalWireIkResult result;
    CorotationalWireIkJob ik = Ik(target, &result);
    const Status status = ik.Run();
    ASSERT_TRUE(status.ok()) << ToString(status);
    std::printf(
        "target/L (%6.3f, %6.3f) tip rotation %4.0f deg: miss/L %.1e, force error %.1e "
        "of |F| = %.2f EI/L^2, %d iterations, %d chain solves\n",
        target.x() / kL, target.y() / kL, c.mirror * c.rotation_degrees, result.miss / kL,
        (result.tip_force - force).norm() / force.norm(), exact.alpha, result.iterations,
        result.chain_solves);
    EXPECT_TRUE(result.reached_target);
    EXPECT_FALSE(result.force_limited || result.beyond_length);
    EXPECT_LT(result.miss, 1e-9 * kL);
    // Forward: the chain under the solved force puts its tip on the target.
    EXPECT_LT((ChainTip(result.tip_force) - target).norm(), 1e-9 * kL);
    // The elastica's force, to the chain's discretisation error (K = 32).
    EXPECT_LT((result.tip_force - force).norm(), 0.02 * force.norm());
  }
}

TEST(CorotationalWireIkJob, FixedLoadsStayApplied) {
  // A drooping tentacle (gravity q L^3 / EI = 3, a dead point load) reaching up: round trip
  // through the chain. The target is the tip under a known force; the IK, starting from the
  // linear guess, recovers that force (the natural equilibrium is unique here) to 1e-6.
  const std::array<LineLoad, 1> gravity = {
      LineLoad{0.0, 1.0, Vec3(0.0, -3.0 * kEI / (kL * kL * kL), 0.0)}};
  const std::array<PointLoad, 1> weight = {PointLoad{0.6, Vec3(0.0, -0.5, 0.0)}};
  const Vec3 known = Vec3(1.5, 6.0, 0.0) * (kEI / (kL * kL));
  CorotationalWireJob forward;
  forward.length = kL;
  forward.bending_stiffness = kEI;
  forward.segments = 32;
  forward.line_loads = gravity;
  forward.point_loads = weight;
  forward.tip_force = known;
  CorotationalWireResult r;
  forward.result = &r;
  ASSERT_TRUE(forward.Run().ok());
  ASSERT_GT(r.tip_rotation, 0.5);  // a real curl, against gravity
  CorotationalWireIkResult result;
  CorotationalWireIkJob ik = Ik(r.tip_position, &result);
  ik.wire.line_loads = gravity;
  ik.wire.point_loads = weight;
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_TRUE(result.reached_target);
  EXPECT_LT(result.miss, 1e-9 * kL);
  EXPECT_LT((result.tip_force - known).norm(), 1e-6 * known.norm());
}

TEST(CorotationalWireIkJob, SmallOffsetsNeedTheLinearForce) {
  // delta = F L^3 / 3EI for a small lateral offset of the tip (its axial shortening is
  // second order and included in the target).
  const double delta = 1e-4 * kL;
  const double f = 3.0 * kEI * delta / (kL * kL * kL);
  const Vec3 target = ChainTip(Vec3(0.0, f, 0.0));
  CorotationalWireIkResult result;
  CorotationalWireIkJob ik = Ik(target, &result);
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_TRUE(result.reached_target);
  EXPECT_NEAR(result.tip_force.y(), f, 1e-6 * f);
  EXPECT_NEAR(result.tip_force.x(), 0.0, 1e-6 * f);
}

TEST(CorotationalWireIkJob, TargetsBeyondTheLengthGiveTheClosestPoint) {
  const std::array<Vec3, 2> targets = {Vec3(1.2 * kL, 0.6 * kL, 0.0), Vec3(0.0, 1.5 * kL, 0.0)};
  for (const Vec3& target : targets) {
    SCOPED_TRACE(::testing::Message() << "target / L " << target.transpose() / kL);
    CorotationalWireIkResult result;
    CorotationalWireIkJob ik = Ik(target, &result);
    ASSERT_TRUE(ik.Run().ok());
    std::printf("unreachable target/L (%4.2f, %4.2f): closest (%6.4f, %6.4f), miss/L %.4f\n",
                target.x() / kL, target.y() / kL, result.reached.x() / kL, result.reached.y() / kL,
                result.miss / kL);
    EXPECT_FALSE(result.reached_target);
    EXPECT_TRUE(result.beyond_length);
    EXPECT_TRUE(result.force_limited);
    EXPECT_NEAR(result.tip_force.norm(), kMaxForce, 1e-9 * kMaxForce);
    EXPECT_LT(result.reached.norm(), kL);
    EXPECT_GE(result.miss, target.norm() - kL);
    // Closest: no nearby admissible force does better (on the bound's circle, or inside it).
    const double psi = std::atan2(result.tip_force.y(), result.tip_force.x());
    for (double dpsi : {-1e-3, 1e-3}) {
      const Vec3 f = kMaxForce * Vec3(std::cos(psi + dpsi), std::sin(psi + dpsi), 0.0);
      EXPECT_GE((ChainTip(f) - target).norm(), result.miss - 1e-12 * kL) << dpsi;
    }
    EXPECT_GE((ChainTip(0.99 * result.tip_force) - target).norm(), result.miss);
  }
}

TEST(CorotationalWireIkJob, ShapesNoTipForceMakesGiveTheClosestPointFound) {
  // Inside the disc but too short for its height: a tip force bends the wire into shapes whose
  // shortening grows with their deflection (x ~ L - c y^2 / L); reaching (0.95, 0.2) L would take
  // an equilibrium off the natural branch. The search stops at the closest point it finds.
  CorotationalWireIkResult result;
  CorotationalWireIkJob ik = Ik(Vec3(0.95, 0.2, 0.0) * kL, &result);
  ASSERT_TRUE(ik.Run().ok());
  std::printf(
      "target/L (0.95, 0.20), not made by a tip force: closest (%6.4f, %6.4f), miss/L "
      "%.4f, |F| L^2/EI %.2f\n",
      result.reached.x() / kL, result.reached.y() / kL, result.miss / kL,
      result.tip_force.norm() * kL * kL / kEI);
  EXPECT_FALSE(result.reached_target);
  EXPECT_FALSE(result.beyond_length);
  EXPECT_GT(result.miss, 1e-3 * kL);
  EXPECT_LT(result.miss, 0.1 * kL);
  EXPECT_LT((ChainTip(result.tip_force) - result.reached).norm(), 1e-12 * kL);
}

TEST(CorotationalWireIkJob, SamplesReceiveTheSolvedShape) {
  std::vector<double> v = {0.0, 0.5, 1.0};
  std::vector<Vec3> p(v.size()), t(v.size());
  CorotationalWireIkResult result;
  // A 70-degree curl of the exact elastica; K automatic (from max_force).
  const testing::ElasticaTip exact = testing::ExactElasticaTip(kPi / 2, 70.0 * kPi / 180.0);
  CorotationalWireIkJob ik = Ik(Vec3(exact.x, exact.y, 0.0) * kL, &result, 0);
  ik.wire.samples = v;
  ik.wire.position = p;
  ik.wire.tangent = t;
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_TRUE(result.reached_target);
  EXPECT_LT((p.back() - ik.target).norm(), 1e-9 * kL);
  EXPECT_LT(p.front().norm(), 1e-15);
}

TEST(CorotationalWireIkJob, ValidateNamesTheFirstBadField) {
  CorotationalWireIkResult result;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto base = [&] { return Ik(Vec3(0.5, 0.5, 0.0), &result); };
  ASSERT_TRUE(base().Validate().ok());
  struct Case {
    const char* field;
    std::function<void(CorotationalWireIkJob&)> edit;
  };
  const std::vector<Case> cases = {
      {"length", [](auto& j) { j.wire.length = -1.0; }},
      {"boundary", [](auto& j) { j.wire.boundary = BoundaryCondition::kClamped; }},
      {"max_force", [](auto& j) { j.max_force = 0.0; }},
      {"max_force", [&](auto& j) { j.max_force = nan; }},
      {"max_force", [](auto& j) { j.max_force = 1e6; }},  // too much for 32 segments
      {"target", [](auto& j) { j.target = Vec3(0.1, 0.2, 0.3); }},
      {"target", [&](auto& j) { j.target.x() = nan; }},
      {"tolerance", [](auto& j) { j.tolerance = 0.0; }},
      {"tolerance", [](auto& j) { j.tolerance = 0.1; }},
      {"tolerance", [&](auto& j) { j.tolerance = nan; }},
      {"max_iterations", [](auto& j) { j.max_iterations = 0; }},
      {"result", [](auto& j) { j.result = nullptr; }},
  };
  for (const Case& c : cases) {
    CorotationalWireIkJob job = base();
    c.edit(job);
    const Status status = job.Validate();
    EXPECT_EQ(status.field, c.field) << ToString(status);
    EXPECT_EQ(job.Run().field, c.field);
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
