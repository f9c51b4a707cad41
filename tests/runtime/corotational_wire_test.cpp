// CorotationalWireJob against independent references: the exact elastica of a cantilever under a
// dead tip force (elliptic integrals, itself checked against an RK4 shooting solve of the
// elastica ODE), the exact circle of a tip moment, an RK4 shooting solve under a dead line load,
// the antisymmetric guided cantilever, and BendingJob (linear theory) for tiny loads.
#include "wirerig/runtime/corotational_wire.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "support/elastica_reference.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using testing::ExactElasticaTip;
using testing::ShootTipForceElastica;

constexpr double kPi = std::numbers::pi;
constexpr double kL = 1.5;   // m
constexpr double kEI = 4.0;  // N m^2

double Deg(double degrees) { return degrees * kPi / 180.0; }

// Runs a chain with a dead tip force; returns the result (asserts success).
CorotationalWireResult RunTipForce(Vec3 force, int segments,
                                   BoundaryCondition bc = BoundaryCondition::kCantileverFree) {
  CorotationalWireJob job;
  job.boundary = bc;
  job.length = kL;
  job.bending_stiffness = kEI;
  job.segments = segments;
  job.tip_force = force;
  CorotationalWireResult result;
  job.result = &result;
  const Status status = job.Run();
  EXPECT_TRUE(status.ok()) << ToString(status);
  return result;
}

// Tip error of the chain against the exact elastica, in units of L; -1 if Validate() refuses
// the segment count for this load.
double TipError(double beta, double tip_rotation, int segments) {
  const testing::ElasticaTip exact = ExactElasticaTip(beta, tip_rotation);
  const double f = exact.alpha * kEI / (kL * kL);
  CorotationalWireJob job;
  job.length = kL;
  job.bending_stiffness = kEI;
  job.segments = segments;
  job.tip_force = f * Vec3(std::cos(beta), std::sin(beta), 0.0);
  if (job.Validate().field == "segments") return -1.0;
  const CorotationalWireResult r = RunTipForce(job.tip_force, segments);
  return std::hypot(r.tip_position.x() / kL - exact.x, r.tip_position.y() / kL - exact.y);
}

TEST(ElasticaReference, ClosedFormMatchesRk4Shooting) {
  // The reference itself, checked by a different method: the elliptic-integral closed form
  // against an RK4 shooting solve of EI theta'' = -F sin(beta - theta).
  // Forces perpendicular to the root and pointing back at 135 degrees (dead), and the follower
  // force's equivalent beta = theta_L + 90 degrees.
  struct Case {
    double beta, degrees;
  };
  std::vector<Case> cases;
  for (double degrees : {10.0, 30.0, 60.0, 80.0, 89.0}) cases.push_back({kPi / 2, degrees});
  for (double degrees : {30.0, 60.0, 90.0, 120.0}) cases.push_back({3 * kPi / 4, degrees});
  for (double degrees : {30.0, 60.0, 120.0, 170.0})
    cases.push_back({Deg(degrees) + kPi / 2, degrees});
  for (const Case& c : cases) {
    {
      const double beta = c.beta, degrees = c.degrees;
      SCOPED_TRACE(::testing::Message() << "beta " << beta << " tip rotation " << degrees);
      const testing::ElasticaTip exact = ExactElasticaTip(beta, Deg(degrees));
      const double f = exact.alpha * kEI / (kL * kL);
      // Bracket: +-10% around the closed form's root curvature (the moment of the tip force
      // about the root, (r_L x F) / EI), which selects the natural branch; the root itself is
      // found by the shooting alone.
      const double kappa0 = f * kL * (exact.x * std::sin(beta) - exact.y * std::cos(beta)) / kEI;
      const testing::ElasticaState shot =
          ShootTipForceElastica(kL, kEI, f, beta, std::min(0.9 * kappa0, 1.1 * kappa0),
                                std::max(0.9 * kappa0, 1.1 * kappa0));
      EXPECT_NEAR(shot.theta, Deg(degrees), 1e-8);
      EXPECT_NEAR(shot.x / kL, exact.x, 1e-8);
      EXPECT_NEAR(shot.y / kL, exact.y, 1e-8);
    }
  }
  // Small loads: the linear tip deflection alpha / 3 and rotation alpha / 2 (perpendicular).
  const testing::ElasticaTip small = ExactElasticaTip(kPi / 2, 1e-4);
  EXPECT_NEAR(small.alpha / 2, 1e-4, 1e-9);
  EXPECT_NEAR(small.y, small.alpha / 3, 1e-9);
}

// The errors of the chain's tip (fraction of L) by tip rotation and K, printed as a table.
TEST(CorotationalWireJob, TipForceConvergesToTheExactElastica) {
  const std::array<int, 6> ks = {4, 8, 16, 32, 64, 128};
  std::printf("tip error / L vs exact elastica, perpendicular dead tip force\n");
  std::printf("rotation  alpha     K=4       K=8       K=16      K=32      K=64      K=128\n");
  for (double degrees : {10.0, 30.0, 60.0, 80.0, 85.0, 89.0}) {
    SCOPED_TRACE(::testing::Message() << "tip rotation " << degrees);
    std::array<double, 6> err{};
    for (std::size_t i = 0; i < ks.size(); ++i) err[i] = TipError(kPi / 2, Deg(degrees), ks[i]);
    std::printf("%5.0f deg %7.3f", degrees, ExactElasticaTip(kPi / 2, Deg(degrees)).alpha);
    for (double e : err)
      if (e < 0.0)
        std::printf("  refused ");
      else
        std::printf("  %.2e", e);
    std::printf("\n");
    // Second order: doubling K divides the error by about 4 once K is past the first turns.
    for (std::size_t i = 2; i + 1 < ks.size(); ++i)
      if (err[i] > 0.0) {
        EXPECT_LT(err[i + 1], 0.35 * err[i]);
      }
    EXPECT_LT(err[5], 1e-3);
  }
}

TEST(CorotationalWireJob, NinetyDegreesUnderAnInclinedForce) {
  // A perpendicular force reaches 90 degrees only as F -> infinity; a force pointing back at
  // 135 degrees turns the tip by 90 (and 120) degrees at a finite load.
  std::printf("tip error / L vs exact elastica, dead tip force at 135 degrees\n");
  for (double degrees : {90.0, 120.0}) {
    SCOPED_TRACE(::testing::Message() << "tip rotation " << degrees);
    std::printf("%5.0f deg alpha %.3f:", degrees,
                ExactElasticaTip(3 * kPi / 4, Deg(degrees)).alpha);
    double previous = 1.0;
    for (int k : {16, 32, 64, 128}) {
      const double e = TipError(3 * kPi / 4, Deg(degrees), k);
      std::printf("  K=%d %.2e", k, e);
      EXPECT_LT(e, 0.35 * previous);
      previous = e;
    }
    std::printf("\n");
  }
}

TEST(CorotationalWireJob, DefaultSegmentsStayWithinATenthOfAPercentOfL) {
  // segments = 0: K from the loads, each segment turning at most about 0.1 rad.
  struct Case {
    double beta, degrees;
  };
  for (const Case& c :
       {Case{kPi / 2, 10.0}, Case{kPi / 2, 30.0}, Case{kPi / 2, 60.0}, Case{kPi / 2, 80.0},
        Case{kPi / 2, 89.0}, Case{3 * kPi / 4, 90.0}, Case{3 * kPi / 4, 120.0}}) {
    SCOPED_TRACE(::testing::Message() << "tip rotation " << c.degrees);
    const testing::ElasticaTip exact = ExactElasticaTip(c.beta, Deg(c.degrees));
    CorotationalWireJob job;
    job.length = kL;
    job.bending_stiffness = kEI;
    job.tip_force = exact.alpha * kEI / (kL * kL) * Vec3(std::cos(c.beta), std::sin(c.beta), 0.0);
    const double error = TipError(c.beta, Deg(c.degrees), 0);
    std::printf(
        "default K: force at %3.0f deg, tip rotation %3.0f deg: K = %d, tip error / L %.2e\n",
        c.beta * 180 / kPi, c.degrees, AutomaticSegmentCount(job), error);
    EXPECT_LT(error, 1e-3);
    EXPECT_GE(error, 0.0);
  }
}

TEST(CorotationalWireJob, FollowerForceMatchesTheElastica) {
  // A tip force that stays perpendicular to the tip's tangent is, in equilibrium, the dead force
  // at beta = theta_L + 90 degrees: the exact elastica with phi_L = 90 degrees.
  for (double degrees : {30.0, 60.0, 120.0, 170.0}) {
    SCOPED_TRACE(::testing::Message() << "tip rotation " << degrees);
    const double theta_l = Deg(degrees);
    const testing::ElasticaTip exact = ExactElasticaTip(theta_l + kPi / 2, theta_l);
    std::printf("follower force, tip rotation %3.0f deg (F L^2/EI %.3f): tip error / L", degrees,
                exact.alpha);
    double previous = 1.0;
    for (int k : {32, 64, 128}) {
      CorotationalWireJob job;
      job.length = kL;
      job.bending_stiffness = kEI;
      job.segments = k;
      job.tip_force = Vec3(0.0, exact.alpha * kEI / (kL * kL), 0.0);  // in the tip's frame
      job.tip_force_follows = true;
      CorotationalWireResult r;
      job.result = &r;
      const Status status = job.Run();
      ASSERT_TRUE(status.ok()) << ToString(status);
      const double e =
          std::hypot(r.tip_position.x() / kL - exact.x, r.tip_position.y() / kL - exact.y);
      std::printf("  K=%d %.2e", k, e);
      EXPECT_NEAR(r.tip_rotation, theta_l, 2e-3);
      EXPECT_LT(e, 0.35 * previous);
      previous = e;
    }
    std::printf("\n");
    EXPECT_LT(previous, 1e-4);
  }
  // A guided tip does not turn: its follower force is the dead force.
  const Vec3 f(0.0, 3.0 * kEI / (kL * kL), 0.0);
  const CorotationalWireResult dead = RunTipForce(f, 32, BoundaryCondition::kCantileverGuided);
  CorotationalWireJob job;
  job.boundary = BoundaryCondition::kCantileverGuided;
  job.length = kL;
  job.bending_stiffness = kEI;
  job.segments = 32;
  job.tip_force = f;
  job.tip_force_follows = true;
  CorotationalWireResult follower;
  job.result = &follower;
  ASSERT_TRUE(job.Run().ok());
  EXPECT_EQ(follower.tip_position, dead.tip_position);
}

TEST(CorotationalWireJob, TipRotationMatchesTheElastica) {
  const testing::ElasticaTip exact = ExactElasticaTip(kPi / 2, Deg(60.0));
  const CorotationalWireResult r = RunTipForce(Vec3(0.0, exact.alpha * kEI / (kL * kL), 0.0), 128);
  EXPECT_NEAR(r.tip_rotation, Deg(60.0), 1e-3);
  EXPECT_NEAR(r.tip_tangent.norm(), 1.0, 1e-15);
  EXPECT_EQ(r.segments, 128);
}

TEST(CorotationalWireJob, TipMomentCurlsIntoACircle) {
  // A tip couple M bends the wire into a circle of radius EI / M: a full turn for M L / EI = 2 pi.
  for (double turns : {0.5, 1.0}) {
    const double m = turns * 2.0 * kPi * kEI / kL;
    const double radius = kEI / m;
    std::vector<double> v = {0.0, 0.1, 0.37, 0.5, 0.8, 1.0};
    std::vector<Vec3> p(v.size()), t(v.size());
    CorotationalWireJob job;
    job.length = kL;
    job.bending_stiffness = kEI;
    job.segments = 64;
    job.tip_moment = m;
    job.samples = v;
    job.position = p;
    job.tangent = t;
    ASSERT_TRUE(job.Run().ok());
    for (std::size_t i = 0; i < v.size(); ++i) {
      const double angle = m * kL * v[i] / kEI;
      EXPECT_NEAR(p[i].x(), radius * std::sin(angle), 1e-3 * kL) << v[i];
      EXPECT_NEAR(p[i].y(), radius * (1.0 - std::cos(angle)), 1e-3 * kL) << v[i];
      EXPECT_NEAR(std::remainder(std::atan2(t[i].y(), t[i].x()) - angle, 2 * kPi), 0.0, 1e-9)
          << v[i];
    }
  }
}

TEST(CorotationalWireJob, TaperedWireCurlsIntoASpiral) {
  // EI(s) = EI0 r^(s/L) under a tip couple M: curvature M/EI0 e^(c s), c = -ln(r)/L, so the
  // tangent turns by theta(s) = M (e^(c s) - 1) / (EI0 c), a spiral (here 1.5 turns); positions
  // by Simpson's rule on (cos theta, sin theta) with 20000 intervals.
  const double r = 0.1, c = -std::log(r) / kL;
  const double m = 3.0 * kPi * kEI * c / (std::exp(c * kL) - 1.0);
  auto theta = [&](double s) { return m * (std::exp(c * s) - 1.0) / (kEI * c); };
  auto exact = [&](double s_end) {
    const int n = 20000;
    const double h = s_end / n;
    Vec3 p = Vec3::Zero();
    for (int i = 0; i <= n; ++i) {
      const double w = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      p += w * h / 3.0 * Vec3(std::cos(theta(i * h)), std::sin(theta(i * h)), 0.0);
    }
    return p;
  };
  std::vector<double> v = {0.25, 0.5, 0.75, 1.0};
  double previous = 1.0;
  for (int k : {32, 64, 128, 256}) {
    std::vector<Vec3> p(v.size()), t(v.size());
    CorotationalWireJob job;
    job.length = kL;
    job.bending_stiffness = kEI;
    job.tip_bending_stiffness = r * kEI;
    job.segments = k;
    job.tip_moment = m;
    job.samples = v;
    job.position = p;
    job.tangent = t;
    CorotationalWireResult result;
    job.result = &result;
    ASSERT_TRUE(job.Run().ok());
    double error = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
      error = std::max(error, (p[i] - exact(v[i] * kL)).norm() / kL);
      // A constant moment: each segment's mean compliance makes the turn exact.
      EXPECT_NEAR(std::remainder(std::atan2(t[i].y(), t[i].x()) - theta(v[i] * kL), 2 * kPi), 0.0,
                  1e-9);
    }
    EXPECT_NEAR(result.tip_rotation, 3.0 * kPi, 1e-9);
    std::printf("tapered spiral (EI tip / root 0.1, 1.5 turns): K=%d position error / L %.2e\n", k,
                error);
    EXPECT_LT(error, 0.35 * previous);
    previous = error;
  }
  EXPECT_LT(previous, 1e-4);
}

TEST(CorotationalWireJob, GuidedTipIsTwoHalfElasticas) {
  // A guided cantilever under a perpendicular tip force is antisymmetric about its midpoint,
  // where the moment vanishes: each half is a free cantilever of length L/2 under the same force,
  // so the tip sits at twice the half-elastica's tip.
  const testing::ElasticaTip half = ExactElasticaTip(kPi / 2, Deg(40.0));
  const double f = half.alpha * kEI / (0.25 * kL * kL);
  const CorotationalWireResult r =
      RunTipForce(Vec3(0.0, f, 0.0), 128, BoundaryCondition::kCantileverGuided);
  EXPECT_NEAR(r.tip_position.x() / kL, half.x, 2e-4);
  EXPECT_NEAR(r.tip_position.y() / kL, half.y, 2e-4);
  EXPECT_NEAR(r.tip_rotation, 0.0, 1e-12);
}

TEST(CorotationalWireJob, DeadLineLoadMatchesRk4Shooting) {
  // Gravity-like uniform load q (N/m, -Y) over the whole wire: dM/ds = q (L - s) cos(theta)
  // for q along -Y (the moment of the load beyond s), solved by RK4 shooting.
  const double q = 6.0 * kEI / (kL * kL * kL);  // q L^3 / EI = 6: a large droop
  const testing::ElasticaState shot = testing::ShootElastica(
      kL, kEI, -q * kL * kL / kEI, 0.0, 20000, [&](double s, const testing::ElasticaState& st) {
        return q * (kL - s) * std::cos(st.theta);
      });
  const std::array<LineLoad, 1> lines = {LineLoad{0.0, 1.0, Vec3(0.0, -q, 0.0)}};
  double previous = 1.0;
  for (int k : {8, 16, 32, 64, 128}) {
    CorotationalWireJob job;
    job.length = kL;
    job.bending_stiffness = kEI;
    job.segments = k;
    job.line_loads = lines;
    CorotationalWireResult r;
    job.result = &r;
    ASSERT_TRUE(job.Run().ok());
    const double e = std::hypot(r.tip_position.x() - shot.x, r.tip_position.y() - shot.y) / kL;
    std::printf("dead line load q L^3/EI = 6 (tip rotation %.1f deg): K=%d tip error / L %.2e\n",
                -shot.theta * 180 / kPi, k, e);
    EXPECT_LT(e, 0.35 * previous);
    previous = e;
  }
  EXPECT_LT(previous, 1e-4);
}

TEST(CorotationalWireJob, PointLoadsMatchRk4Shooting) {
  // Two dead point loads, one with an axial part: dM/ds = -sum over loads beyond s of
  // t(s) x F_j = -sum (cos(theta) F_y - sin(theta) F_x).
  const std::array<PointLoad, 2> loads = {PointLoad{0.4, Vec3(-3.0, 5.0, 0.0)},
                                          PointLoad{0.8, Vec3(1.0, 4.0, 0.0)}};
  const testing::ElasticaState shot = testing::ShootElastica(
      kL, kEI, 0.0, 15.0 * kL / kEI, 40000, [&](double s, const testing::ElasticaState& st) {
        double dm = 0.0;
        for (const PointLoad& p : loads)
          if (s < p.at * kL)
            dm -= std::cos(st.theta) * p.force.y() - std::sin(st.theta) * p.force.x();
        return dm;
      });
  CorotationalWireJob job;
  job.length = kL;
  job.bending_stiffness = kEI;
  job.segments = 100;  // nodes on both loads
  job.point_loads = loads;
  CorotationalWireResult r;
  job.result = &r;
  ASSERT_TRUE(job.Run().ok());
  EXPECT_GT(r.tip_rotation, Deg(40.0));
  EXPECT_NEAR(r.tip_position.x(), shot.x, 2e-4 * kL);
  EXPECT_NEAR(r.tip_position.y(), shot.y, 2e-4 * kL);
  EXPECT_NEAR(r.tip_rotation, shot.theta, 2e-4);
}

TEST(CorotationalWireJob, TinyLoadsEqualBendingJob) {
  // Loads perpendicular to the straight wire with tip rotations ~1e-7: the chain is linear
  // theory up to relative terms of order theta^2.
  const double scale = 1e-7 * kEI / (kL * kL);
  const std::array<PointLoad, 2> points = {PointLoad{0.3, Vec3(0.0, 2.0 * scale, 0.0)},
                                           PointLoad{0.71, Vec3(0.0, -0.5 * scale, 0.0)}};
  const std::array<LineLoad, 1> lines = {LineLoad{0.2, 0.9, Vec3(0.0, 1.5 * scale / kL, 0.0)}};
  const Vec3 tip(0.0, 0.7 * scale, 0.0);
  std::vector<double> v;
  for (int i = 0; i <= 40; ++i) v.push_back(i / 40.0);
  v.push_back(0.3);
  v.push_back(0.555);
  for (BoundaryCondition bc :
       {BoundaryCondition::kCantileverFree, BoundaryCondition::kCantileverGuided}) {
    SCOPED_TRACE(ToString(bc));
    for (int k : {1, 7, 16}) {
      SCOPED_TRACE(::testing::Message() << "K " << k);
      std::vector<Vec3> p(v.size()), t(v.size()), x(v.size()), slope(v.size());
      CorotationalWireJob chain;
      chain.boundary = bc;
      chain.length = kL;
      chain.bending_stiffness = kEI;
      chain.segments = k;
      chain.tip_force = tip;
      chain.point_loads = points;
      chain.line_loads = lines;
      chain.samples = v;
      chain.position = p;
      chain.tangent = t;
      ASSERT_TRUE(chain.Run().ok());
      BendingJob linear;
      linear.boundary = bc;
      linear.length = kL;
      linear.bending_stiffness = kEI;
      linear.tip_force = tip;
      linear.point_loads = points;
      linear.line_loads = lines;
      linear.samples = v;
      linear.displacement = x;
      linear.slope = slope;
      ASSERT_TRUE(linear.Run().ok());
      double max_w = 0.0, max_slope = 0.0;
      for (std::size_t i = 0; i < v.size(); ++i) {
        max_w = std::max(max_w, std::abs(x[i].y()));
        max_slope = std::max(max_slope, std::abs(slope[i].y()));
      }
      for (std::size_t i = 0; i < v.size(); ++i) {
        EXPECT_NEAR(p[i].y(), x[i].y(), 1e-9 * max_w) << v[i];
        EXPECT_NEAR(t[i].y() / t[i].x(), slope[i].y(), 1e-9 * max_slope) << v[i];
        // Axially the chain is inextensible to second order: s - x = O(theta^2 L).
        EXPECT_NEAR(p[i].x(), kL * v[i], 10.0 * max_slope * max_slope * kL) << v[i];
      }
    }
  }
}

TEST(CorotationalWireJob, SamplesFollowTheChain) {
  // Arc length between close samples equals L dv to second order; the tip sample is the tip.
  const testing::ElasticaTip exact = ExactElasticaTip(kPi / 2, Deg(80.0));
  std::vector<double> v;
  for (int i = 0; i <= 400; ++i) v.push_back(i / 400.0);
  std::vector<Vec3> p(v.size()), t(v.size());
  CorotationalWireJob job;
  job.length = kL;
  job.bending_stiffness = kEI;
  job.tip_force = Vec3(0.0, exact.alpha * kEI / (kL * kL), 0.0);
  job.samples = v;
  job.position = p;
  job.tangent = t;
  CorotationalWireResult r;
  job.result = &r;
  ASSERT_TRUE(job.Run().ok());
  EXPECT_EQ(r.segments, AutomaticSegmentCount(job));
  EXPECT_LT((p.back() - r.tip_position).norm(), 1e-12);
  EXPECT_LT((p.front()).norm(), 1e-15);
  double arc = 0.0;
  for (std::size_t i = 1; i < v.size(); ++i) {
    arc += (p[i] - p[i - 1]).norm();
    EXPECT_NEAR(t[i].norm(), 1.0, 1e-14);
    // The chord direction agrees with the tangents at its ends.
    const Vec3 chord = (p[i] - p[i - 1]).normalized();
    EXPECT_GT(chord.dot(t[i]), std::cos(0.2));
  }
  EXPECT_NEAR(arc, kL, 2e-3 * kL);
}

TEST(CorotationalWireJob, ZeroLoadsLeaveTheWireStraight) {
  const CorotationalWireResult r = RunTipForce(Vec3::Zero(), 8);
  EXPECT_NEAR(r.tip_position.x(), kL, 1e-15);
  EXPECT_EQ(r.tip_position.y(), 0.0);
  EXPECT_EQ(r.tip_rotation, 0.0);
}

TEST(CorotationalWireJob, ValidateNamesTheFirstBadField) {
  std::array<double, 2> v = {0.0, 1.0};
  std::array<Vec3, 2> p, t;
  std::array<Vec3, 1> short_out;
  std::array<PointLoad, 1> bad_point = {PointLoad{1.5, Vec3(0.0, 1.0, 0.0)}};
  std::array<PointLoad, 1> off_plane = {PointLoad{0.5, Vec3(0.0, 1.0, 1.0)}};
  std::array<LineLoad, 1> bad_line = {LineLoad{0.6, 0.2, Vec3(0.0, 1.0, 0.0)}};
  std::array<PointLoad, CorotationalWireJob::kMaxPointLoads + 1> many_points{};
  std::array<double, 1> bad_sample = {1.2};
  auto base = [&] {
    CorotationalWireJob job;
    job.length = kL;
    job.bending_stiffness = kEI;
    job.tip_force = Vec3(0.0, 1.0, 0.0);
    job.samples = v;
    job.position = p;
    job.tangent = t;
    return job;
  };
  ASSERT_TRUE(base().Validate().ok());
  struct Case {
    const char* field;
    std::function<void(CorotationalWireJob&)> edit;
  };
  const std::vector<Case> cases = {
      {"boundary", [](auto& j) { j.boundary = BoundaryCondition::kClamped; }},
      {"boundary", [](auto& j) { j.boundary = BoundaryCondition::kSimplySupported; }},
      {"length", [](auto& j) { j.length = 0.0; }},
      {"length", [](auto& j) { j.length = std::numeric_limits<double>::infinity(); }},
      {"bending_stiffness", [](auto& j) { j.bending_stiffness = -1.0; }},
      {"bending_stiffness", [](auto& j) { j.bending_stiffness = 1e-320; }},
      {"tip_bending_stiffness", [](auto& j) { j.tip_bending_stiffness = -1.0; }},
      {"tip_bending_stiffness", [](auto& j) { j.tip_bending_stiffness = 1e-20; }},
      {"segments", [](auto& j) { j.segments = -1; }},
      {"segments", [](auto& j) { j.segments = CorotationalWireJob::kMaxSegments + 1; }},
      {"segments", [](auto& j) { j.segments = 2, j.tip_force = Vec3(0.0, 100.0, 0.0); }},
      {"tip_force", [](auto& j) { j.tip_force = Vec3(0.0, 0.0, 1.0); }},
      {"tip_force", [](auto& j) { j.tip_force.x() = std::numeric_limits<double>::quiet_NaN(); }},
      {"tip_moment", [](auto& j) { j.tip_moment = std::numeric_limits<double>::infinity(); }},
      {"tip_moment",
       [](auto& j) { j.boundary = BoundaryCondition::kCantileverGuided, j.tip_moment = 1.0; }},
      {"point_loads", [&](auto& j) { j.point_loads = bad_point; }},
      {"point_loads", [&](auto& j) { j.point_loads = off_plane; }},
      {"point_loads", [&](auto& j) { j.point_loads = many_points; }},
      {"line_loads", [&](auto& j) { j.line_loads = bad_line; }},
      {"tip_force", [](auto& j) { j.tip_force = Vec3(0.0, 1e300, 0.0); }},
      {"segments", [](auto& j) { j.segments = 8, j.tip_force = Vec3(0.0, 1e90, 0.0); }},
      {"root_moment_guess",
       [](auto& j) { j.warm_start = true, j.root_moment_guess = std::nan(""); }},
      {"samples", [&](auto& j) { j.samples = bad_sample, j.position = {}, j.tangent = {}; }},
      {"position", [&](auto& j) { j.position = short_out; }},
      {"tangent", [&](auto& j) { j.tangent = short_out; }},
  };
  for (const Case& c : cases) {
    CorotationalWireJob job = base();
    c.edit(job);
    const Status status = job.Validate();
    EXPECT_EQ(status.field, c.field) << ToString(status);
    EXPECT_EQ(job.Run().field, c.field);
  }
  // Outputs are optional.
  CorotationalWireJob job = base();
  job.samples = {};
  job.position = {};
  job.tangent = {};
  EXPECT_TRUE(job.Run().ok());
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
