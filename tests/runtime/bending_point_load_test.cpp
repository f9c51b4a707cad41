// BendingJob (kExact) with point loads only, the runtime's piecewise-cubic fast path (up to 16
// loads; bending_segments.cpp), over many random load sets in all four boundary families:
// against the textbook Green's-function formulas of PHYSICS.md section 2 (written out here, one
// load at a time), against the general Macaulay evaluator (the same job with a zero line load
// added, which the fast path does not take), and for independence from the samples' order.
// Load sets include loads at v = 0 and v = 1, coinciding loads and samples at load positions;
// end displacements, tip forces and tip couples are random where the family allows them.
//
// Errors are relative to the deflection scale S = |X0| + |X1| + (L^3/EI)(sum |P| + |F_tip|)
// + L^2 |M_tip| / EI (S/L for slopes, S/L^2 for curvatures). Measured worst: 3.5e-15 against
// the textbook formulas and 1.3e-15 against the general evaluator for clamped wires (whose
// cubic cancels most), 4e-16 and 2e-16 for the other families; the tests ask for 1e-13.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "wirerig/runtime/bending_job.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr std::array kFamilies = {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped,
                                  BoundaryCondition::kCantileverFree,
                                  BoundaryCondition::kCantileverGuided};
constexpr double kTolerance = 1e-13;  // relative to the deflection scale
constexpr int kSetsPerFamily = 400;

// X, dX/ds and d2X/ds2 at the samples.
struct Curve {
  std::vector<Vec3> x, slope, curvature;
  explicit Curve(std::size_t n) : x(n), slope(n), curvature(n) {}
};

struct Problem {
  BoundaryCondition boundary = BoundaryCondition::kClamped;
  double length = 1.0, stiffness = 1.0;
  Vec3 x0 = Vec3::Zero(), x1 = Vec3::Zero(), tip_force = Vec3::Zero(), tip_couple = Vec3::Zero();
  std::vector<PointLoad> loads;
  std::vector<double> samples;

  double Scale() const {
    double load = tip_force.lpNorm<1>();
    for (const PointLoad& p : loads) load += p.force.lpNorm<1>();
    return x0.lpNorm<1>() + x1.lpNorm<1>() + length * length * length / stiffness * load +
           length * length * tip_couple.lpNorm<1>() / stiffness;
  }
};

// Runs the job; with_zero_line_load adds a line load of zero force (no deflection), which
// routes the job to the general evaluator.
Curve RunJob(const Problem& p, bool with_zero_line_load = false) {
  Curve c(p.samples.size());
  const std::array<LineLoad, 1> zero{{{0.25, 0.75, Vec3::Zero()}}};
  BendingJob job;
  job.boundary = p.boundary;
  job.length = p.length;
  job.bending_stiffness = p.stiffness;
  job.start_displacement = p.x0;
  job.end_displacement = p.x1;
  job.tip_force = p.tip_force;
  job.tip_couple = p.tip_couple;
  job.point_loads = p.loads;
  if (with_zero_line_load) job.line_loads = zero;
  job.samples = p.samples;
  job.displacement = c.x;
  job.slope = c.slope;
  job.curvature = c.curvature;
  const Status status = job.Run();
  EXPECT_TRUE(status.ok()) << ToString(status);
  return c;
}

// PHYSICS.md section 2, expanded forms: the Green's function G(v; a) of one unit load at a
// (X = L^3/(6 EI) P G) and its first two derivatives in v.
std::array<double, 3> Green(BoundaryCondition bc, double v, double a) {
  const double w = 1.0 - a, t = std::max(v - a, 0.0);
  double k2 = 0.0, k3 = -1.0, k1 = 0.0;  // G = k1 v + k2 v^2 + k3 v^3 + t^3
  switch (bc) {
    case BoundaryCondition::kSimplySupported:
      k1 = w * (1.0 - w * w), k3 = -w;
      break;
    case BoundaryCondition::kClamped:
      k2 = 3.0 * a * w * w, k3 = -w * w * (1.0 + 2.0 * a);
      break;
    case BoundaryCondition::kCantileverFree:
      k2 = 3.0 * a;
      break;
    case BoundaryCondition::kCantileverGuided:
      k2 = 1.5 * a * (2.0 - a);
      break;
  }
  return {k1 * v + k2 * v * v + k3 * v * v * v + t * t * t,
          k1 + 2.0 * k2 * v + 3.0 * k3 * v * v + 3.0 * t * t, 2.0 * k2 + 6.0 * k3 * v + 6.0 * t};
}

// The textbook solution at v: {X, dX/ds, d2X/ds2}.
std::array<Vec3, 3> Textbook(const Problem& p, double v) {
  const double l = p.length, c = l * l * l / p.stiffness;  // L^3 / EI
  const Vec3 d = p.x1 - p.x0;
  std::array<Vec3, 3> r = {p.x0, Vec3::Zero(), Vec3::Zero()};  // derivatives in v first
  switch (p.boundary) {
    case BoundaryCondition::kSimplySupported:  // X0 + D v
      r[0] += d * v, r[1] += d;
      break;
    case BoundaryCondition::kClamped:  // X0 + D (3 v^2 - 2 v^3)
      r[0] += d * (3 * v * v - 2 * v * v * v), r[1] += d * (6 * v - 6 * v * v);
      r[2] += d * (6 - 12 * v);
      break;
    case BoundaryCondition::kCantileverFree: {  // F L^3 v^2 (3 - v) / 6EI + M L^2 v^2 / 2EI
      const Vec3 m = p.tip_couple * (l * l / p.stiffness);
      r[0] += c * p.tip_force * (v * v * (3 - v) / 6) + m * (v * v / 2);
      r[1] += c * p.tip_force * (v - v * v / 2) + m * v, r[2] += c * p.tip_force * (1 - v) + m;
      break;
    }
    case BoundaryCondition::kCantileverGuided:  // F L^3 v^2 (3 - 2v) / 12EI
      r[0] += c * p.tip_force * (v * v * (3 - 2 * v) / 12);
      r[1] += c * p.tip_force * (v - v * v) / 2, r[2] += c * p.tip_force * (1 - 2 * v) / 2;
      break;
  }
  for (const PointLoad& load : p.loads) {
    const std::array<double, 3> g = Green(p.boundary, v, load.at);
    for (int k = 0; k < 3; ++k) r[k] += (c / 6.0) * g[k] * load.force;
  }
  r[1] /= l, r[2] /= l * l;
  return r;
}

// A random problem of `loads` point loads; positions drawn from a few exact values (the ends,
// a shared position) as well as uniformly, and samples both in order and shuffled.
Problem RandomProblem(BoundaryCondition bc, int loads, std::mt19937* rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 9);
  Problem p;
  p.boundary = bc;
  p.length = 0.1 + 3.0 * unit(*rng);
  p.stiffness = 0.05 + 50.0 * unit(*rng);
  auto vec = [&] { return Vec3(sym(*rng), sym(*rng), sym(*rng)); };
  p.x0 = 0.1 * vec();
  if (!IsCantilever(bc)) p.x1 = 0.1 * vec();
  if (IsCantilever(bc) && pick(*rng) < 7) p.tip_force = 10.0 * vec();
  if (bc == BoundaryCondition::kCantileverFree && pick(*rng) < 5) p.tip_couple = 3.0 * vec();
  const double shared = unit(*rng);
  for (int j = 0; j < loads; ++j) {
    double at = unit(*rng);
    switch (pick(*rng)) {
      case 0:
        at = 0.0;
        break;
      case 1:
        at = 1.0;
        break;
      case 2:
      case 3:
        at = shared;  // coinciding loads
        break;
      default:
        break;
    }
    p.loads.push_back({at, 10.0 * vec()});
  }
  const int grid = 1 + pick(*rng) * 7;
  for (int i = 0; i <= grid; ++i) p.samples.push_back(static_cast<double>(i) / grid);
  for (const PointLoad& load : p.loads) p.samples.push_back(load.at);  // at the load, exactly
  for (int i = 0; i < 8; ++i) p.samples.push_back(unit(*rng));
  if (pick(*rng) < 5) std::shuffle(p.samples.begin(), p.samples.end(), *rng);
  return p;
}

// Max over the samples of the error of X, slope and curvature against `reference`, each
// relative to its scale (S, S/L, S/L^2).
template <typename Reference>
double WorstError(const Problem& p, const Curve& c, Reference reference) {
  const double s = p.Scale(), l = p.length;
  double worst = 0.0;
  for (std::size_t i = 0; i < p.samples.size(); ++i) {
    const std::array<Vec3, 3> r = reference(i);
    worst = std::max({worst, (c.x[i] - r[0]).lpNorm<Eigen::Infinity>() / s,
                      (c.slope[i] - r[1]).lpNorm<Eigen::Infinity>() * l / s,
                      (c.curvature[i] - r[2]).lpNorm<Eigen::Infinity>() * l * l / s});
  }
  return worst;
}

TEST(BendingPointLoads, MatchTextbookGreensFunctionsOverRandomLoadSets) {
  std::mt19937 rng(20261121);
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    // 0 to 16 loads take the fast path; 17 to 24 the general evaluator.
    for (int set = 0; set < kSetsPerFamily; ++set) {
      const Problem p = RandomProblem(bc, set % 25, &rng);
      const Curve c = RunJob(p);
      const double err = WorstError(p, c, [&](std::size_t i) { return Textbook(p, p.samples[i]); });
      EXPECT_LE(err, kTolerance) << "set " << set << " with " << p.loads.size() << " loads";
    }
  }
}

TEST(BendingPointLoads, MatchTheGeneralEvaluator) {
  std::mt19937 rng(7);
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    for (int set = 0; set < kSetsPerFamily; ++set) {
      const Problem p = RandomProblem(bc, set % 17, &rng);
      const Curve fast = RunJob(p), general = RunJob(p, /*with_zero_line_load=*/true);
      const double err = WorstError(p, fast, [&](std::size_t i) {
        return std::array<Vec3, 3>{general.x[i], general.slope[i], general.curvature[i]};
      });
      EXPECT_LE(err, kTolerance) << "set " << set << " with " << p.loads.size() << " loads";
    }
  }
}

TEST(BendingPointLoads, SampleOrderDoesNotChangeAnyValue) {
  std::mt19937 rng(99);
  for (BoundaryCondition bc : kFamilies) {
    SCOPED_TRACE(ToString(bc));
    for (int set = 0; set < 50; ++set) {
      Problem p = RandomProblem(bc, 1 + set % 16, &rng);
      std::sort(p.samples.begin(), p.samples.end());
      const Curve sorted = RunJob(p);
      std::vector<std::size_t> order(p.samples.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::shuffle(order.begin(), order.end(), rng);
      Problem shuffled = p;
      for (std::size_t i = 0; i < order.size(); ++i) shuffled.samples[i] = p.samples[order[i]];
      const Curve c = RunJob(shuffled);
      for (std::size_t i = 0; i < order.size(); ++i) {
        EXPECT_EQ(c.x[i], sorted.x[order[i]]) << "v = " << shuffled.samples[i];
        EXPECT_EQ(c.slope[i], sorted.slope[order[i]]) << "v = " << shuffled.samples[i];
        EXPECT_EQ(c.curvature[i], sorted.curvature[order[i]]) << "v = " << shuffled.samples[i];
      }
    }
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
