// The paper's series mode (Eqs. 10-17): end conditions hold for every N, the series agrees with
// the exact solution, and it converges at the rates of PHYSICS.md (N^-3 for simply supported
// and clamped wires, N^-1 for cantilevers).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "wirerig/runtime/bending_job.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr std::array kFamilies = {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped,
                                  BoundaryCondition::kCantileverFree,
                                  BoundaryCondition::kCantileverGuided};

struct Evaluation {
  std::vector<Vec3> x, slope, curvature;
};

Evaluation Evaluate(BoundaryCondition bc, BendingMode mode, int terms,
                    std::span<const PointLoad> loads, std::span<const LineLoad> line_loads,
                    std::span<const double> samples, Vec3 tip = Vec3::Zero()) {
  Evaluation e{std::vector<Vec3>(samples.size()), std::vector<Vec3>(samples.size()),
               std::vector<Vec3>(samples.size())};
  BendingJob job;
  job.boundary = bc;
  job.mode = mode;
  job.series_terms = terms;
  job.length = 1.0;
  job.bending_stiffness = 1.0;
  job.tip_force = tip;
  job.start_displacement = Vec3(0.0, 0.01, 0.0);
  if (!IsCantilever(bc)) job.end_displacement = Vec3(0.0, -0.02, 0.0);
  job.point_loads = loads;
  job.line_loads = line_loads;
  job.samples = samples;
  job.displacement = e.x;
  job.slope = e.slope;
  job.curvature = e.curvature;
  const Status status = job.Run();
  EXPECT_TRUE(status.ok()) << ToString(status);
  return e;
}

// 4001 uniform samples plus the load points (PHYSICS.md section 2's error measure).
std::vector<double> ErrorSamples(std::span<const PointLoad> loads) {
  std::vector<double> v;
  for (int i = 0; i <= 4000; ++i) v.push_back(i / 4000.0);
  for (const PointLoad& p : loads) v.push_back(p.at);
  return v;
}

// max |X_series - X_exact| / max |X_exact - X_homogeneous|, displacement only.
double RelativeSeriesError(BoundaryCondition bc, int terms, std::span<const PointLoad> loads) {
  const std::vector<double> v = ErrorSamples(loads);
  const Evaluation exact = Evaluate(bc, BendingMode::kExact, 0, loads, {}, v);
  const Evaluation series = Evaluate(bc, BendingMode::kSeries, terms, loads, {}, v);
  const Evaluation unloaded = Evaluate(bc, BendingMode::kExact, 0, {}, {}, v);
  double err = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    err = std::max(err, (series.x[i] - exact.x[i]).norm());
    peak = std::max(peak, (exact.x[i] - unloaded.x[i]).norm());
  }
  return err / peak;
}

TEST(BendingSeries, EndConditionsHoldForAnyNumberOfTerms) {
  const std::array<PointLoad, 2> loads{{{0.3, Vec3(0, -1, 0)}, {0.7, Vec3(0, 0.4, 0.2)}}};
  const std::array<double, 2> ends{0.0, 1.0};
  const Vec3 tip(0.0, 0.3, -0.1);
  for (BoundaryCondition bc : kFamilies) {
    for (int terms : {1, 5, 20}) {
      SCOPED_TRACE(std::string(ToString(bc)) + " N=" + std::to_string(terms));
      const Vec3 t = IsCantilever(bc) ? tip : Vec3::Zero();
      const Evaluation e = Evaluate(bc, BendingMode::kSeries, terms, loads, {}, ends, t);
      EXPECT_LT((e.x[0] - Vec3(0, 0.01, 0)).norm(), 1e-12);
      if (bc == BoundaryCondition::kSimplySupported) {
        EXPECT_LT(e.curvature[0].norm(), 1e-10);
        EXPECT_LT((e.x[1] - Vec3(0, -0.02, 0)).norm(), 1e-12);
        EXPECT_LT(e.curvature[1].norm(), 1e-10);
      } else {
        EXPECT_LT(e.slope[0].norm(), 1e-12);
      }
      if (bc == BoundaryCondition::kClamped) {
        EXPECT_LT((e.x[1] - Vec3(0, -0.02, 0)).norm(), 1e-12);
        EXPECT_LT(e.slope[1].norm(), 1e-12);
      }
      if (bc == BoundaryCondition::kCantileverFree) {
        EXPECT_LT(e.curvature[1].norm(), 1e-10);
      }
      if (bc == BoundaryCondition::kCantileverGuided) {
        EXPECT_LT(e.slope[1].norm(), 1e-12);
      }
    }
  }
}

TEST(BendingSeries, ConvergesAtThePublishedRates) {
  // One load P = 1 at v = 0.3 (PHYSICS.md section 2, first table).
  const std::array<PointLoad, 1> loads{{{0.3, Vec3(0, 1, 0)}}};
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const double e100 = RelativeSeriesError(bc, 100, loads);
    const double e1000 = RelativeSeriesError(bc, 1000, loads);
    const double rate = std::log10(e100 / e1000);
    if (IsCantilever(bc)) {
      EXPECT_NEAR(rate, 1.0, 0.05);
    } else {
      EXPECT_NEAR(rate, 3.0, 0.1);
    }
    // The table's values at N = 100 (within 5%): SS 2.05e-7, CC 3.56e-6, CF 1.33e-2, CG 7.51e-3.
    const double expected_e100[] = {2.05e-7, 3.56e-6, 1.33e-2, 7.51e-3};
    EXPECT_NEAR(e100, expected_e100[static_cast<int>(bc)],
                0.05 * expected_e100[static_cast<int>(bc)]);
  }
}

TEST(BendingSeries, LineLoadSeriesConvergesToTheExactPatchSolution) {
  const std::array<LineLoad, 1> patch{{{0.2, 0.6, Vec3(0, -3, 0)}}};
  const std::vector<double> v = {0.1, 0.4, 0.5, 0.8};
  for (BoundaryCondition bc : {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped}) {
    SCOPED_TRACE(ToString(bc));
    const Evaluation exact = Evaluate(bc, BendingMode::kExact, 0, {}, patch, v);
    const Evaluation series = Evaluate(bc, BendingMode::kSeries, 2000, {}, patch, v);
    for (std::size_t i = 0; i < v.size(); ++i)
      EXPECT_LT((series.x[i] - exact.x[i]).norm(), 1e-9) << "v=" << v[i];
  }
}

// A linearly varying load's series (its exact sine coefficients) converges to the exact
// Macaulay solution on every family: max |X_series - X_exact| / max |X_exact - X_homogeneous|
// over 4001 samples falls with N (as N^-1 only for the cantilevers, PHYSICS.md section 2).
TEST(BendingSeries, LinearLoadSeriesConvergesToTheExactSolution) {
  std::vector<double> v;
  for (int i = 0; i <= 4000; ++i) v.push_back(i / 4000.0);
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const auto error = [&](int terms) {
      std::array<Evaluation, 3> e;
      const std::array<LinearLineLoad, 2> loads{
          {{0.2, 0.7, Vec3(0, -3, 1), Vec3(0, 2, 0.5)}, {0.0, 1.0, Vec3::Zero(), Vec3(0, 0, -1)}}};
      const std::array<BendingMode, 3> modes = {BendingMode::kExact, BendingMode::kSeries,
                                                BendingMode::kExact};
      for (int k = 0; k < 3; ++k) {
        e[k] = {std::vector<Vec3>(v.size()), std::vector<Vec3>(v.size()),
                std::vector<Vec3>(v.size())};
        BendingJob job;
        job.boundary = bc;
        job.mode = modes[k];
        job.series_terms = terms;
        job.length = 1.0;
        job.bending_stiffness = 1.0;
        job.start_displacement = Vec3(0.0, 0.01, 0.0);
        if (!IsCantilever(bc)) job.end_displacement = Vec3(0.0, -0.02, 0.0);
        if (k < 2) job.linear_line_loads = loads;
        job.samples = v;
        job.displacement = e[k].x;
        EXPECT_TRUE(job.Run().ok());
      }
      double err = 0.0, peak = 0.0;
      for (std::size_t i = 0; i < v.size(); ++i) {
        err = std::max(err, (e[1].x[i] - e[0].x[i]).norm());
        peak = std::max(peak, (e[0].x[i] - e[2].x[i]).norm());
      }
      return err / peak;
    };
    const double e10 = error(10), e100 = error(100), e1000 = error(1000);
    std::printf("[measure] %s linear load series error: N=10 %.2e, N=100 %.2e, N=1000 %.2e\n",
                std::string(ToString(bc)).c_str(), e10, e100, e1000);
    EXPECT_LT(e100, e10);
    EXPECT_LT(e1000, e100);
    // Measured: SS 5.8e-9 -> 5.5e-13 (N^-4: the load's sine coefficients fall as 1/n), CC
    // 1.1e-6 -> 1.1e-9 (N^-3), the cantilevers 1.1e-2 -> 1.1e-3 and 9.7e-3 -> 9.8e-4 (N^-1).
    const double rate = std::log10(e100 / e1000);
    if (IsCantilever(bc)) {
      EXPECT_NEAR(rate, 1.0, 0.05);
      EXPECT_LT(e1000, 2e-3);
    } else {
      EXPECT_GT(rate, 2.9);
      EXPECT_LT(e1000, bc == BoundaryCondition::kClamped ? 2e-9 : 1e-12);
    }
  }
}

TEST(BendingSeries, SlopeAndCurvatureAreDerivativesOfTheSeries) {
  const std::array<PointLoad, 1> loads{{{0.3, Vec3(0, -1, 0.5)}}};
  const double v = 0.55, h = 1e-5;
  const std::array<double, 3> samples{v - h, v, v + h};
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    const Evaluation e = Evaluate(bc, BendingMode::kSeries, 50, loads, {}, samples);
    EXPECT_LT(((e.x[2] - e.x[0]) / (2 * h) - e.slope[1]).norm(), 1e-7);
    EXPECT_LT(((e.x[2] - 2.0 * e.x[1] + e.x[0]) / (h * h) - e.curvature[1]).norm(), 1e-4);
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
