// PolygonCrossesItself against two references: the sweep profile_curves.cpp used before
// (boxes sorted by lower x as 40-byte records, then the same crossing test), which it must match
// exactly on every polygon, and all pairs of edges (O(n^2)), which it must match where no
// orientation is within rounding of zero (random real coordinates). Polygons: star-shaped loops
// like the profiles rays give, random ones, grid-snapped ones with collinear and repeated
// points, open and closed, 0 to 300 vertices.
#include "wirerig/rig/polygon_crossing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

double Orient(double px, double py, double qx, double qy, double rx, double ry) {
  return (qx - px) * (ry - py) - (qy - py) * (rx - px);
}

bool Straddles(double s0, double s1) { return (s0 > 0.0 && s1 < 0.0) || (s0 < 0.0 && s1 > 0.0); }

// Edges i < j properly cross (the predicate both references and the code under test use).
bool Crosses(const std::vector<double>& x, const std::vector<double>& y, bool closed, std::size_t i,
             std::size_t j) {
  const std::size_t n = x.size() - 1;  // x[n] repeats x[0]
  if (j < i + 2 || (closed && i == 0 && j == n - 1)) return false;
  const double ax = x[i], ay = y[i], bx = x[i + 1], by = y[i + 1];
  if (!Straddles(Orient(ax, ay, bx, by, x[j], y[j]), Orient(ax, ay, bx, by, x[j + 1], y[j + 1])))
    return false;
  const double o3 = Orient(x[j], y[j], x[j + 1], y[j + 1], ax, ay);
  const double o4 = Orient(x[j], y[j], x[j + 1], y[j + 1], bx, by);
  return ((o3 > 0.0) != (o4 > 0.0)) && o3 != 0.0 && o4 != 0.0;
}

// The previous implementation (profile_curves.cpp before 2026-11-29), verbatim but for names.
bool PreviousSweep(std::vector<double> x, std::vector<double> y, bool closed) {
  const std::size_t n = x.size();
  if (n < 4) return false;
  double size = 0.0;
  for (std::size_t i = 0; i < n; ++i) size = std::max({size, std::abs(x[i]), std::abs(y[i])});
  x.push_back(x[0]);
  y.push_back(y[0]);
  struct Box {
    double x0, x1, y0, y1;
    std::uint32_t edge;
  };
  const std::size_t edges = closed ? n : n - 1;
  const double pad = 1e-9 * size;
  std::vector<Box> boxes(edges);
  for (std::size_t i = 0; i < edges; ++i) {
    boxes[i] = {std::min(x[i], x[i + 1]) - pad, std::max(x[i], x[i + 1]) + pad,
                std::min(y[i], y[i + 1]) - pad, std::max(y[i], y[i + 1]) + pad,
                static_cast<std::uint32_t>(i)};
  }
  std::sort(boxes.begin(), boxes.end(), [](const Box& a, const Box& b) {
    return a.x0 < b.x0 || (a.x0 == b.x0 && a.edge < b.edge);
  });
  for (std::size_t p = 0; p < edges; ++p) {
    for (std::size_t q = p + 1; q < edges && boxes[q].x0 <= boxes[p].x1; ++q) {
      if (boxes[q].y0 > boxes[p].y1 || boxes[p].y0 > boxes[q].y1) continue;
      const std::size_t i = std::min(boxes[p].edge, boxes[q].edge);
      const std::size_t j = std::max(boxes[p].edge, boxes[q].edge);
      if (Crosses(x, y, closed, i, j)) return true;
    }
  }
  return false;
}

bool AllPairs(std::vector<double> x, std::vector<double> y, bool closed) {
  const std::size_t n = x.size();
  if (n < 4) return false;
  x.push_back(x[0]);
  y.push_back(y[0]);
  const std::size_t edges = closed ? n : n - 1;
  for (std::size_t i = 0; i < edges; ++i)
    for (std::size_t j = i + 2; j < edges; ++j)
      if (Crosses(x, y, closed, i, j)) return true;
  return false;
}

struct Random {
  std::uint64_t state;
  double Uniform() {  // in [0, 1)
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) * 0x1p-53;
  }
};

TEST(PolygonCrossing, KnownShapes) {
  PolygonCrossingScratch scratch;
  const std::vector<double> sx = {0, 1, 1, 0}, sy = {0, 0, 1, 1};  // a square
  EXPECT_FALSE(PolygonCrossesItself(sx, sy, true, scratch));
  EXPECT_FALSE(PolygonCrossesItself(sx, sy, false, scratch));
  const std::vector<double> bx = {0, 1, 0, 1}, by = {0, 1, 1, 0};  // a bow tie
  EXPECT_TRUE(PolygonCrossesItself(bx, by, true, scratch));
  EXPECT_TRUE(PolygonCrossesItself(bx, by, false, scratch));
  // Only the closing edge (2, 1.5) -> (0, 0) crosses an edge, (1, 2) -> (2, 0).
  const std::vector<double> ox = {0, 1, 2, 2}, oy = {0, 2, 0, 1.5};
  EXPECT_TRUE(PolygonCrossesItself(ox, oy, true, scratch));
  EXPECT_FALSE(PolygonCrossesItself(ox, oy, false, scratch));
  EXPECT_FALSE(PolygonCrossesItself(std::vector<double>{0, 1, 2}, std::vector<double>{0, 1, 0},
                                    true, scratch));
  EXPECT_FALSE(PolygonCrossesItself({}, {}, true, scratch));
}

// Rays around the centre of a square hit its sides in collinear runs: the orientations of
// non-adjacent edges on one side are rounding noise, yet the loop is star-shaped and simple.
// Wound twice it crosses; a loop whose centre lies outside it is left to the sweep.
TEST(PolygonCrossing, RaysAroundTheOriginGiveASimpleLoop) {
  PolygonCrossingScratch scratch;
  for (const double turns : {1.0, 2.0}) {
    for (const std::size_t n : {std::size_t(7), std::size_t(100), std::size_t(257)}) {
      std::vector<double> x(n), y(n);
      for (std::size_t i = 0; i < n; ++i) {
        const double angle = turns * 2.0 * std::numbers::pi * (double(i) + 0.37) / double(n);
        const double c = std::cos(angle), s = std::sin(angle);
        const double t = 0.3 / std::max(std::abs(c), std::abs(s));  // on the square |x|,|y| = 0.3
        x[i] = 1e3 * t * c;  // far from 1: rounding is relative
        y[i] = 1e3 * t * s;
      }
      const bool crosses = turns == 2.0;  // twice round: the turns cross each other
      EXPECT_EQ(PolygonCrossesItself(x, y, true, scratch), crosses) << n << " " << turns;
      std::reverse(x.begin(), x.end());  // clockwise
      std::reverse(y.begin(), y.end());
      EXPECT_EQ(PolygonCrossesItself(x, y, true, scratch), crosses) << n << " " << turns;
      EXPECT_FALSE(PolygonCrossesItself(std::span(x).first(n / 2 + 1),
                                        std::span(y).first(n / 2 + 1), false, scratch));
      for (double& v : x) v += 2e3;  // the origin outside: the sweep finds the crossing
      if (crosses) {
        EXPECT_TRUE(PolygonCrossesItself(x, y, true, scratch)) << n;
      }
    }
  }
}

TEST(PolygonCrossing, MatchesThePreviousSweepAndAllPairs) {
  Random random{31};
  PolygonCrossingScratch scratch;  // reused across sizes, as the profile code does
  int crossing = 0, polygons = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    const int kind = trial % 4;
    const auto n = static_cast<std::size_t>(random.Uniform() * (trial % 50 == 0 ? 300 : 40));
    std::vector<double> x(n), y(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (kind == 0) {  // star-shaped: a ray loop with noisy radii (crosses when noise is large)
        const double angle = 2.0 * std::numbers::pi * double(i) / double(n);
        const double radius = 1.0 + (trial % 8 == 0 ? 3.0 : 0.2) * random.Uniform();
        x[i] = radius * std::cos(angle);
        y[i] = radius * std::sin(angle);
      } else if (kind == 1) {  // random points
        x[i] = random.Uniform() - 0.5;
        y[i] = random.Uniform() - 0.5;
      } else if (kind == 2) {  // a 5 x 5 grid: collinear edges, repeated points, touching
        x[i] = std::floor(5.0 * random.Uniform());
        y[i] = std::floor(5.0 * random.Uniform());
      } else {  // a random walk: long chains, mostly simple
        x[i] = (i > 0 ? x[i - 1] : 0.0) + random.Uniform() - 0.3;
        y[i] = (i > 0 ? y[i - 1] : 0.0) + random.Uniform() - 0.5;
      }
    }
    for (const bool closed : {true, false}) {
      const bool result = PolygonCrossesItself(x, y, closed, scratch);
      ASSERT_EQ(result, PreviousSweep(x, y, closed))
          << "trial " << trial << " n " << n << " closed " << closed;
      if (kind != 2) {
        ASSERT_EQ(result, AllPairs(x, y, closed)) << "trial " << trial << " n " << n;
      }
      crossing += result;
      ++polygons;
    }
  }
  // Both answers occur often.
  EXPECT_GT(crossing, polygons / 5);
  EXPECT_LT(crossing, polygons * 4 / 5);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
