// BendingJob (kExact) against an independent finite-difference reference
// (tests/support/fd_beam_reference.h), and the reference itself against textbook formulas.
//
// Accuracy of the reference (measured with the FdBeamReference tests below): a single solve is
// O(h^2), e.g. 2e-4 relative at 100 intervals; after Richardson extrapolation over 100, 200 and
// 400 intervals the error against the textbook formulas is below 1e-14 relative (the nodal error
// of this scheme is exactly c h^2 for piecewise-polynomial solutions, and iterative refinement
// keeps rounding at that level). The tests ask for 1e-11; the agreement tests ask for 1e-6.
// Measured agreement of BendingJob with the reference over the random sets below: worst
// 3e-13 (clamped), 3e-15 (simply supported), 1e-15 (cantilevers), relative to max |X|; the
// residue is rounding in both (checked against 40-digit evaluations of textbook formulas).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "support/fd_beam_reference.h"
#include "wirerig/runtime/bending_job.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using ::wirerig::testing::FdBeamProblem;
using ::wirerig::testing::FdBeamSolution;
using ::wirerig::testing::FdScalarBeamProblem;
using ::wirerig::testing::FdScalarLinearLineLoad;
using ::wirerig::testing::FdScalarLineLoad;
using ::wirerig::testing::FdScalarPointLoad;
using ::wirerig::testing::SolveFdBeam;
using ::wirerig::testing::SolveFdBeamRichardson;

constexpr int kCoarse = 100;            // coarse grid: nodes v_k = k/100
constexpr double kFdTolerance = 1e-11;  // reference vs textbook, relative to max |X|
constexpr double kAgreement = 1e-6;     // BendingJob vs reference, relative to max |X|

constexpr double kL = 2.5;    // m
constexpr double kEI = 40.0;  // N m^2
constexpr double kF = 12.0;   // N
constexpr double kQ = 7.0;    // N/m

FdScalarBeamProblem Scalar(BoundaryCondition bc) {
  FdScalarBeamProblem p;
  p.boundary = bc;
  p.length = kL;
  p.bending_stiffness = kEI;
  return p;
}

// Max |fd - exact(s)| / max |exact(s)| over the coarse nodes, s = L k/n.
template <typename Exact>
double RelativeError(const FdBeamSolution& fd, double length, Exact exact) {
  EXPECT_TRUE(fd.ok()) << fd.error;
  if (!fd.ok()) return 1.0;
  const int n = static_cast<int>(fd.scalar.size()) - 1;
  double err = 0.0;
  double scale = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double x = exact(length * k / n);
    err = std::max(err, std::abs(fd.scalar[k] - x));
    scale = std::max(scale, std::abs(x));
  }
  return err / scale;
}

// Value of the reference at v (a coarse node).
double At(const FdBeamSolution& fd, double v) {
  const int n = static_cast<int>(fd.scalar.size()) - 1;
  return fd.scalar[static_cast<size_t>(std::lround(v * n))];
}

// ------------------------------------------------------------------------------------------
// The reference against textbook formulas (computed here, never by the runtime).

TEST(FdBeamReference, CantileverTipLoadIsFL3Over3EI) {
  FdScalarBeamProblem p = Scalar(BoundaryCondition::kCantileverFree);
  p.tip_force = kF;
  const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
  ASSERT_TRUE(fd.ok()) << fd.error;
  const double tip = kF * kL * kL * kL / (3.0 * kEI);
  EXPECT_NEAR(At(fd, 1.0), tip, kFdTolerance * tip);
  EXPECT_LE(
      RelativeError(fd, kL, [](double s) { return kF * s * s * (3.0 * kL - s) / (6.0 * kEI); }),
      kFdTolerance);
}

TEST(FdBeamReference, SimplySupportedCentreLoadIsFL3Over48EI) {
  FdScalarBeamProblem p = Scalar(BoundaryCondition::kSimplySupported);
  p.point_loads = {{0.5, kF}};
  const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
  ASSERT_TRUE(fd.ok()) << fd.error;
  const double centre = kF * kL * kL * kL / (48.0 * kEI);
  EXPECT_NEAR(At(fd, 0.5), centre, kFdTolerance * centre);
  EXPECT_LE(RelativeError(fd, kL,
                          [](double s) {
                            const double x = std::min(s, kL - s);
                            return kF * x * (3.0 * kL * kL - 4.0 * x * x) / (48.0 * kEI);
                          }),
            kFdTolerance);
}

TEST(FdBeamReference, ClampedCentreLoadIsFL3Over192EI) {
  FdScalarBeamProblem p = Scalar(BoundaryCondition::kClamped);
  p.point_loads = {{0.5, kF}};
  const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
  ASSERT_TRUE(fd.ok()) << fd.error;
  const double centre = kF * kL * kL * kL / (192.0 * kEI);
  EXPECT_NEAR(At(fd, 0.5), centre, kFdTolerance * centre);
  EXPECT_LE(RelativeError(fd, kL,
                          [](double s) {
                            const double x = std::min(s, kL - s);
                            return kF * x * x * (3.0 * kL - 4.0 * x) / (48.0 * kEI);
                          }),
            kFdTolerance);
}

TEST(FdBeamReference, GuidedCantileverTipLoadIsFL3Over12EI) {
  FdScalarBeamProblem p = Scalar(BoundaryCondition::kCantileverGuided);
  p.tip_force = kF;
  const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
  ASSERT_TRUE(fd.ok()) << fd.error;
  const double tip = kF * kL * kL * kL / (12.0 * kEI);
  EXPECT_NEAR(At(fd, 1.0), tip, kFdTolerance * tip);
  EXPECT_LE(RelativeError(
                fd, kL, [](double s) { return kF * s * s * (3.0 * kL - 2.0 * s) / (12.0 * kEI); }),
            kFdTolerance);
}

TEST(FdBeamReference, UniformLoads) {
  const double l4 = kQ * kL * kL * kL * kL / kEI;
  struct Case {
    BoundaryCondition bc;
    double v;         // where the textbook value applies
    double expected;  // deflection there
    double (*shape)(double s);
  };
  const Case cases[] = {
      {BoundaryCondition::kSimplySupported, 0.5, 5.0 * l4 / 384.0,
       [](double s) {
         return kQ * s * (kL * kL * kL - 2.0 * kL * s * s + s * s * s) / (24.0 * kEI);
       }},
      {BoundaryCondition::kCantileverFree, 1.0, l4 / 8.0,
       [](double s) { return kQ * s * s * (6.0 * kL * kL - 4.0 * kL * s + s * s) / (24.0 * kEI); }},
      {BoundaryCondition::kClamped, 0.5, l4 / 384.0,
       [](double s) { return kQ * s * s * (kL - s) * (kL - s) / (24.0 * kEI); }},
      {BoundaryCondition::kCantileverGuided, 1.0, l4 / 24.0,
       [](double s) { return kQ * s * s * (2.0 * kL - s) * (2.0 * kL - s) / (24.0 * kEI); }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(ToString(c.bc)));
    FdScalarBeamProblem p = Scalar(c.bc);
    p.line_loads = {{0.0, 1.0, kQ}};
    const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
    ASSERT_TRUE(fd.ok()) << fd.error;
    EXPECT_NEAR(At(fd, c.v), c.expected, kFdTolerance * c.expected);
    EXPECT_LE(RelativeError(fd, kL, c.shape), kFdTolerance);
  }
}

// Off-centre point loads: the textbook single-load formulas.
TEST(FdBeamReference, OffCentrePointLoads) {
  {
    SCOPED_TRACE("simply supported, load at v = 0.3");
    const double a = 0.3 * kL;
    const double b = kL - a;
    FdScalarBeamProblem p = Scalar(BoundaryCondition::kSimplySupported);
    p.point_loads = {{0.3, kF}};
    EXPECT_LE(RelativeError(SolveFdBeamRichardson(p, kCoarse), kL,
                            [&](double s) {
                              if (s <= a)
                                return kF * b * s * (kL * kL - b * b - s * s) / (6 * kL * kEI);
                              const double x = kL - s;
                              return kF * a * x * (kL * kL - a * a - x * x) / (6 * kL * kEI);
                            }),
              kFdTolerance);
  }
  {
    SCOPED_TRACE("cantilever, load at v = 0.37");
    const double a = 0.37 * kL;
    FdScalarBeamProblem p = Scalar(BoundaryCondition::kCantileverFree);
    p.point_loads = {{0.37, kF}};
    EXPECT_LE(RelativeError(SolveFdBeamRichardson(p, kCoarse), kL,
                            [&](double s) {
                              if (s <= a) return kF * s * s * (3.0 * a - s) / (6.0 * kEI);
                              return kF * a * a * (3.0 * s - a) / (6.0 * kEI);
                            }),
              kFdTolerance);
  }
}

// Patch loads, through reciprocity: the tip deflection of a cantilever under q on [a, b] is
// the integral of q times the tip-load influence line t^2 (3L - t)/(6EI); the centre
// deflection of a simply supported wire uses t (3L^2 - 4t^2)/(48EI) for t <= L/2.
TEST(FdBeamReference, PatchLoads) {
  {
    SCOPED_TRACE("cantilever, q on [0.23, 0.61]");
    FdScalarBeamProblem p = Scalar(BoundaryCondition::kCantileverFree);
    p.line_loads = {{0.23, 0.61, kQ}};
    const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
    ASSERT_TRUE(fd.ok()) << fd.error;
    auto primitive = [](double t) { return kL * t * t * t / 2.0 - t * t * t * t / 8.0; };
    const double tip = kQ * (primitive(0.61 * kL) - primitive(0.23 * kL)) / (3.0 * kEI);
    EXPECT_NEAR(At(fd, 1.0), tip, kFdTolerance * tip);
  }
  {
    SCOPED_TRACE("simply supported, q on [0.1, 0.4]");
    FdScalarBeamProblem p = Scalar(BoundaryCondition::kSimplySupported);
    p.line_loads = {{0.1, 0.4, kQ}};
    const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
    ASSERT_TRUE(fd.ok()) << fd.error;
    auto primitive = [](double t) { return 1.5 * kL * kL * t * t - t * t * t * t; };
    const double centre = kQ * (primitive(0.4 * kL) - primitive(0.1 * kL)) / (48.0 * kEI);
    EXPECT_NEAR(At(fd, 0.5), centre, kFdTolerance * centre);
  }
}

// Triangular loads (textbook beam tables, w the peak load per length): a cantilever under a
// load rising to the tip, y = w x^2 (20 L^3 - 10 L^2 x + x^3) / (120 L EI), tip 11 w L^4 /
// 120 EI, or falling to it, y = w x^2 (10 L^3 - 10 L^2 x + 5 L x^2 - x^3) / (120 L EI), tip
// w L^4 / 30 EI; a simply supported wire, y = w x (7 L^4 - 10 L^2 x^2 + 3 x^4) / (360 L EI),
// 5 w L^4 / 768 EI at midspan. The reference's nodal error for linear loads is still even in h.
TEST(FdBeamReference, TriangularLoads) {
  const double l4 = kQ * kL * kL * kL * kL / kEI;
  {
    SCOPED_TRACE("cantilever, rising to the tip");
    FdScalarBeamProblem p = Scalar(BoundaryCondition::kCantileverFree);
    p.linear_line_loads = {{0.0, 1.0, 0.0, kQ}};
    const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
    ASSERT_TRUE(fd.ok()) << fd.error;
    EXPECT_NEAR(At(fd, 1.0), 11.0 * l4 / 120.0, kFdTolerance * l4);
    EXPECT_LE(RelativeError(fd, kL,
                            [](double x) {
                              return kQ * x * x *
                                     (20 * kL * kL * kL - 10 * kL * kL * x + x * x * x) /
                                     (120 * kL * kEI);
                            }),
              kFdTolerance);
  }
  {
    SCOPED_TRACE("cantilever, falling to the tip");
    FdScalarBeamProblem p = Scalar(BoundaryCondition::kCantileverFree);
    p.linear_line_loads = {{0.0, 1.0, kQ, 0.0}};
    const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
    ASSERT_TRUE(fd.ok()) << fd.error;
    EXPECT_NEAR(At(fd, 1.0), l4 / 30.0, kFdTolerance * l4);
    EXPECT_LE(
        RelativeError(fd, kL,
                      [](double x) {
                        return kQ * x * x *
                               (10 * kL * kL * kL - 10 * kL * kL * x + 5 * kL * x * x - x * x * x) /
                               (120 * kL * kEI);
                      }),
        kFdTolerance);
  }
  {
    SCOPED_TRACE("simply supported, rising");
    FdScalarBeamProblem p = Scalar(BoundaryCondition::kSimplySupported);
    p.linear_line_loads = {{0.0, 1.0, 0.0, kQ}};
    const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
    ASSERT_TRUE(fd.ok()) << fd.error;
    EXPECT_NEAR(At(fd, 0.5), 5.0 * l4 / 768.0, kFdTolerance * l4);
    EXPECT_LE(
        RelativeError(fd, kL,
                      [](double x) {
                        return kQ * x *
                               (7 * kL * kL * kL * kL - 10 * kL * kL * x * x + 3 * x * x * x * x) /
                               (360 * kL * kEI);
                      }),
        kFdTolerance);
  }
  {
    // A partial ramp through reciprocity: the cantilever's tip deflection under r (x - a) on
    // [a, b] is the integral of r (x - a) x^2 (3L - x) / 6EI over [a, b].
    SCOPED_TRACE("cantilever, ramp on [0.2, 0.7]");
    FdScalarBeamProblem p = Scalar(BoundaryCondition::kCantileverFree);
    p.linear_line_loads = {{0.2, 0.7, 0.0, kQ}};
    const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
    ASSERT_TRUE(fd.ok()) << fd.error;
    const double a = 0.2 * kL, b = 0.7 * kL, r = kQ / (b - a);
    // Antiderivative of (x - a) x^2 (3L - x) = -x^4 + (3L + a) x^3 - 3 a L x^2.
    auto primitive = [&](double x) {
      return -x * x * x * x * x / 5.0 + (3 * kL + a) * x * x * x * x / 4.0 - a * kL * x * x * x;
    };
    const double tip = r * (primitive(b) - primitive(a)) / (6.0 * kEI);
    EXPECT_NEAR(At(fd, 1.0), tip, kFdTolerance * tip);
  }
}

// End displacements alone: a straight line (simply supported), the Hermite cubic (clamped),
// a rigid translation (cantilevers, which ignore X1).
TEST(FdBeamReference, EndDisplacements) {
  const double x0 = 0.004;
  const double x1 = -0.007;
  for (BoundaryCondition bc :
       {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped,
        BoundaryCondition::kCantileverFree, BoundaryCondition::kCantileverGuided}) {
    SCOPED_TRACE(std::string(ToString(bc)));
    FdScalarBeamProblem p = Scalar(bc);
    p.start_displacement = x0;
    p.end_displacement = x1;
    EXPECT_LE(RelativeError(SolveFdBeamRichardson(p, kCoarse), kL,
                            [&](double s) {
                              const double v = s / kL;
                              switch (bc) {
                                case BoundaryCondition::kSimplySupported:
                                  return x0 + (x1 - x0) * v;
                                case BoundaryCondition::kClamped:
                                  return x0 + (x1 - x0) * v * v * (3.0 - 2.0 * v);
                                default:
                                  return x0;
                              }
                            }),
              kFdTolerance);
  }
}

// A single solve converges at second order, which is what the extrapolation assumes.
TEST(FdBeamReference, SingleSolveIsSecondOrder) {
  FdScalarBeamProblem p = Scalar(BoundaryCondition::kCantileverFree);
  p.point_loads = {{0.3, kF}};
  p.line_loads = {{0.5, 0.8, kQ}};
  const FdBeamSolution exact = SolveFdBeamRichardson(p, kCoarse);
  ASSERT_TRUE(exact.ok()) << exact.error;
  double previous = 0.0;
  for (int n : {100, 200, 400, 800}) {
    const FdBeamSolution fd = SolveFdBeam(p, n);
    ASSERT_TRUE(fd.ok()) << fd.error;
    double err = 0.0;
    for (int k = 0; k <= kCoarse; ++k) {
      err = std::max(err, std::abs(fd.scalar[k * (n / kCoarse)] - exact.scalar[k]));
    }
    if (previous > 0.0) {
      EXPECT_NEAR(previous / err, 4.0, 0.01) << "n = " << n;
    }
    previous = err;
  }
}

// 3D loads are solved per component with one matrix: the same as three scalar solves.
TEST(FdBeamReference, ComponentsAreIndependent) {
  const std::vector<PointLoad> points = {{0.2, Vec3(1.0, -2.0, 3.0)}, {0.75, Vec3(-4.0, 0.5, 0.0)}};
  const std::vector<LineLoad> lines = {{0.1, 0.6, Vec3(2.0, 3.0, -1.0)}};
  FdBeamProblem p;
  p.boundary = BoundaryCondition::kCantileverGuided;
  p.length = kL;
  p.bending_stiffness = kEI;
  p.start_displacement = Vec3(0.001, 0.002, -0.003);
  p.tip_force = Vec3(5.0, -6.0, 7.0);
  p.point_loads = points;
  p.line_loads = lines;
  const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
  ASSERT_TRUE(fd.ok()) << fd.error;
  ASSERT_EQ(fd.displacement.size(), static_cast<size_t>(kCoarse + 1));
  for (int c = 0; c < 3; ++c) {
    FdScalarBeamProblem s = Scalar(p.boundary);
    s.start_displacement = p.start_displacement[c];
    s.tip_force = p.tip_force[c];
    for (const PointLoad& l : points) s.point_loads.push_back({l.at, l.force[c]});
    for (const LineLoad& l : lines) s.line_loads.push_back({l.from, l.to, l.force_per_length[c]});
    const FdBeamSolution one = SolveFdBeamRichardson(s, kCoarse);
    ASSERT_TRUE(one.ok()) << one.error;
    for (int k = 0; k <= kCoarse; ++k) {
      EXPECT_NEAR(fd.displacement[k][c], one.scalar[k], 1e-14 * std::abs(one.scalar[k]) + 1e-300);
    }
  }
}

// Degenerate loads: on a prescribed node the support takes them; on a cantilever's end node a
// point load is a tip force.
TEST(FdBeamReference, LoadsAtTheEnds) {
  for (BoundaryCondition bc : {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped}) {
    FdScalarBeamProblem p = Scalar(bc);
    p.point_loads = {{0.0, kF}, {1.0, -kF}};
    const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
    ASSERT_TRUE(fd.ok()) << fd.error;
    for (double x : fd.scalar) EXPECT_EQ(x, 0.0);
  }
  FdScalarBeamProblem load = Scalar(BoundaryCondition::kCantileverFree);
  load.point_loads = {{1.0, kF}};
  FdScalarBeamProblem tip = Scalar(BoundaryCondition::kCantileverFree);
  tip.tip_force = kF;
  const FdBeamSolution a = SolveFdBeamRichardson(load, kCoarse);
  const FdBeamSolution b = SolveFdBeamRichardson(tip, kCoarse);
  ASSERT_TRUE(a.ok() && b.ok());
  for (int k = 0; k <= kCoarse; ++k) EXPECT_DOUBLE_EQ(a.scalar[k], b.scalar[k]);
}

TEST(FdBeamReference, RefusesLoadsOffTheGrid) {
  FdScalarBeamProblem p = Scalar(BoundaryCondition::kSimplySupported);
  p.point_loads = {{0.305, kF}};
  EXPECT_FALSE(SolveFdBeamRichardson(p, kCoarse).ok());
  p.point_loads.clear();
  p.line_loads = {{0.1, 0.1234, kQ}};
  EXPECT_FALSE(SolveFdBeamRichardson(p, kCoarse).ok());
  p.line_loads = {{0.4, 0.4, kQ}};
  EXPECT_FALSE(SolveFdBeamRichardson(p, kCoarse).ok());
  p.line_loads = {{0.4, 0.5, kQ}};
  EXPECT_TRUE(SolveFdBeamRichardson(p, kCoarse).ok());
}

// ------------------------------------------------------------------------------------------
// BendingJob (exact mode) against the reference.

struct LoadSet {
  std::string name;
  double length = 1.0;
  double ei = 1.0;
  Vec3 x0 = Vec3::Zero();
  Vec3 x1 = Vec3::Zero();
  Vec3 tip = Vec3::Zero();
  std::vector<PointLoad> points;
  std::vector<LineLoad> lines;
  std::vector<LinearLineLoad> linear;
};

std::string Describe(const LoadSet& s) {
  std::ostringstream out;
  out.precision(17);
  out << s.name << ": L = " << s.length << ", EI = " << s.ei << ", X0 = " << s.x0.transpose()
      << ", X1 = " << s.x1.transpose() << ", tip = " << s.tip.transpose();
  for (const PointLoad& p : s.points) out << "; P(" << p.at << ") = " << p.force.transpose();
  for (const LineLoad& l : s.lines) {
    out << "; q[" << l.from << ", " << l.to << "] = " << l.force_per_length.transpose();
  }
  for (const LinearLineLoad& l : s.linear) {
    out << "; q[" << l.from << ", " << l.to << "] = " << l.start_force_per_length.transpose()
        << " -> " << l.end_force_per_length.transpose();
  }
  return out.str();
}

LoadSet RandomLoadSet(BoundaryCondition bc, std::mt19937* rng, int index) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Draws in a fixed order (function arguments are evaluated in an unspecified order).
  auto vec = [&](double scale) {
    const double x = unit(*rng);
    const double y = unit(*rng);
    const double z = unit(*rng);
    return Vec3(scale * x, scale * y, scale * z);
  };
  LoadSet s;
  s.name = std::string(ToString(bc)) + " #" + std::to_string(index);
  s.length = std::uniform_real_distribution<double>(0.5, 3.0)(*rng);
  s.ei = std::pow(10.0, std::uniform_real_distribution<double>(0.0, 3.0)(*rng));  // [1, 1000]
  s.x0 = vec(0.010);                                                              // up to 10 mm
  s.x1 = vec(0.010);  // given to cantilevers too: they must ignore it
  if (IsCantilever(bc)) s.tip = vec(100.0);
  const int points = std::uniform_int_distribution<int>(1, 5)(*rng);
  for (int i = 0; i < points; ++i) {
    const int k = std::uniform_int_distribution<int>(1, 99)(*rng);
    s.points.push_back({k / 100.0, vec(100.0)});
  }
  const int lines = std::uniform_int_distribution<int>(0, 2)(*rng);
  for (int i = 0; i < lines; ++i) {
    const int a = std::uniform_int_distribution<int>(0, 99)(*rng);
    const int b = std::uniform_int_distribution<int>(a + 1, 100)(*rng);
    s.lines.push_back({a / 100.0, b / 100.0, vec(100.0)});
  }
  return s;
}

// Runs BendingJob at the coarse nodes and the reference; returns
// max |difference| / max |X_reference| over nodes and components.
double CompareWithReference(BoundaryCondition bc, const LoadSet& s) {
  std::vector<double> samples(kCoarse + 1);
  for (int k = 0; k <= kCoarse; ++k) samples[k] = k / static_cast<double>(kCoarse);
  std::vector<Vec3> x(samples.size(), Vec3::Zero());
  BendingJob job;
  job.boundary = bc;
  job.mode = BendingMode::kExact;
  job.length = s.length;
  job.bending_stiffness = s.ei;
  job.start_displacement = s.x0;
  job.end_displacement = s.x1;
  job.tip_force = s.tip;
  job.point_loads = s.points;
  job.line_loads = s.lines;
  job.linear_line_loads = s.linear;
  job.samples = samples;
  job.displacement = x;
  const Status status = job.Run();
  EXPECT_TRUE(status.ok()) << ToString(status);
  if (!status.ok()) return 1.0;

  FdBeamProblem p;
  p.boundary = bc;
  p.length = s.length;
  p.bending_stiffness = s.ei;
  p.start_displacement = s.x0;
  p.end_displacement = s.x1;
  p.tip_force = s.tip;
  p.point_loads = s.points;
  p.line_loads = s.lines;
  p.linear_line_loads = s.linear;
  const FdBeamSolution fd = SolveFdBeamRichardson(p, kCoarse);
  EXPECT_TRUE(fd.ok()) << fd.error;
  if (!fd.ok()) return 1.0;

  double diff = 0.0;
  double scale = 0.0;
  int worst = 0;
  for (int k = 0; k <= kCoarse; ++k) {
    const double d = (x[k] - fd.displacement[k]).cwiseAbs().maxCoeff();
    if (d > diff) {
      diff = d;
      worst = k;
    }
    scale = std::max(scale, fd.displacement[k].cwiseAbs().maxCoeff());
  }
  const double relative = diff / scale;
  EXPECT_LE(relative, kAgreement) << "worst at v = " << samples[worst] << ": job "
                                  << x[worst].transpose() << ", reference "
                                  << fd.displacement[worst].transpose();
  return relative;
}

void CheckRandomLoadSets(BoundaryCondition bc, std::uint32_t seed) {
  std::mt19937 rng(seed);
  double worst = 0.0;
  for (int i = 0; i < 25; ++i) {
    const LoadSet s = RandomLoadSet(bc, &rng, i);
    SCOPED_TRACE(Describe(s));
    worst = std::max(worst, CompareWithReference(bc, s));
  }
  std::ostringstream text;
  text << worst;
  ::testing::Test::RecordProperty("worst_relative_difference", text.str());
}

TEST(BendingReference, SimplySupportedRandomLoadsMatchFiniteDifferences) {
  CheckRandomLoadSets(BoundaryCondition::kSimplySupported, 1001u);
}

TEST(BendingReference, ClampedRandomLoadsMatchFiniteDifferences) {
  CheckRandomLoadSets(BoundaryCondition::kClamped, 2002u);
}

TEST(BendingReference, CantileverFreeRandomLoadsMatchFiniteDifferences) {
  CheckRandomLoadSets(BoundaryCondition::kCantileverFree, 3003u);
}

TEST(BendingReference, CantileverGuidedRandomLoadsMatchFiniteDifferences) {
  CheckRandomLoadSets(BoundaryCondition::kCantileverGuided, 4004u);
}

// Loads next to and on the ends, line loads over the whole wire and touching either end.
TEST(BendingReference, LoadsAtAndNearTheEndsMatchFiniteDifferences) {
  for (BoundaryCondition bc :
       {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped,
        BoundaryCondition::kCantileverFree, BoundaryCondition::kCantileverGuided}) {
    LoadSet s;
    s.name = std::string(ToString(bc)) + " ends";
    s.length = 1.7;
    s.ei = 35.0;
    s.x0 = Vec3(0.002, -0.001, 0.0);
    s.x1 = Vec3(-0.003, 0.0, 0.004);
    if (IsCantilever(bc)) s.tip = Vec3(3.0, -8.0, 1.0);
    s.points = {{0.0, Vec3(50.0, 50.0, 50.0)},
                {0.01, Vec3(-20.0, 10.0, 5.0)},
                {0.99, Vec3(30.0, -40.0, 15.0)},
                {1.0, Vec3(-25.0, 60.0, -10.0)}};
    s.lines = {{0.0, 1.0, Vec3(4.0, -3.0, 2.0)},
               {0.0, 0.01, Vec3(-50.0, 20.0, 70.0)},
               {0.99, 1.0, Vec3(80.0, -30.0, 10.0)}};
    SCOPED_TRACE(Describe(s));
    CompareWithReference(bc, s);
  }
}

// Linearly varying loads on every family: a partial trapezoid (the task's case), ramps touching
// either end, a full-span triangle, with end displacements and tip forces, then random sets of
// trapezoids and point loads.
TEST(BendingReference, LinearLoadsOnEveryFamilyMatchFiniteDifferences) {
  double worst = 0.0;
  for (BoundaryCondition bc :
       {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped,
        BoundaryCondition::kCantileverFree, BoundaryCondition::kCantileverGuided}) {
    {
      LoadSet s;
      s.name = std::string(ToString(bc)) + " partial trapezoid";
      s.length = 2.1;
      s.ei = 55.0;
      s.linear = {{0.23, 0.71, Vec3(30.0, -12.0, 5.0), Vec3(-8.0, 40.0, 20.0)}};
      SCOPED_TRACE(Describe(s));
      worst = std::max(worst, CompareWithReference(bc, s));
    }
    {
      LoadSet s;
      s.name = std::string(ToString(bc)) + " ends";
      s.length = 1.7;
      s.ei = 35.0;
      s.x0 = Vec3(0.002, -0.001, 0.0);
      s.x1 = Vec3(-0.003, 0.0, 0.004);
      if (IsCantilever(bc)) s.tip = Vec3(3.0, -8.0, 1.0);
      s.points = {{0.37, Vec3(-20.0, 10.0, 5.0)}};
      s.lines = {{0.1, 0.3, Vec3(4.0, -3.0, 2.0)}};
      s.linear = {{0.0, 1.0, Vec3::Zero(), Vec3(-10.0, 25.0, 6.0)},
                  {0.0, 0.15, Vec3(50.0, 0.0, -20.0), Vec3(-5.0, 10.0, 0.0)},
                  {0.85, 1.0, Vec3(0.0, -30.0, 8.0), Vec3(60.0, 15.0, -40.0)}};
      SCOPED_TRACE(Describe(s));
      worst = std::max(worst, CompareWithReference(bc, s));
    }
    std::mt19937 rng(5005u + static_cast<std::uint32_t>(bc));
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto vec = [&](double scale) {
      const double x = unit(rng);
      const double y = unit(rng);
      const double z = unit(rng);
      return Vec3(scale * x, scale * y, scale * z);
    };
    for (int i = 0; i < 10; ++i) {
      LoadSet s;
      s.name = std::string(ToString(bc)) + " random #" + std::to_string(i);
      s.length = std::uniform_real_distribution<double>(0.5, 3.0)(rng);
      s.ei = std::pow(10.0, std::uniform_real_distribution<double>(0.0, 3.0)(rng));
      s.x0 = vec(0.010);
      s.x1 = vec(0.010);
      if (IsCantilever(bc)) s.tip = vec(100.0);
      s.points.push_back({std::uniform_int_distribution<int>(1, 99)(rng) / 100.0, vec(100.0)});
      const int count = std::uniform_int_distribution<int>(1, 3)(rng);
      for (int k = 0; k < count; ++k) {
        const int a = std::uniform_int_distribution<int>(0, 99)(rng);
        const int b = std::uniform_int_distribution<int>(a + 1, 100)(rng);
        const Vec3 start = vec(100.0);
        s.linear.push_back({a / 100.0, b / 100.0, start, vec(100.0)});
      }
      SCOPED_TRACE(Describe(s));
      worst = std::max(worst, CompareWithReference(bc, s));
    }
  }
  std::printf("[measure] linear loads vs finite differences: worst %.1e of max |X|\n", worst);
  std::ostringstream text;
  text << worst;
  ::testing::Test::RecordProperty("worst_relative_difference", text.str());
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
