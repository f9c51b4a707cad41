// BendingJob against textbook beam formulas in physical units, the boundary conditions and
// the ODE itself (finite differences of the evaluated curve), and its input validation.
#include "wirerig/runtime/bending_job.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

// A job that owns its buffers: samples at v_i = i/(n-1), all three outputs.
struct BendingCase {
  BendingJob job;
  std::vector<PointLoad> point_loads;
  std::vector<LineLoad> line_loads;
  std::vector<LinearLineLoad> linear_line_loads;
  std::vector<double> samples;
  std::vector<Vec3> x, slope, curvature;

  BendingCase(BoundaryCondition bc, double length, double ei, std::vector<double> v)
      : samples(std::move(v)), x(samples.size()), slope(samples.size()), curvature(samples.size()) {
    job.boundary = bc;
    job.length = length;
    job.bending_stiffness = ei;
  }
  // Runs and returns the displacement at the first sample.
  void Run() {
    job.point_loads = point_loads;
    job.line_loads = line_loads;
    job.linear_line_loads = linear_line_loads;
    job.samples = samples;
    job.displacement = x;
    job.slope = slope;
    job.curvature = curvature;
    const Status status = job.Run();
    ASSERT_TRUE(status.ok()) << ToString(status);
  }
};

std::vector<double> Points(std::initializer_list<double> v) { return std::vector<double>(v); }

constexpr double kL = 2.0;    // m
constexpr double kEI = 20.0;  // N m^2 (E = 2 GPa, I = 1e-8 m^4)
constexpr double kF = 10.0;   // N
constexpr double kQ = 5.0;    // N/m
const Vec3 kDown = -Vec3::UnitY();

constexpr std::array kFamilies = {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped,
                                  BoundaryCondition::kCantileverFree,
                                  BoundaryCondition::kCantileverGuided};

double Deflection(BoundaryCondition bc, double at, std::vector<PointLoad> p,
                  std::vector<LineLoad> q, Vec3 tip = Vec3::Zero()) {
  BendingCase c(bc, kL, kEI, Points({at}));
  c.point_loads = std::move(p);
  c.line_loads = std::move(q);
  c.job.tip_force = tip;
  c.Run();
  return -c.x[0].y();
}

TEST(BendingJobTextbook, CantileverTipLoadIsFL3Over3EI) {
  const double expected = kF * kL * kL * kL / (3.0 * kEI);
  EXPECT_NEAR(Deflection(BoundaryCondition::kCantileverFree, 1.0, {}, {}, kF * kDown), expected,
              1e-12 * expected);
  // The same load given as a point load at v = 1 (PHYSICS.md section 2, special cases).
  EXPECT_NEAR(Deflection(BoundaryCondition::kCantileverFree, 1.0, {{1.0, kF * kDown}}, {}),
              expected, 1e-12 * expected);
}

TEST(BendingJobTextbook, CantileverTipCoupleIsML2Over2EIInBothModes) {
  // A couple M at the free tip bends the cantilever into w = M s^2 / 2EI, w' = M s / EI.
  const double m = 3.0;  // N m
  for (BendingMode mode : {BendingMode::kExact, BendingMode::kSeries}) {
    const std::vector<double> v = {0.0, 0.3, 0.5, 1.0};
    std::vector<Vec3> x(v.size()), slope(v.size());
    BendingJob job;
    job.boundary = BoundaryCondition::kCantileverFree;
    job.mode = mode;
    job.length = kL;
    job.bending_stiffness = kEI;
    job.tip_couple = m * kDown;
    job.samples = v;
    job.displacement = x;
    job.slope = slope;
    ASSERT_TRUE(job.Run().ok());
    for (std::size_t i = 0; i < v.size(); ++i) {
      const double s = v[i] * kL;
      EXPECT_NEAR(-x[i].y(), m * s * s / (2.0 * kEI), 1e-12) << ToString(mode) << " v " << v[i];
      EXPECT_NEAR(-slope[i].y(), m * s / kEI, 1e-12) << ToString(mode) << " v " << v[i];
    }
    // A guided tip's support takes the couple: refused, named.
    job.boundary = BoundaryCondition::kCantileverGuided;
    EXPECT_EQ(job.Validate().field, "tip_couple");
  }
}

TEST(BendingJobTextbook, SimplySupportedCentreLoadIsFL3Over48EI) {
  const double expected = kF * kL * kL * kL / (48.0 * kEI);
  EXPECT_NEAR(Deflection(BoundaryCondition::kSimplySupported, 0.5, {{0.5, kF * kDown}}, {}),
              expected, 1e-12 * expected);
}

TEST(BendingJobTextbook, ClampedCentreLoadIsFL3Over192EI) {
  const double expected = kF * kL * kL * kL / (192.0 * kEI);
  EXPECT_NEAR(Deflection(BoundaryCondition::kClamped, 0.5, {{0.5, kF * kDown}}, {}), expected,
              1e-12 * expected);
}

TEST(BendingJobTextbook, GuidedCantileverTipLoadIsFL3Over12EI) {
  const double expected = kF * kL * kL * kL / (12.0 * kEI);
  EXPECT_NEAR(Deflection(BoundaryCondition::kCantileverGuided, 1.0, {}, {}, kF * kDown), expected,
              1e-12 * expected);
}

TEST(BendingJobTextbook, UniformLoadDeflections) {
  const double ql4 = kQ * kL * kL * kL * kL / kEI;
  const std::vector<LineLoad> uniform = {{0.0, 1.0, kQ * kDown}};
  EXPECT_NEAR(Deflection(BoundaryCondition::kSimplySupported, 0.5, {}, uniform), 5.0 * ql4 / 384.0,
              1e-12 * ql4);
  EXPECT_NEAR(Deflection(BoundaryCondition::kCantileverFree, 1.0, {}, uniform), ql4 / 8.0,
              1e-12 * ql4);
  EXPECT_NEAR(Deflection(BoundaryCondition::kClamped, 0.5, {}, uniform), ql4 / 384.0, 1e-12 * ql4);
  EXPECT_NEAR(Deflection(BoundaryCondition::kCantileverGuided, 1.0, {}, uniform), ql4 / 24.0,
              1e-12 * ql4);
}

TEST(BendingJobTextbook, SimplySupportedOffCentreLoadMatchesGreensFunction) {
  // Textbook: load F at distance a from the left, b = L - a; deflection at x <= a is
  // F b x (L^2 - b^2 - x^2) / (6 L EI).
  const double a = 0.3 * kL, b = kL - a, x = 0.2 * kL;
  const double expected = kF * b * x * (kL * kL - b * b - x * x) / (6.0 * kL * kEI);
  EXPECT_NEAR(Deflection(BoundaryCondition::kSimplySupported, 0.2, {{0.3, kF * kDown}}, {}),
              expected, 1e-12 * expected);
}

TEST(BendingJobTextbook, PatchLoadEqualsManyPointLoads) {
  // A patch load on [0.2, 0.6] against 20000 point loads at the midpoints of equal slices.
  std::vector<PointLoad> slices;
  const int n = 20000;
  for (int k = 0; k < n; ++k)
    slices.push_back({0.2 + 0.4 * (k + 0.5) / n, kQ * kL * 0.4 / n * kDown});
  for (BoundaryCondition bc :
       {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped,
        BoundaryCondition::kCantileverFree, BoundaryCondition::kCantileverGuided}) {
    SCOPED_TRACE(ToString(bc));
    for (double v : {0.1, 0.4, 0.75, 1.0}) {
      const double patch = Deflection(bc, v, {}, {{0.2, 0.6, kQ * kDown}});
      EXPECT_NEAR(Deflection(bc, v, slices, {}), patch, 1e-8 * std::abs(patch) + 1e-15);
    }
  }
}

// ---------------------------------------------------------------------------------------
// Linearly varying loads against textbook beam tables (Roark's Formulas for Stress and Strain,
// table 8.1; the AISC beam diagrams), w the largest load per length.

// Lateral deflection (along kDown) at the samples under linear loads alone.
std::vector<double> LinearDeflections(BoundaryCondition bc, BendingMode mode,
                                      std::vector<LinearLineLoad> loads, std::vector<double> v,
                                      int terms = 20) {
  BendingCase c(bc, kL, kEI, std::move(v));
  c.job.mode = mode;
  c.job.series_terms = terms;
  c.linear_line_loads = std::move(loads);
  c.Run();
  std::vector<double> out;
  for (const Vec3& x : c.x) out.push_back(x.dot(kDown));
  return out;
}

TEST(BendingJobTextbook, CantileverTriangularLoads) {
  const double wl4 = kQ * kL * kL * kL * kL / kEI;
  std::vector<double> v;
  for (int i = 0; i <= 20; ++i) v.push_back(i / 20.0);
  // Rising from 0 at the clamp to w at the tip: tip 11 w L^4 / 120 EI, and
  // y(x) = w x^2 (20 L^3 - 10 L^2 x + x^3) / (120 L EI).
  const std::vector<double> rising =
      LinearDeflections(BoundaryCondition::kCantileverFree, BendingMode::kExact,
                        {{0.0, 1.0, Vec3::Zero(), kQ * kDown}}, v);
  EXPECT_NEAR(rising.back(), 11.0 * wl4 / 120.0, 1e-13 * wl4);
  // Falling from w at the clamp to 0 at the tip: tip w L^4 / 30 EI, and
  // y(x) = w x^2 (10 L^3 - 10 L^2 x + 5 L x^2 - x^3) / (120 L EI).
  const std::vector<double> falling =
      LinearDeflections(BoundaryCondition::kCantileverFree, BendingMode::kExact,
                        {{0.0, 1.0, kQ * kDown, Vec3::Zero()}}, v);
  EXPECT_NEAR(falling.back(), wl4 / 30.0, 1e-13 * wl4);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double x = v[i] * kL, l = kL;
    const double up = kQ * x * x * (20 * l * l * l - 10 * l * l * x + x * x * x) / (120 * l * kEI);
    const double down = kQ * x * x * (10 * l * l * l - 10 * l * l * x + 5 * l * x * x - x * x * x) /
                        (120 * l * kEI);
    EXPECT_NEAR(rising[i], up, 1e-13 * wl4) << "v = " << v[i];
    EXPECT_NEAR(falling[i], down, 1e-13 * wl4) << "v = " << v[i];
  }
}

TEST(BendingJobTextbook, SimplySupportedTriangularLoad) {
  // Rising from 0 at the left support to w at the right: y = w x (7 L^4 - 10 L^2 x^2 + 3 x^4) /
  // (360 L EI); at midspan 5 w L^4 / 768 EI; the largest 0.00652 w L^4 / EI at
  // x = L sqrt(1 - sqrt(8/15)) = 0.5193 L.
  const double wl4 = kQ * kL * kL * kL * kL / kEI;
  std::vector<double> v;
  for (int i = 0; i <= 100000; ++i) v.push_back(i / 100000.0);
  const std::vector<double> y =
      LinearDeflections(BoundaryCondition::kSimplySupported, BendingMode::kExact,
                        {{0.0, 1.0, Vec3::Zero(), kQ * kDown}}, v);
  EXPECT_NEAR(y[50000], 5.0 * wl4 / 768.0, 1e-13 * wl4);
  const auto peak = std::max_element(y.begin(), y.end());
  const double at = v[std::size_t(peak - y.begin())];
  EXPECT_NEAR(*peak / wl4, 0.00652, 0.000005);  // the table's three digits
  EXPECT_NEAR(at, 0.519, 0.0005);
  EXPECT_NEAR(at, std::sqrt(1.0 - std::sqrt(8.0 / 15.0)), 1e-5);
  for (int i = 0; i <= 100000; i += 2500) {
    const double x = v[std::size_t(i)] * kL, l = kL;
    const double expected =
        kQ * x * (7 * l * l * l * l - 10 * l * l * x * x + 3 * x * x * x * x) / (360 * l * kEI);
    EXPECT_NEAR(y[std::size_t(i)], expected, 1e-13 * wl4) << "v = " << v[std::size_t(i)];
  }
}

TEST(BendingJobTextbook, ClampedAndGuidedTriangularLoads) {
  // Clamped at both ends, rising 0 -> w: y = w x^2 (L - x)^2 (2L + x) / (120 L EI), largest
  // 0.00131 w L^4 / EI at x = 0.525 L (the tables' digits); a guided cantilever (the symmetric half
  // of a clamped-clamped wire) rising 0 -> w toward its guided end: w x^2 (25 L^3 - 20 L^2 x + 2
  // x^3) / (240 L EI), here from the Macaulay table with a = 0, b = 1 (m0 = 1/120, m1 = 1/24, m3 =
  // 1/2).
  const double wl4 = kQ * kL * kL * kL * kL / kEI;
  std::vector<double> v;
  for (int i = 0; i <= 20; ++i) v.push_back(i / 20.0);
  const std::vector<LinearLineLoad> ramp = {{0.0, 1.0, Vec3::Zero(), kQ * kDown}};
  const std::vector<double> clamped =
      LinearDeflections(BoundaryCondition::kClamped, BendingMode::kExact, ramp, v);
  const std::vector<double> guided =
      LinearDeflections(BoundaryCondition::kCantileverGuided, BendingMode::kExact, ramp, v);
  std::vector<double> fine;
  for (int i = 0; i <= 10000; ++i) fine.push_back(i / 10000.0);
  const std::vector<double> y =
      LinearDeflections(BoundaryCondition::kClamped, BendingMode::kExact, ramp, fine);
  const auto peak = std::max_element(y.begin(), y.end());
  EXPECT_NEAR(*peak / wl4, 0.00131, 0.000005);
  EXPECT_NEAR(fine[std::size_t(peak - y.begin())], 0.525, 0.0005);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double x = v[i] * kL, l = kL;
    EXPECT_NEAR(clamped[i], kQ * x * x * (l - x) * (l - x) * (2 * l + x) / (120 * l * kEI),
                1e-13 * wl4);
    EXPECT_NEAR(guided[i],
                kQ * x * x * (25 * l * l * l - 20 * l * l * x + 2 * x * x * x) / (240 * l * kEI),
                1e-13 * wl4);
  }
}

TEST(BendingJobTextbook, LinearLoadEqualsManyPointLoads) {
  // A trapezoid on [0.2, 0.6] against 20000 point loads at the slices' midpoints, each the
  // slice's load (exact for a linear load: its midpoint value times the slice).
  const Vec3 start = kQ * kDown, end = Vec3(2.0, -0.5 * kQ, 3.0);
  std::vector<PointLoad> slices;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const double t = (k + 0.5) / n;
    slices.push_back({0.2 + 0.4 * t, ((1.0 - t) * start + t * end) * (kL * 0.4 / n)});
  }
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    BendingCase linear(bc, kL, kEI, Points({0.1, 0.4, 0.75, 1.0}));
    linear.linear_line_loads = {{0.2, 0.6, start, end}};
    linear.Run();
    BendingCase points(bc, kL, kEI, Points({0.1, 0.4, 0.75, 1.0}));
    points.point_loads = slices;
    points.Run();
    for (std::size_t i = 0; i < 4; ++i)
      EXPECT_LT((linear.x[i] - points.x[i]).norm(), 1e-8 * points.x[i].norm() + 1e-15);
  }
}

TEST(BendingJobTextbook, TrapezoidIsUniformPlusRampInBothModes) {
  // p_a -> p_b over [a, b] = p_a uniform over [a, b] + a ramp 0 -> p_b - p_a; and a linear
  // load with equal ends is the uniform LineLoad.
  const Vec3 pa(1.0, -4.0, 2.0), pb(-3.0, 2.5, 0.5);
  for (BendingMode mode : {BendingMode::kExact, BendingMode::kSeries})
    for (BoundaryCondition bc : kFamilies) {
      SCOPED_TRACE(std::string(ToString(bc)) + " " + std::string(ToString(mode)));
      const std::vector<double> v = Points({0.0, 0.1, 0.3, 0.5, 0.62, 0.9, 1.0});
      BendingCase trapezoid(bc, kL, kEI, v), parts(bc, kL, kEI, v), level(bc, kL, kEI, v),
          uniform(bc, kL, kEI, v);
      for (BendingCase* c : {&trapezoid, &parts, &level, &uniform}) c->job.mode = mode;
      trapezoid.linear_line_loads = {{0.25, 0.7, pa, pb}};
      parts.line_loads = {{0.25, 0.7, pa}};
      parts.linear_line_loads = {{0.25, 0.7, Vec3::Zero(), pb - pa}};
      level.linear_line_loads = {{0.25, 0.7, pa, pa}};
      uniform.line_loads = {{0.25, 0.7, pa}};
      for (BendingCase* c : {&trapezoid, &parts, &level, &uniform}) c->Run();
      double scale = 0.0;
      for (const Vec3& x : trapezoid.x) scale = std::max(scale, x.norm());
      for (std::size_t i = 0; i < v.size(); ++i) {
        EXPECT_LT((trapezoid.x[i] - parts.x[i]).norm(), 1e-14 * scale) << "v = " << v[i];
        EXPECT_LT((trapezoid.slope[i] - parts.slope[i]).norm(), 1e-13 * scale) << "v = " << v[i];
        EXPECT_LT((level.x[i] - uniform.x[i]).norm(), 1e-14 * scale) << "v = " << v[i];
        EXPECT_LT((level.curvature[i] - uniform.curvature[i]).norm(), 1e-13 * scale);
      }
    }
}

TEST(BendingJobBoundary, OdeHoldsUnderALinearLoad) {
  // EI X'''' = p(v) inside the load (fourth difference: exact for the quintic pieces), with the
  // end conditions met (a trapezoid over [0.3, 0.8] on every family).
  const Vec3 start(1.0, -6.0, 2.0), end(-2.0, 3.0, 0.5);
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    for (double centre : {0.45, 0.6, 0.7}) {
      const double h = 0.01;
      BendingCase c(bc, kL, kEI,
                    Points({centre - 2 * h, centre - h, centre, centre + h, centre + 2 * h}));
      c.linear_line_loads = {{0.3, 0.8, start, end}};
      c.Run();
      const double hs = h * kL;
      const Vec3 fourth =
          (c.x[0] - 4.0 * c.x[1] + 6.0 * c.x[2] - 4.0 * c.x[3] + c.x[4]) / (hs * hs * hs * hs);
      const double t = (centre - 0.3) / 0.5;
      const Vec3 p = (1.0 - t) * start + t * end;
      EXPECT_LT((kEI * fourth - p).norm(), 1e-4 * start.norm()) << "v = " << centre;
    }
  }
}

TEST(BendingJobDegenerate, NarrowLinearLoadIsAPointLoadAtItsCentroid) {
  // Over a width of 1e-6 and 1e-9 a trapezoid acts as its total load at its centroid,
  // a + d (p_a + 2 p_b) / (3 (p_a + p_b)) (to rounding: like a uniform patch's, a narrow
  // load's terms cancel to about 1e-16 / d of its effect); over widths down to 1e-300 it stays
  // finite (nothing divides by the width unguarded).
  for (double requested : {1e-6, 1e-9}) {
    for (BoundaryCondition bc : kFamilies) {
      SCOPED_TRACE(std::string(ToString(bc)) + " width " + std::to_string(requested));
      const double a = 0.4, b = a + requested, width = b - a;
      const double pa = 1e3, pb = 3e3;  // N/m, along kDown
      const double total = 0.5 * (pa + pb) * width * kL;
      const double centroid = a + width * (pa + 2.0 * pb) / (3.0 * (pa + pb));
      for (BendingMode mode : {BendingMode::kExact, BendingMode::kSeries}) {
        BendingCase linear(bc, kL, kEI, Points({0.2, centroid, 0.7, 1.0}));
        linear.job.mode = mode;
        linear.linear_line_loads = {{a, b, pa * kDown, pb * kDown}};
        linear.Run();
        BendingCase point(bc, kL, kEI, Points({0.2, centroid, 0.7, 1.0}));
        point.job.mode = mode;
        point.point_loads = {{centroid, total * kDown}};
        point.Run();
        const double scale = point.x[2].norm() + point.x[3].norm();
        ASSERT_GT(scale, 0.0);
        for (std::size_t i = 0; i < 4; ++i)
          EXPECT_LT((linear.x[i] - point.x[i]).norm(), 1e-6 * scale) << ToString(mode) << " " << i;
      }
    }
  }
  for (BoundaryCondition bc : kFamilies)
    for (BendingMode mode : {BendingMode::kExact, BendingMode::kSeries})
      for (auto [a, b] : {std::pair{0.0, 1e-300}, std::pair{0.5, std::nextafter(0.5, 1.0)},
                          std::pair{std::nextafter(1.0, 0.0), 1.0}}) {
        BendingCase c(bc, kL, kEI, Points({0.0, a, 0.5, 1.0}));
        c.job.mode = mode;
        c.linear_line_loads = {{a, b, 1e5 * kDown, -2e5 * kDown}};
        c.Run();
        for (const Vec3& x : c.x) EXPECT_LT(x.norm(), 1e-6);
      }
}

TEST(BendingJobDegenerate, LinearLoadsAtTheEndsAndEqualEnds) {
  // A ramp ending at either end of the wire, a triangle whose peak sits on a support, and a
  // load on a sliver at v = 1 of a clamped wire (the support takes it): all finite, and the
  // last one tiny.
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    BendingCase c(bc, kL, kEI, Points({0.0, 0.5, 1.0}));
    c.linear_line_loads = {{0.0, 0.2, kQ * kDown, Vec3::Zero()},
                           {0.8, 1.0, Vec3::Zero(), kQ * kDown}};
    c.Run();
    EXPECT_LT((c.x[0] - c.job.start_displacement).norm(), 1e-15);
  }
  BendingCase sliver(BoundaryCondition::kClamped, kL, kEI, Points({0.5, 0.999}));
  sliver.linear_line_loads = {{1.0 - 1e-12, 1.0, kQ * kDown, kQ * kDown}};
  sliver.Run();
  EXPECT_LT(sliver.x[0].norm(), 1e-30);
}

// ---------------------------------------------------------------------------------------
// Boundary conditions, the ODE between loads and the jump at loads, for every family.

BendingCase LoadedCase(BoundaryCondition bc, std::vector<double> v) {
  BendingCase c(bc, kL, kEI, std::move(v));
  c.point_loads = {{0.3, Vec3(1.0, -4.0, 2.0)}, {0.55, Vec3(-3.0, 2.5, 0.5)}};
  c.line_loads = {{0.6, 0.8, Vec3(0.5, -6.0, 1.0)}};
  c.job.start_displacement = Vec3(0.01, -0.02, 0.005);
  c.job.end_displacement = Vec3(-0.01, 0.03, 0.0);
  if (IsCantilever(bc)) c.job.tip_force = Vec3(0.7, -1.5, 0.2);
  return c;
}

TEST(BendingJobBoundary, EndConditionsHold) {
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const double h = 1e-4;
    BendingCase c = LoadedCase(bc, Points({0.0, 1.0 - h, 1.0}));
    c.Run();
    const double tol = 1e-10;
    EXPECT_LT((c.x[0] - c.job.start_displacement).norm(), tol);
    if (bc == BoundaryCondition::kSimplySupported) {
      EXPECT_LT(c.curvature[0].norm(), tol);
      EXPECT_LT((c.x[2] - c.job.end_displacement).norm(), tol);
      EXPECT_LT(c.curvature[2].norm(), tol);
    } else {
      EXPECT_LT(c.slope[0].norm(), tol);
    }
    if (bc == BoundaryCondition::kClamped) {
      EXPECT_LT((c.x[2] - c.job.end_displacement).norm(), tol);
      EXPECT_LT(c.slope[2].norm(), tol);
    }
    if (IsCantilever(bc)) {
      if (bc == BoundaryCondition::kCantileverFree) {
        EXPECT_LT(c.curvature[2].norm(), tol);
      } else {
        EXPECT_LT(c.slope[2].norm(), tol);
      }
      // Near the free end X is cubic, so the curvature is linear: one difference is exact.
      const Vec3 third = (c.curvature[2] - c.curvature[1]) / (h * kL);
      EXPECT_LT((kEI * third + c.job.tip_force).norm(), 1e-6);
    }
  }
}

// Fourth finite difference over 5 samples spaced h: exact for the quartic pieces of X.
Vec3 FourthDerivative(BoundaryCondition bc, double centre, double h) {
  BendingCase c =
      LoadedCase(bc, Points({centre - 2 * h, centre - h, centre, centre + h, centre + 2 * h}));
  c.Run();
  const double hs = h * kL;
  return (c.x[0] - 4.0 * c.x[1] + 6.0 * c.x[2] - 4.0 * c.x[3] + c.x[4]) / (hs * hs * hs * hs);
}

TEST(BendingJobBoundary, OdeHoldsBetweenAndUnderLoads) {
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    // Between loads EI X'''' = 0; under the line load EI X'''' = q.
    for (double centre : {0.15, 0.45, 0.9})
      EXPECT_LT((kEI * FourthDerivative(bc, centre, 0.01)).norm(), 1e-4) << "at v=" << centre;
    const Vec3 q = LoadedCase(bc, {}).line_loads[0].force_per_length;
    EXPECT_LT((kEI * FourthDerivative(bc, 0.7, 0.01) - q).norm(), 1e-4 * q.norm());
  }
}

TEST(BendingJobBoundary, JumpOfShearAtAPointLoadEqualsTheLoad) {
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const double a = 0.3, h = 1e-3;
    BendingCase c = LoadedCase(bc, Points({a - 2 * h, a - h, a + h, a + 2 * h}));
    c.Run();
    // The curvature is linear on each side of the load, so these differences are exact.
    const Vec3 before = (c.curvature[1] - c.curvature[0]) / (h * kL);
    const Vec3 after = (c.curvature[3] - c.curvature[2]) / (h * kL);
    const Vec3 load = c.point_loads[0].force;
    EXPECT_LT((kEI * (after - before) - load).norm(), 1e-6 * load.norm());
    // X, X' and X'' are continuous across the load.
    BendingCase at = LoadedCase(bc, Points({a - 1e-9, a + 1e-9}));
    at.Run();
    EXPECT_LT((at.x[1] - at.x[0]).norm(), 1e-8);
    EXPECT_LT((at.slope[1] - at.slope[0]).norm(), 1e-8);
    EXPECT_LT((at.curvature[1] - at.curvature[0]).norm(), 1e-6);
  }
}

TEST(BendingJobBoundary, SlopeAndCurvatureAreDerivativesOfDisplacement) {
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const double v = 0.42, h = 1e-5;
    BendingCase c = LoadedCase(bc, Points({v - h, v, v + h}));
    c.Run();
    const double hs = h * kL;
    EXPECT_LT(((c.x[2] - c.x[0]) / (2 * hs) - c.slope[1]).norm(), 1e-6);
    EXPECT_LT(((c.x[2] - 2.0 * c.x[1] + c.x[0]) / (hs * hs) - c.curvature[1]).norm(), 1e-3);
  }
}

// ---------------------------------------------------------------------------------------
// Degenerate cases, by name.

TEST(BendingJobDegenerate, LoadAtTheFixedEndProducesNoDeflection) {
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    // Zero up to round-off of the deflection scale F L^3 / EI = 4 m.
    for (double v : {0.25, 0.5, 1.0})
      EXPECT_NEAR(Deflection(bc, v, {{0.0, kF * kDown}}, {}), 0.0, 1e-14);
  }
}

TEST(BendingJobDegenerate, LoadAtTheFarSupportProducesNoDeflection) {
  for (BoundaryCondition bc : {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped})
    for (double v : {0.25, 0.5, 0.9})
      EXPECT_NEAR(Deflection(bc, v, {{1.0, kF * kDown}}, {}), 0.0, 1e-14);
}

TEST(BendingJobDegenerate, CoincidentLoadsAddUp) {
  for (BoundaryCondition bc : kFamilies) {
    const double single = Deflection(bc, 0.6, {{0.4, 3.0 * kF * kDown}}, {});
    EXPECT_NEAR(Deflection(bc, 0.6, {{0.4, kF * kDown}, {0.4, 2.0 * kF * kDown}}, {}), single,
                1e-13 * std::abs(single));
  }
}

TEST(BendingJobDegenerate, EndDisplacementsAloneGiveTheHomogeneousSolution) {
  // No load: simply supported is the straight line X0 + (X1 - X0) v; clamped is the
  // Hermite blend X0 + (X1 - X0)(3v^2 - 2v^3); cantilevers translate rigidly by X0.
  const Vec3 x0(0.1, 0.2, -0.3), x1(-0.2, 0.5, 0.4);
  const double v = 0.35;
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    BendingCase c(bc, kL, kEI, Points({v}));
    c.job.start_displacement = x0;
    c.job.end_displacement = x1;
    c.Run();
    Vec3 expected = x0;
    if (bc == BoundaryCondition::kSimplySupported) expected = x0 + (x1 - x0) * v;
    if (bc == BoundaryCondition::kClamped) expected = x0 + (x1 - x0) * (3 * v * v - 2 * v * v * v);
    EXPECT_LT((c.x[0] - expected).norm(), 1e-14);
  }
}

// ---------------------------------------------------------------------------------------
// Validation: one test per kind of invalid input; each mutates one input of a valid job.

class BendingJobValidation : public ::testing::Test {
 protected:
  std::array<PointLoad, 1> point_loads{{{0.5, Vec3(0, -1, 0)}}};
  std::array<LineLoad, 1> line_loads{{{0.2, 0.4, Vec3(0, -1, 0)}}};
  std::array<double, 3> samples{0.0, 0.5, 1.0};
  std::array<Vec3, 3> x, slope;
  BendingJob job;

  void SetUp() override {
    job.boundary = BoundaryCondition::kCantileverFree;
    job.length = 1.0;
    job.bending_stiffness = 1.0;
    job.point_loads = point_loads;
    job.line_loads = line_loads;
    job.samples = samples;
    job.displacement = x;
    ASSERT_TRUE(job.Validate().ok());
  }
  // Expects Validate() and Run() to refuse, naming `field`, and Run() to write nothing.
  void ExpectRefused(std::string_view field, int index = -1, std::string_view member = {}) {
    x.fill(Vec3::Constant(42.0));
    const Status status = job.Validate();
    EXPECT_FALSE(status.ok());
    EXPECT_EQ(status.field, field) << ToString(status);
    EXPECT_EQ(status.index, index) << ToString(status);
    EXPECT_EQ(status.member, member) << ToString(status);
    EXPECT_FALSE(status.reason.empty());
    EXPECT_FALSE(job.Run().ok());
    for (const Vec3& p : x) EXPECT_EQ(p, Vec3::Constant(42.0));
  }
  static double NaN() { return std::numeric_limits<double>::quiet_NaN(); }
  static double Inf() { return std::numeric_limits<double>::infinity(); }
};

TEST_F(BendingJobValidation, UnknownBoundaryCondition) {
  job.boundary = static_cast<BoundaryCondition>(7);
  ExpectRefused("boundary");
}
TEST_F(BendingJobValidation, UnknownMode) {
  job.mode = static_cast<BendingMode>(5);
  ExpectRefused("mode");
}
TEST_F(BendingJobValidation, SeriesTermsOutOfRange) {
  job.mode = BendingMode::kSeries;
  job.series_terms = 0;
  ExpectRefused("series_terms");
  job.series_terms = BendingJob::kMaxSeriesTerms + 1;
  ExpectRefused("series_terms");
}
TEST_F(BendingJobValidation, LengthNotPositiveOrNotFinite) {
  for (double bad : {0.0, -1.0, NaN(), Inf()}) {
    job.length = bad;
    ExpectRefused("length");
  }
  // So short that 1/L^2 overflows: the curvatures came out NaN (found by trying the CLI).
  job.length = 1e-160;
  ExpectRefused("length");
  job.length = 1e-150;
  EXPECT_TRUE(job.Validate().ok());
}
TEST_F(BendingJobValidation, StiffnessNotPositiveOrNotFinite) {
  for (double bad : {0.0, -3.0, NaN(), Inf()}) {
    job.bending_stiffness = bad;
    ExpectRefused("bending_stiffness");
  }
}
TEST_F(BendingJobValidation, NonFiniteEndDisplacements) {
  job.start_displacement = Vec3(0, NaN(), 0);
  ExpectRefused("start_displacement");
  job.start_displacement = Vec3::Zero();
  job.end_displacement = Vec3(Inf(), 0, 0);
  ExpectRefused("end_displacement");
}
TEST_F(BendingJobValidation, TipForceNotFiniteOrOnANonCantilever) {
  job.tip_force = Vec3(0, NaN(), 0);
  ExpectRefused("tip_force");
  job.tip_force = Vec3(0, -1, 0);
  job.boundary = BoundaryCondition::kClamped;
  ExpectRefused("tip_force");
}
TEST_F(BendingJobValidation, PointLoadOutsideTheWireOrNotFinite) {
  for (double bad : {-0.1, 1.5, NaN()}) {
    point_loads[0].at = bad;
    ExpectRefused("point_loads", 0, "at");
  }
  point_loads[0].at = 0.5;
  point_loads[0].force = Vec3(0, Inf(), 0);
  ExpectRefused("point_loads", 0, "force");
}
TEST_F(BendingJobValidation, LineLoadOutsideEmptyOrNotFinite) {
  line_loads[0].from = -0.2;
  ExpectRefused("line_loads", 0, "from");
  line_loads[0].from = 0.2;
  line_loads[0].to = 2.0;
  ExpectRefused("line_loads", 0, "to");
  line_loads[0].to = 0.2;  // zero width
  ExpectRefused("line_loads", 0, "to");
  line_loads[0].to = 0.4;
  line_loads[0].force_per_length = Vec3(NaN(), 0, 0);
  ExpectRefused("line_loads", 0, "force_per_length");
}
TEST_F(BendingJobValidation, LinearLineLoadOutsideEmptyReversedOrNotFinite) {
  std::array<LinearLineLoad, 2> linear{
      {{0.0, 1.0, Vec3(0, -1, 0), Vec3::Zero()}, {0.2, 0.4, Vec3(0, -1, 0), Vec3(1, -2, 0)}}};
  job.linear_line_loads = linear;
  ASSERT_TRUE(job.Validate().ok());
  for (double bad : {-0.2, 1.1, NaN(), Inf()}) {
    linear[1].from = bad;
    ExpectRefused("linear_line_loads", 1, "from");
  }
  linear[1].from = 0.2;
  for (double bad : {2.0, -0.1, NaN()}) {
    linear[1].to = bad;
    ExpectRefused("linear_line_loads", 1, "to");
  }
  linear[1].to = 0.2;  // zero width
  ExpectRefused("linear_line_loads", 1, "to");
  linear[1].to = 0.1;  // from > to
  ExpectRefused("linear_line_loads", 1, "to");
  linear[1].to = 0.4;
  linear[1].start_force_per_length = Vec3(0, NaN(), 0);
  ExpectRefused("linear_line_loads", 1, "start_force_per_length");
  linear[1].start_force_per_length = Vec3(0, -1, 0);
  linear[1].end_force_per_length = Vec3(0, 0, -Inf());
  ExpectRefused("linear_line_loads", 1, "end_force_per_length");
  linear[1].end_force_per_length = Vec3(0, -1e200, 0);
  ExpectRefused("loads");
  linear[1].end_force_per_length = Vec3::Zero();
  job.mode = BendingMode::kSeries;
  EXPECT_TRUE(job.Run().ok());
}
TEST_F(BendingJobValidation, LoadsThatWouldOverflow) {
  point_loads[0].force = Vec3(0, -1e200, 0);
  ExpectRefused("loads");
}
TEST_F(BendingJobValidation, TooFewSamplesOrSampleOutsideTheWire) {
  job.samples = {};
  job.displacement = {};
  ExpectRefused("samples");
  job.samples = samples;
  job.displacement = x;
  samples[1] = 1.01;
  ExpectRefused("samples", 1);
  samples[1] = NaN();
  ExpectRefused("samples", 1);
}
TEST_F(BendingJobValidation, OutputsOfTheWrongSize) {
  job.displacement = std::span<Vec3>(x).first(2);
  ExpectRefused("displacement");
  job.displacement = x;
  job.slope = std::span<Vec3>(slope).first(1);
  ExpectRefused("slope");
  job.slope = {};
  job.curvature = std::span<Vec3>(slope).first(2);
  ExpectRefused("curvature");
}

TEST(BendingJobNames, RoundTripAndUnknownNames) {
  for (BoundaryCondition bc : kFamilies) {
    BoundaryCondition parsed = BoundaryCondition::kSimplySupported;
    ASSERT_TRUE(ParseBoundaryCondition(ToString(bc), &parsed));
    EXPECT_EQ(parsed, bc);
  }
  BoundaryCondition bc = BoundaryCondition::kClamped;
  EXPECT_FALSE(ParseBoundaryCondition("pinned", &bc));
  EXPECT_EQ(bc, BoundaryCondition::kClamped);
  BendingMode mode = BendingMode::kExact;
  EXPECT_TRUE(ParseBendingMode("series", &mode));
  EXPECT_EQ(mode, BendingMode::kSeries);
  EXPECT_FALSE(ParseBendingMode("fourier", &mode));
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
