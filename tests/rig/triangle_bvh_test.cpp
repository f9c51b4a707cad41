// Tests for TriangleBvh and WindingNumber against independent references: brute-force
// Moller-Trumbore ray casting and plane-projection closest points over every triangle, exact
// hits on an axis-aligned cube, rays aimed at every shared vertex and edge of closed meshes
// (watertightness), the closed-form solid angle of a square, and the interior solid angles of a
// polyhedral cylinder at its vertices, edges and faces.
#include "wirerig/rig/triangle_bvh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "wirerig/procedural/shapes.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kPi = std::numbers::pi;
constexpr double kFar = std::numeric_limits<double>::max();

bool IsFinite(const Vec3& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

// ---- References -------------------------------------------------------------------------

struct RefHit {
  double t;
  std::uint32_t triangle;
};

// Moller-Trumbore (1997), the textbook form; parallel rays (|det| tiny) miss.
std::optional<double> MollerTrumbore(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                                     const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-200) return std::nullopt;
  const Vec3 s = o - a;
  const double u = s.dot(p) / det;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  return e2.dot(q) / det;
}

// All hits with t in (t_min, t_max], sorted by t.
std::vector<RefHit> AllHits(const std::vector<Vec3>& positions,
                            const std::vector<Triangle>& triangles,
                            const std::vector<std::uint32_t>& candidates, const Vec3& o,
                            const Vec3& d, double t_min, double t_max) {
  std::vector<RefHit> hits;
  for (std::uint32_t f : candidates) {
    const Triangle& tri = triangles[f];
    const auto t = MollerTrumbore(o, d, positions[tri[0]], positions[tri[1]], positions[tri[2]]);
    if (t && *t > t_min && *t <= t_max) hits.push_back({*t, f});
  }
  std::sort(hits.begin(), hits.end(), [](const RefHit& x, const RefHit& y) {
    return x.t < y.t || (x.t == y.t && x.triangle < y.triangle);
  });
  return hits;
}

std::vector<std::uint32_t> AllIndices(std::size_t count) {
  std::vector<std::uint32_t> indices(count);
  for (std::size_t i = 0; i < count; ++i) indices[i] = static_cast<std::uint32_t>(i);
  return indices;
}

// Distance from p to the segment ab, by clamped projection.
double SegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Distance from p to the triangle: projection onto its plane if that falls inside (by the signs
// of the three sub-triangle normals), else the nearest edge (always for collinear vertices).
double TriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double nn = n.squaredNorm();
  if (nn > 1e-24 * (b - a).squaredNorm() * (c - a).squaredNorm()) {
    const Vec3 q = p - n * (n.dot(p - a) / nn);
    if ((b - a).cross(q - a).dot(n) >= 0.0 && (c - b).cross(q - b).dot(n) >= 0.0 &&
        (a - c).cross(q - c).dot(n) >= 0.0)
      return (p - q).norm();
  }
  return std::min({SegmentDistance(p, a, b), SegmentDistance(p, b, c), SegmentDistance(p, c, a)});
}

double BruteClosestDistance(const std::vector<Vec3>& positions,
                            const std::vector<Triangle>& triangles,
                            const std::vector<std::uint32_t>& candidates, const Vec3& p) {
  double best = std::numeric_limits<double>::max();
  for (std::uint32_t f : candidates) {
    const Triangle& t = triangles[f];
    best = std::min(best, TriangleDistance(p, positions[t[0]], positions[t[1]], positions[t[2]]));
  }
  return best;
}

// ---- Fixtures -----------------------------------------------------------------------------

struct Soup {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
};

// `count` independent random triangles (edges up to ~0.4) with centres in [-1, 1]^3.
Soup RandomSoup(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> centre(-1.0, 1.0), offset(-0.2, 0.2);
  Soup soup;
  for (int i = 0; i < count; ++i) {
    const Vec3 m(centre(rng), centre(rng), centre(rng));
    const auto first = static_cast<std::uint32_t>(soup.positions.size());
    for (int k = 0; k < 3; ++k)
      soup.positions.push_back(m + Vec3(offset(rng), offset(rng), offset(rng)));
    soup.triangles.push_back({first, first + 1, first + 2});
  }
  return soup;
}

Vec3 RandomUnit(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> z_dist(-1.0, 1.0), phi_dist(0.0, 2.0 * kPi);
  const double z = z_dist(rng), phi = phi_dist(rng), s = std::sqrt(1.0 - z * z);
  return Vec3(s * std::cos(phi), s * std::sin(phi), z);
}

// A point inside the polyhedral torus (R, r): within 0.8 r of the core circle.
Vec3 InsideTorus(std::mt19937_64& rng, double major, double minor) {
  std::uniform_real_distribution<double> angle(0.0, 2.0 * kPi), radius(0.0, 0.8 * minor);
  const double phi = angle(rng), theta = angle(rng), s = radius(rng);
  const double rho = major + s * std::cos(theta);
  return Vec3(rho * std::cos(phi), s * std::sin(theta), rho * std::sin(phi));
}

// Unit cube [0, 1]^3 as 12 outward triangles.
Soup UnitCube() {
  Soup cube;
  for (int i = 0; i < 8; ++i) cube.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const Vec3 centre(0.5, 0.5, 0.5);
  const int quads[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    for (Triangle t : {Triangle{std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])},
                       Triangle{std::uint32_t(q[0]), std::uint32_t(q[2]), std::uint32_t(q[3])}}) {
      const Vec3 &a = cube.positions[t[0]], &b = cube.positions[t[1]], &c = cube.positions[t[2]];
      if ((b - a).cross(c - a).dot((a + b + c) / 3.0 - centre) < 0.0) std::swap(t[1], t[2]);
      cube.triangles.push_back(t);
    }
  }
  return cube;
}

// Checks a BVH hit against the brute-force list of hits in the same window: same nearest t
// (to 1e-12) and the same triangle, or another triangle hit at that same t (a shared edge).
// Returns false (after reporting) on a mismatch.
bool SameAsBruteForce(const std::optional<RayHit>& hit, const std::vector<RefHit>& ref,
                      const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                      const Vec3& o, const Vec3& d) {
  EXPECT_EQ(hit.has_value(), !ref.empty());
  if (!hit || ref.empty()) return hit.has_value() == !ref.empty();
  EXPECT_NEAR(hit->t, ref.front().t, 1e-12);
  bool same_triangle = hit->triangle == ref.front().triangle;
  for (const RefHit& r : ref)
    if (r.triangle == hit->triangle && std::abs(r.t - hit->t) <= 1e-12) same_triangle = true;
  EXPECT_TRUE(same_triangle) << "BVH triangle " << hit->triangle << " not hit at t = " << hit->t;
  // The reported point is on the ray and on the reported triangle, with valid barycentrics.
  EXPECT_LE((hit->point - (o + hit->t * d)).norm(), 1e-9);
  const Triangle& t = triangles[hit->triangle];
  EXPECT_LE(TriangleDistance(hit->point, positions[t[0]], positions[t[1]], positions[t[2]]), 1e-9);
  EXPECT_GE(hit->u, 0.0);
  EXPECT_GE(hit->v, 0.0);
  EXPECT_LE(hit->u + hit->v, 1.0 + 1e-15);
  return std::abs(hit->t - ref.front().t) <= 1e-12 && same_triangle;
}

// ---- Ray casting --------------------------------------------------------------------------

TEST(TriangleBvhTest, EmptyBvhReturnsNothing) {
  const TriangleBvh unbuilt;
  EXPECT_EQ(unbuilt.triangle_count(), 0u);
  EXPECT_FALSE(unbuilt.Raycast(Vec3::Zero(), Vec3::UnitX(), 0.0, kFar));
  EXPECT_FALSE(unbuilt.Closest(Vec3::Zero()));

  const std::vector<Vec3> positions = {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()};
  const std::vector<Triangle> none;
  const TriangleBvh empty = TriangleBvh::Build(positions, none);
  EXPECT_EQ(empty.triangle_count(), 0u);
  EXPECT_FALSE(empty.Raycast(Vec3(0.2, 0.2, -1.0), Vec3::UnitZ(), 0.0, kFar));
  EXPECT_FALSE(empty.Closest(Vec3::Zero()));
}

TEST(TriangleBvhTest, SingleTriangle) {
  const std::vector<Vec3> positions = {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()};
  const std::vector<Triangle> triangles = {{0, 1, 2}};
  const TriangleBvh bvh = TriangleBvh::Build(positions, triangles);
  EXPECT_EQ(bvh.triangle_count(), 1u);
  for (double sign : {1.0, -1.0}) {  // both faces count
    const auto hit = bvh.Raycast(Vec3(0.25, 0.5, -sign), Vec3(0.0, 0.0, 2.0 * sign), 0.0, kFar);
    ASSERT_TRUE(hit);
    EXPECT_DOUBLE_EQ(hit->t, 0.5);  // in units of |direction| = 2
    EXPECT_EQ(hit->triangle, 0u);
    EXPECT_DOUBLE_EQ(hit->u, 0.25);
    EXPECT_DOUBLE_EQ(hit->v, 0.5);
    EXPECT_LE((hit->point - Vec3(0.25, 0.5, 0.0)).norm(), 1e-15);
  }
  EXPECT_FALSE(bvh.Raycast(Vec3(0.75, 0.75, -1.0), Vec3::UnitZ(), 0.0, kFar));
  EXPECT_FALSE(bvh.Raycast(Vec3(0.25, 0.25, 1.0), Vec3::UnitZ(), 0.0, kFar));  // behind
}

TEST(TriangleBvhTest, RaycastMatchesBruteForceOnTorus) {
  const Mesh torus = MakeTorus(1.0, 0.35, 48, 24);
  const auto& positions = torus.welded_positions;
  const auto& triangles = torus.welded_triangles;
  const TriangleBvh bvh = TriangleBvh::Build(positions, triangles);
  ASSERT_EQ(bvh.triangle_count(), triangles.size());
  const auto all = AllIndices(triangles.size());
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> box(-1.6, 1.6), scale(0.25, 4.0);
  int hits = 0, mismatches = 0;
  for (int i = 0; i < 4000; ++i) {
    // Half the rays start inside the tube (always hit), half anywhere around the torus.
    const Vec3 o = i % 2 ? InsideTorus(rng, 1.0, 0.35) : Vec3(box(rng), 0.4 * box(rng), box(rng));
    const Vec3 d = scale(rng) * RandomUnit(rng);  // t is in units of |d|
    const auto hit = bvh.Raycast(o, d, 0.0, kFar);
    if (!SameAsBruteForce(hit, AllHits(positions, triangles, all, o, d, 0.0, kFar), positions,
                          triangles, o, d))
      ++mismatches;
    hits += hit.has_value();
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(hits, 2500);  // the test exercises hits, not only misses
}

TEST(TriangleBvhTest, RaycastMatchesBruteForceOnTriangleSoup) {
  const Soup soup = RandomSoup(2000, 2);
  const TriangleBvh bvh = TriangleBvh::Build(soup.positions, soup.triangles);
  const auto all = AllIndices(soup.triangles.size());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> box(-1.5, 1.5);
  int hits = 0, mismatches = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 o(box(rng), box(rng), box(rng));
    const Vec3 d = RandomUnit(rng);
    const auto hit = bvh.Raycast(o, d, 0.0, kFar);
    if (!SameAsBruteForce(hit, AllHits(soup.positions, soup.triangles, all, o, d, 0.0, kFar),
                          soup.positions, soup.triangles, o, d))
      ++mismatches;
    hits += hit.has_value();
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(hits, 1000);
}

TEST(TriangleBvhTest, AxisAlignedRaysMatchBruteForce) {
  // Directions with one or two zero components exercise the slab test's zero handling.
  const Soup soup = RandomSoup(1000, 4);
  const Mesh torus = MakeTorus(1.0, 0.35, 40, 20);
  std::vector<Vec3> directions;
  for (int a = 0; a < 3; ++a)
    for (double s : {1.0, -1.0}) {
      directions.push_back(s * Vec3::Unit(a));
      Vec3 two = Vec3::Zero();
      two[a] = s * 0.6;
      two[(a + 1) % 3] = 0.8;
      directions.push_back(two);
    }
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> box(-1.5, 1.5);
  int mismatches = 0, hits = 0;
  for (const auto& [positions, triangles] :
       {std::pair{soup.positions, soup.triangles},
        std::pair{torus.welded_positions, torus.welded_triangles}}) {
    const TriangleBvh bvh = TriangleBvh::Build(positions, triangles);
    const auto all = AllIndices(triangles.size());
    for (int i = 0; i < 300; ++i) {
      const Vec3 o(box(rng), 0.5 * box(rng), box(rng));
      for (const Vec3& d : directions) {
        const auto hit = bvh.Raycast(o, d, 0.0, kFar);
        if (!SameAsBruteForce(hit, AllHits(positions, triangles, all, o, d, 0.0, kFar), positions,
                              triangles, o, d))
          ++mismatches;
        hits += hit.has_value();
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(hits, 1000);
}

TEST(TriangleBvhTest, RespectsTMinAndTMax) {
  const Mesh torus = MakeTorus(1.0, 0.35, 48, 24);
  const auto& positions = torus.welded_positions;
  const auto& triangles = torus.welded_triangles;
  const TriangleBvh bvh = TriangleBvh::Build(positions, triangles);
  const auto all = AllIndices(triangles.size());

  // A ray through both sides of the tube: four hits.
  const Vec3 o(-2.0, 0.05, 0.013), d = Vec3(1.0, 0.001, 0.002).normalized();
  const auto ref = AllHits(positions, triangles, all, o, d, -kFar, kFar);
  ASSERT_EQ(ref.size(), 4u);
  const auto first = bvh.Raycast(o, d, 0.0, kFar);
  ASSERT_TRUE(first);
  EXPECT_NEAR(first->t, ref[0].t, 1e-12);
  // t_max is inclusive, t_min exclusive.
  const auto inclusive = bvh.Raycast(o, d, 0.0, first->t);
  ASSERT_TRUE(inclusive);
  EXPECT_EQ(inclusive->t, first->t);
  EXPECT_EQ(inclusive->triangle, first->triangle);
  EXPECT_FALSE(bvh.Raycast(o, d, 0.0, first->t * (1.0 - 1e-9)));
  const auto second = bvh.Raycast(o, d, first->t, kFar);
  ASSERT_TRUE(second);
  EXPECT_NEAR(second->t, ref[1].t, 1e-12);
  const auto third = bvh.Raycast(o, d, 0.5 * (ref[1].t + ref[2].t), kFar);
  ASSERT_TRUE(third);
  EXPECT_NEAR(third->t, ref[2].t, 1e-12);
  EXPECT_FALSE(bvh.Raycast(o, d, ref[3].t + 1e-9, kFar));
  // Negative t: from a point between the second and third hit, the whole line.
  const Vec3 mid = o + 0.5 * (ref[1].t + ref[2].t) * d;
  const auto line = bvh.Raycast(mid, d, -kFar, kFar);
  ASSERT_TRUE(line);
  EXPECT_NEAR(line->t, ref[0].t - 0.5 * (ref[1].t + ref[2].t), 1e-12);
  // Empty and inverted windows.
  EXPECT_FALSE(bvh.Raycast(o, d, 1.0, 1.0));
  EXPECT_FALSE(bvh.Raycast(o, d, 2.0, 1.0));

  // Random windows against brute force.
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> window(-1.0, 4.0);
  int mismatches = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 origin = InsideTorus(rng, 1.0, 0.35);
    const Vec3 dir = RandomUnit(rng);
    double t0 = window(rng), t1 = window(rng);
    if (t0 > t1) std::swap(t0, t1);
    const auto hit = bvh.Raycast(origin, dir, t0, t1);
    if (!SameAsBruteForce(hit, AllHits(positions, triangles, all, origin, dir, t0, t1), positions,
                          triangles, origin, dir))
      ++mismatches;
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(TriangleBvhTest, SubsetBuildOnlyHitsSubset) {
  const Mesh torus = MakeTorus(1.0, 0.35, 48, 24);
  const auto& positions = torus.welded_positions;
  const auto& triangles = torus.welded_triangles;
  // Every third triangle, plus all triangles with a vertex at x > 0.5.
  std::vector<std::uint32_t> subset;
  std::vector<bool> in_subset(triangles.size(), false);
  for (std::uint32_t f = 0; f < triangles.size(); ++f) {
    const bool take =
        f % 3 == 0 || std::any_of(triangles[f].begin(), triangles[f].end(),
                                  [&](std::uint32_t v) { return positions[v].x() > 0.5; });
    if (take) {
      subset.push_back(f);
      in_subset[f] = true;
    }
  }
  const TriangleBvh bvh = TriangleBvh::Build(positions, triangles, subset);
  EXPECT_EQ(bvh.triangle_count(), subset.size());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> box(-1.6, 1.6);
  int mismatches = 0, hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 o = i % 2 ? InsideTorus(rng, 1.0, 0.35) : Vec3(box(rng), 0.4 * box(rng), box(rng));
    const Vec3 d = RandomUnit(rng);
    const auto hit = bvh.Raycast(o, d, 0.0, kFar);
    if (hit) {
      ++hits;
      EXPECT_TRUE(in_subset[hit->triangle]);
    }
    if (!SameAsBruteForce(hit, AllHits(positions, triangles, subset, o, d, 0.0, kFar), positions,
                          triangles, o, d))
      ++mismatches;
    if (i % 3 != 0) continue;  // closest points for a third of the origins (both kinds)
    const auto closest = bvh.Closest(o);
    ASSERT_TRUE(closest);
    EXPECT_TRUE(in_subset[closest->triangle]);
    EXPECT_NEAR(closest->distance, BruteClosestDistance(positions, triangles, subset, o), 1e-12);
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(hits, 1000);
}

// Rays from interior points aimed exactly at every vertex, every edge midpoint and a point a
// third along every edge of a closed mesh must hit it. On a convex mesh the first hit is at the
// target (t = 1) or before; on a non-convex one a ray can touch a reflex edge or saddle vertex
// from inside and go on inside, so it must only hit somewhere.
void ExpectWatertight(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                      const std::vector<Vec3>& origins, bool convex = true) {
  const TriangleBvh bvh = TriangleBvh::Build(positions, triangles);
  std::vector<Vec3> targets = positions;
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const Vec3 &a = positions[t[k]], &b = positions[t[(k + 1) % 3]];
      targets.push_back(0.5 * (a + b));
      targets.push_back(a + (b - a) / 3.0);
    }
  int misses = 0;
  for (const Vec3& o : origins)
    for (const Vec3& target : targets) {
      const Vec3 d = target - o;
      const auto hit = bvh.Raycast(o, d, 0.0, kFar);
      if (!hit || (convex && hit->t > 1.0 + 1e-9)) ++misses;
    }
  EXPECT_EQ(misses, 0) << "of " << origins.size() * targets.size() << " rays";
}

TEST(TriangleBvhTest, RaysAtSharedVerticesAndEdgesAlwaysHit) {
  {
    const Mesh m = MakeCylinder(1.0, 2.0, 32, 3);
    ExpectWatertight(m.welded_positions, m.welded_triangles,
                     {Vec3(0.0, 1.0, 0.0), Vec3(0.3, 0.2, -0.4), Vec3(-0.5, 1.7, 0.1),
                      Vec3(0.0, 0.0 + 1e-3, 0.0), Vec3(0.9, 1.0, 0.0)});
  }
  {
    const Mesh m = MakeCone(0.8, 0.0, 1.5, 24, 3);  // a 24-valent apex
    ExpectWatertight(m.welded_positions, m.welded_triangles,
                     {Vec3(0.0, 0.5, 0.0), Vec3(0.2, 0.3, 0.1), Vec3(0.0, 1.2, 0.0)});
  }
  {
    const Mesh m = MakeCapsule(0.5, 1.0, 24, 3, 6);
    ExpectWatertight(m.welded_positions, m.welded_triangles,
                     {Vec3(0.0, 0.5, 0.0), Vec3(0.1, -0.3, 0.2), Vec3(-0.2, 1.3, 0.1)});
  }
  {
    const Mesh m = MakeTorus(1.0, 0.35, 32, 16);
    ExpectWatertight(m.welded_positions, m.welded_triangles,
                     {Vec3(1.0, 0.0, 0.0), Vec3(0.0, 0.1, -1.0), Vec3(-0.8, -0.1, 0.55)},
                     /*convex=*/false);
  }
  // Random directions from inside always hit a closed mesh.
  const Mesh torus = MakeTorus(1.0, 0.35, 32, 16);
  const TriangleBvh bvh = TriangleBvh::Build(torus.welded_positions, torus.welded_triangles);
  std::mt19937_64 rng(8);
  int misses = 0;
  for (int i = 0; i < 20000; ++i)
    misses += !bvh.Raycast(InsideTorus(rng, 1.0, 0.35), RandomUnit(rng), 0.0, kFar).has_value();
  EXPECT_EQ(misses, 0);
}

TEST(TriangleBvhTest, ExactHitsOnCubeVerticesEdgesAndDiagonals) {
  // From the centre of the unit cube, directions to corners, edge midpoints and face centres
  // (on the triangles' shared diagonals) are exact, so the hits are exactly on shared vertices
  // and edges, at t = 1; many directions have zero components.
  const Soup cube = UnitCube();
  const TriangleBvh bvh = TriangleBvh::Build(cube.positions, cube.triangles);
  const Vec3 centre(0.5, 0.5, 0.5);
  int count = 0;
  for (int x = 0; x <= 2; ++x)
    for (int y = 0; y <= 2; ++y)
      for (int z = 0; z <= 2; ++z) {
        if (x == 1 && y == 1 && z == 1) continue;
        const Vec3 target(0.5 * x, 0.5 * y, 0.5 * z);
        const auto hit = bvh.Raycast(centre, target - centre, 0.0, kFar);
        ASSERT_TRUE(hit) << target.transpose();
        EXPECT_DOUBLE_EQ(hit->t, 1.0) << target.transpose();
        EXPECT_LE((hit->point - target).norm(), 1e-15);
        ++count;
      }
  EXPECT_EQ(count, 26);
  // Rays lying in a face plane (origin on the face, zero component along its normal) do not
  // hit that face's triangles but do hit the faces they reach.
  const auto grazing = bvh.Raycast(Vec3(0.5, 0.5, 1.0), Vec3(1.0, 0.0, 0.0), 0.0, kFar);
  ASSERT_TRUE(grazing);
  EXPECT_DOUBLE_EQ(grazing->t, 0.5);
  EXPECT_DOUBLE_EQ(grazing->point.x(), 1.0);
}

TEST(TriangleBvhTest, RaysInTheVertexPlaneOfATorusAlwaysHit) {
  // y = 0 holds the torus's outer and inner equator vertices exactly; horizontal rays from
  // inside the tube in that plane run through shared vertices and edges.
  const Mesh torus = MakeTorus(1.0, 0.35, 36, 12);
  const auto& positions = torus.welded_positions;
  const auto& triangles = torus.welded_triangles;
  const TriangleBvh bvh = TriangleBvh::Build(positions, triangles);
  const auto all = AllIndices(triangles.size());
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * kPi), offset(-0.25, 0.25);
  int misses = 0, disagreements = 0;
  for (int i = 0; i < 3000; ++i) {
    const double phi = angle(rng), rho = 1.0 + offset(rng), psi = angle(rng);
    const Vec3 o(rho * std::cos(phi), 0.0, rho * std::sin(phi));
    const Vec3 d(std::cos(psi), 0.0, std::sin(psi));
    const auto hit = bvh.Raycast(o, d, 0.0, kFar);
    if (!hit) {
      ++misses;
      continue;
    }
    const auto ref = AllHits(positions, triangles, all, o, d, 0.0, kFar);
    // Moller-Trumbore may slip through an edge; the BVH hit must then be on an edge.
    if (ref.empty() || std::abs(ref.front().t - hit->t) > 1e-12) {
      if (std::min({hit->u, hit->v, 1.0 - hit->u - hit->v}) > 1e-9) ++disagreements;
    }
  }
  EXPECT_EQ(misses, 0);
  EXPECT_EQ(disagreements, 0);
}

TEST(TriangleBvhTest, HandlesExtremeArguments) {
  const Mesh torus = MakeTorus(1.0, 0.35, 24, 12);
  const TriangleBvh bvh = TriangleBvh::Build(torus.welded_positions, torus.welded_triangles);
  const Vec3 o(0.0, 0.0, 0.0), d = Vec3(1.0, 0.01, 0.02).normalized();
  const auto reference = bvh.Raycast(o, d, 0.0, kFar);
  ASSERT_TRUE(reference);
  const auto infinite = bvh.Raycast(o, d, -std::numeric_limits<double>::infinity(),
                                    std::numeric_limits<double>::infinity());
  ASSERT_TRUE(infinite);  // the whole line: the hit furthest behind
  EXPECT_LT(infinite->t, 0.0);
  // Scaled directions scale t inversely.
  for (double s : {1e-6, 1e-3, 1e3, 1e6}) {
    const auto scaled = bvh.Raycast(o, s * d, 0.0, kFar);
    ASSERT_TRUE(scaled);
    EXPECT_NEAR(scaled->t * s, reference->t, 1e-12 * reference->t);
    EXPECT_EQ(scaled->triangle, reference->triangle);
  }
  // Zero and vanishing directions hit nothing.
  EXPECT_FALSE(bvh.Raycast(o, Vec3::Zero(), 0.0, kFar));
  EXPECT_FALSE(bvh.Raycast(o, Vec3(1e-200, 0.0, 0.0), 0.0, kFar));
  // Far away origins and rays that miss everything.
  const auto far_hit = bvh.Raycast(Vec3(-1e6, 0.01, 0.02), Vec3::UnitX(), 0.0, kFar);
  ASSERT_TRUE(far_hit);
  EXPECT_NEAR(far_hit->point.x(), -1.35, 3e-2);
  EXPECT_FALSE(bvh.Raycast(Vec3(0.0, 5.0, 0.0), Vec3::UnitX(), 0.0, kFar));
  EXPECT_FALSE(bvh.Raycast(Vec3(0.0, 5.0, 0.0), Vec3::UnitY(), 0.0, kFar));
}

TEST(TriangleBvhTest, DegenerateTrianglesAreNeverHit) {
  Soup soup = RandomSoup(300, 10);
  const auto first_degenerate = static_cast<std::uint32_t>(soup.triangles.size());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> box(-1.0, 1.0);
  std::vector<Vec3> aims;  // points on the degenerate triangles
  for (int i = 0; i < 100; ++i) {
    const Vec3 a(box(rng), box(rng), box(rng)), b(box(rng), box(rng), box(rng));
    const auto n = static_cast<std::uint32_t>(soup.positions.size());
    soup.positions.push_back(a);
    soup.positions.push_back(b);
    soup.positions.push_back(0.25 * a + 0.75 * b);  // collinear
    soup.triangles.push_back({n, n + 1, n + 2});
    soup.triangles.push_back({n, n, n + 1});          // repeated index
    soup.triangles.push_back({n + 1, n + 1, n + 1});  // a point
    aims.push_back(0.5 * (a + b));
    aims.push_back(b);
  }
  const TriangleBvh bvh = TriangleBvh::Build(soup.positions, soup.triangles);
  EXPECT_EQ(bvh.triangle_count(), soup.triangles.size());
  for (const Vec3& aim : aims)
    for (int k = 0; k < 4; ++k) {
      const Vec3 o = aim - RandomUnit(rng);
      const auto hit = bvh.Raycast(o, aim - o, 0.0, kFar);
      if (hit) {
        EXPECT_LT(hit->triangle, first_degenerate);
        EXPECT_TRUE(IsFinite(hit->point));
      }
    }
  // Closest still sees them (as segments and points), and matches brute force.
  const auto all = AllIndices(soup.triangles.size());
  for (int i = 0; i < 500; ++i) {
    const Vec3 p(box(rng), box(rng), box(rng));
    const auto closest = bvh.Closest(p);
    ASSERT_TRUE(closest);
    EXPECT_NEAR(closest->distance, BruteClosestDistance(soup.positions, soup.triangles, all, p),
                1e-12);
  }
  for (const Vec3& aim : aims) {
    const auto closest = bvh.Closest(aim);
    ASSERT_TRUE(closest);
    EXPECT_LE(closest->distance, 1e-15);
  }
  // A BVH of degenerate triangles only is never hit.
  std::vector<std::uint32_t> degenerate;
  for (auto f = first_degenerate; f < soup.triangles.size(); ++f) degenerate.push_back(f);
  const TriangleBvh only = TriangleBvh::Build(soup.positions, soup.triangles, degenerate);
  for (const Vec3& aim : aims) {
    const Vec3 o = aim - RandomUnit(rng);
    EXPECT_FALSE(only.Raycast(o, aim - o, 0.0, kFar));
  }
}

TEST(TriangleBvhTest, CoincidentAndClusteredTrianglesBuildShallowTrees) {
  // 5000 copies of one triangle (no centroid extent at all), and 3000 triangles at
  // exponentially shrinking positions (SAH peels one at a time): both must build and answer
  // within the fixed traversal stack.
  std::vector<Vec3> positions = {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()};
  std::vector<Triangle> triangles(5000, Triangle{0, 1, 2});
  for (int i = 0; i < 3000; ++i) {
    const double x = 3.0 + std::pow(0.5, i % 1000) + 1e-3 * (i / 1000);
    const auto n = static_cast<std::uint32_t>(positions.size());
    positions.emplace_back(x, 0.0, 0.0);
    positions.emplace_back(x, 1.0, 0.0);
    positions.emplace_back(x, 0.0, 1.0);
    triangles.push_back({n, n + 1, n + 2});
  }
  const TriangleBvh bvh = TriangleBvh::Build(positions, triangles);
  const auto hit = bvh.Raycast(Vec3(0.2, 0.2, 1.0), -Vec3::UnitZ(), 0.0, kFar);
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->t, 1.0);
  EXPECT_LT(hit->triangle, 5000u);
  const auto all = AllIndices(triangles.size());
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> y(0.01, 0.4);
  for (int i = 0; i < 100; ++i) {
    const Vec3 o(-1.0, y(rng), y(rng));
    const auto h = bvh.Raycast(o, Vec3::UnitX(), 0.0, kFar);
    EXPECT_TRUE(SameAsBruteForce(h, AllHits(positions, triangles, all, o, Vec3::UnitX(), 0.0, kFar),
                                 positions, triangles, o, Vec3::UnitX()));
    const Vec3 p(3.0 + y(rng), y(rng), y(rng));
    const auto c = bvh.Closest(p);
    ASSERT_TRUE(c);
    EXPECT_NEAR(c->distance, BruteClosestDistance(positions, triangles, all, p), 1e-12);
  }
}

TEST(TriangleBvhTest, BuildIsDeterministic) {
  const Soup soup = RandomSoup(3000, 13);
  const TriangleBvh a = TriangleBvh::Build(soup.positions, soup.triangles);
  const TriangleBvh b = TriangleBvh::Build(soup.positions, soup.triangles);
  std::mt19937_64 rng(14);
  std::uniform_real_distribution<double> box(-1.5, 1.5);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 o(box(rng), box(rng), box(rng)), d = RandomUnit(rng);
    const auto ha = a.Raycast(o, d, 0.0, kFar), hb = b.Raycast(o, d, 0.0, kFar);
    ASSERT_EQ(ha.has_value(), hb.has_value());
    if (ha) {
      EXPECT_EQ(ha->t, hb->t);
      EXPECT_EQ(ha->triangle, hb->triangle);
    }
    const auto ca = a.Closest(o), cb = b.Closest(o);
    EXPECT_EQ(ca->triangle, cb->triangle);
    EXPECT_EQ(ca->distance, cb->distance);
  }
}

TEST(TriangleBvhTest, ConcurrentQueriesAgreeWithSequentialOnes) {
  const Mesh torus = MakeTorus(1.0, 0.35, 64, 32);
  const TriangleBvh bvh = TriangleBvh::Build(torus.welded_positions, torus.welded_triangles);
  std::mt19937_64 rng(15);
  std::vector<Vec3> origins, directions;
  for (int i = 0; i < 4000; ++i) {
    origins.push_back(InsideTorus(rng, 1.0, 0.35));
    directions.push_back(RandomUnit(rng));
  }
  std::vector<double> sequential(origins.size());
  for (std::size_t i = 0; i < origins.size(); ++i)
    sequential[i] = bvh.Raycast(origins[i], directions[i], 0.0, kFar)->t;
  std::vector<std::vector<double>> parallel(4, std::vector<double>(origins.size()));
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < parallel.size(); ++k)
    threads.emplace_back([&, k] {
      for (std::size_t i = 0; i < origins.size(); ++i) {
        const auto hit = bvh.Raycast(origins[i], directions[i], 0.0, kFar);
        parallel[k][i] = hit ? hit->t : -1.0;
      }
    });
  for (std::thread& t : threads) t.join();
  for (const auto& result : parallel) EXPECT_EQ(result, sequential);
}

// ---- Closest point ------------------------------------------------------------------------

TEST(TriangleBvhTest, ClosestMatchesBruteForce) {
  const Mesh torus = MakeTorus(1.0, 0.35, 48, 24);
  const Soup soup = RandomSoup(2000, 16);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> box(-2.0, 2.0), unit(0.0, 1.0);
  for (const auto& [positions, triangles] :
       {std::pair{torus.welded_positions, torus.welded_triangles},
        std::pair{soup.positions, soup.triangles}}) {
    const TriangleBvh bvh = TriangleBvh::Build(positions, triangles);
    const auto all = AllIndices(triangles.size());
    for (int i = 0; i < 600; ++i) {
      Vec3 p(box(rng), 0.5 * box(rng), box(rng));
      if (i % 3 == 1) p = InsideTorus(rng, 1.0, 0.35);
      if (i % 3 == 2) {  // on or very near a triangle
        const Triangle& t = triangles[std::size_t(unit(rng) * double(triangles.size()))];
        double u = unit(rng), v = unit(rng);
        if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
        p = positions[t[0]] + u * (positions[t[1]] - positions[t[0]]) +
            v * (positions[t[2]] - positions[t[0]]) + 1e-6 * (unit(rng) - 0.5) * Vec3::Ones();
      }
      const auto closest = bvh.Closest(p);
      ASSERT_TRUE(closest);
      EXPECT_NEAR(closest->distance, BruteClosestDistance(positions, triangles, all, p), 1e-12);
      EXPECT_NEAR((closest->point - p).norm(), closest->distance, 1e-15);
      const Triangle& t = triangles[closest->triangle];
      EXPECT_LE(TriangleDistance(closest->point, positions[t[0]], positions[t[1]], positions[t[2]]),
                1e-12);
    }
    // Vertices are at distance zero.
    for (std::size_t v = 0; v < positions.size(); v += 7)
      EXPECT_EQ(bvh.Closest(positions[v])->distance, 0.0);
  }
}

// ---- Winding number -----------------------------------------------------------------------

double Winding(const Mesh& mesh, const Vec3& p) {
  return WindingNumber(mesh.welded_positions, mesh.welded_triangles, p);
}

TEST(WindingNumberTest, OneInsideZeroOutsideClosedMeshes) {
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> unit(0.0, 1.0), angle(0.0, 2.0 * kPi);
  // Cylinder r = 0.5, h = 2 with 24 segments: inside the inscribed radius 0.5 cos(pi/24).
  const Mesh cylinder = MakeCylinder(0.5, 2.0, 24, 4);
  const Mesh capsule = MakeCapsule(0.5, 1.0, 24, 3, 6);
  const Mesh cone = MakeCone(0.8, 0.2, 1.5, 24, 3);
  for (int i = 0; i < 300; ++i) {
    const double phi = angle(rng), s = std::sqrt(unit(rng));
    const Vec3 inside(0.48 * s * std::cos(phi), 0.02 + 1.96 * unit(rng), 0.48 * s * std::sin(phi));
    EXPECT_NEAR(Winding(cylinder, inside), 1.0, 1e-10);
    // Capsule r = 0.5, h = 1: within 0.45 of its axis segment.
    const Vec3 in_capsule =
        Vec3(0.0, unit(rng), 0.0) + 0.45 * std::cbrt(unit(rng)) * RandomUnit(rng);
    EXPECT_NEAR(Winding(capsule, in_capsule), 1.0, 1e-10);
    const Vec3 outside(inside.x() * 1.1 / s, inside.y(), inside.z() * 1.1 / s);  // radius 0.528
    EXPECT_NEAR(Winding(cylinder, outside), 0.0, 1e-10);
    EXPECT_NEAR(Winding(cylinder, Vec3(inside.x(), -0.01 - unit(rng), inside.z())), 0.0, 1e-10);
    EXPECT_NEAR(Winding(cylinder, Vec3(inside.x(), 2.01 + unit(rng), inside.z())), 0.0, 1e-10);
    EXPECT_NEAR(Winding(capsule, 3.0 * RandomUnit(rng)), 0.0, 1e-10);
    const double y = 0.01 + 1.48 * unit(rng);
    const Vec3 in_cone =
        (0.8 - 0.4 * y) * 0.95 * s * Vec3(std::cos(phi), 0.0, std::sin(phi)) + Vec3(0.0, y, 0.0);
    EXPECT_NEAR(Winding(cone, in_cone), 1.0, 1e-10);
  }
  const Mesh torus = MakeTorus(1.0, 0.35, 48, 24);
  for (int i = 0; i < 300; ++i)
    EXPECT_NEAR(Winding(torus, InsideTorus(rng, 1.0, 0.35)), 1.0, 1e-10);
  // The hole, the axis and the space around are outside.
  EXPECT_NEAR(Winding(torus, Vec3::Zero()), 0.0, 1e-12);
  for (double y : {-2.0, -0.3, 0.3, 2.0}) EXPECT_NEAR(Winding(torus, Vec3(0, y, 0)), 0.0, 1e-12);
  for (int i = 0; i < 100; ++i) {
    const double phi = angle(rng), rho = 0.5 * unit(rng);
    EXPECT_NEAR(Winding(torus, Vec3(rho * std::cos(phi), 0.1, rho * std::sin(phi))), 0.0, 1e-10);
    EXPECT_NEAR(Winding(torus, (1.5 + unit(rng)) * RandomUnit(rng)), 0.0, 1e-10);
  }
}

TEST(WindingNumberTest, SurfacePointsGetTheirInteriorSolidAngle) {
  // A regular n-gon prism. Interior solid angle / 4 pi: on a face 1/2; on a side edge or side
  // vertex the wedge of dihedral angle pi (n - 2) / n: (n - 2) / 2n; on a cap rim edge (right
  // dihedral angle) 1/4; at a rim vertex the wedge cut in half by the cap: (n - 2) / 4n.
  const int n = 16;
  const double expect_side = (n - 2) / (2.0 * n), expect_rim = (n - 2) / (4.0 * n);
  const Mesh cylinder = MakeCylinder(0.5, 2.0, n, 2);
  const auto& p = cylinder.welded_positions;
  for (const Triangle& t : cylinder.welded_triangles)
    EXPECT_NEAR(Winding(cylinder, (p[t[0]] + p[t[1]] + p[t[2]]) / 3.0), 0.5, 1e-12);
  for (const Vec3& v : p) {
    const double w = Winding(cylinder, v);
    const bool on_axis = std::abs(v.x()) + std::abs(v.z()) == 0.0;
    const bool on_rim = !on_axis && (v.y() == 0.0 || v.y() == 2.0);
    EXPECT_NEAR(w, on_axis ? 0.5 : on_rim ? expect_rim : expect_side, 1e-12) << v.transpose();
  }
  // Rim edge midpoints and side edge midpoints between vertices of the same angle.
  for (int i = 0; i < n; ++i) {
    const Vec3 &a = p[1 + i], &b = p[1 + (i + 1) % n];  // ring at y = 0 follows the centre
    EXPECT_NEAR(Winding(cylinder, 0.5 * (a + b)), 0.25, 1e-12);
    const Vec3 &c = p[1 + n + i], &d = p[1 + 2 * n + i];  // rings at y = 1 and y = 2
    EXPECT_NEAR(Winding(cylinder, 0.5 * (c + d)), expect_side, 1e-12);
  }
}

TEST(WindingNumberTest, OpenSquareGivesItsSolidAngle) {
  // A square of side 2 seen from distance h above its centre subtends
  // 4 arcsin(1 / (1 + h^2)) (the rectangle formula); it faces +Z, so points above it are on
  // its outer side (negative), points below on its inner side (positive).
  const std::vector<Vec3> positions = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0),
                                       Vec3(-1, 1, 0)};
  const std::vector<Triangle> triangles = {{0, 1, 2}, {0, 2, 3}};
  for (double h : {1e-6, 0.01, 0.3, 1.0, 5.0, 100.0}) {
    // asin(1 / (1 + h^2)), in a form that stays accurate as h -> 0.
    const double expected = std::atan2(1.0, h * std::sqrt(2.0 + h * h)) / kPi;
    // Near the surface the winding number is ill-conditioned: a relative perturbation eps of
    // the input moves it by ~ eps * size / distance.
    const double tolerance = 1e-12 + std::numeric_limits<double>::epsilon() / h;
    EXPECT_NEAR(WindingNumber(positions, triangles, Vec3(0, 0, -h)), expected, tolerance);
    EXPECT_NEAR(WindingNumber(positions, triangles, Vec3(0, 0, h)), -expected, tolerance);
  }
  // On the square itself (at its centre, a vertex, an edge) and in its plane: zero.
  for (const Vec3& q : {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0, -1, 0), Vec3(3, 0.5, 0)})
    EXPECT_EQ(WindingNumber(positions, triangles, q), 0.0);
  EXPECT_EQ(WindingNumber(positions, {}, Vec3::Zero()), 0.0);
}

TEST(WindingNumberTest, RobustAtVerticesAndDegenerateTriangles) {
  const Mesh torus = MakeTorus(1.0, 0.35, 24, 12);
  for (const Vec3& v : torus.welded_positions) {
    const double w = Winding(torus, v);
    ASSERT_TRUE(std::isfinite(w));
    EXPECT_GT(w, 0.0);
    EXPECT_LT(w, 1.0);
  }
  // Degenerate triangles add nothing, wherever the point is (even on them).
  Mesh capsule = MakeCapsule(0.5, 1.0, 12, 2, 3);
  const Vec3 inside(0.1, 0.4, -0.1);
  const double before = Winding(capsule, inside);
  capsule.welded_positions.push_back(Vec3(0.1, 0.4, 0.3));
  const auto extra = static_cast<std::uint32_t>(capsule.welded_positions.size() - 1);
  capsule.welded_triangles.push_back({0, 0, 1});
  capsule.welded_triangles.push_back({extra, extra, extra});
  capsule.welded_triangles.push_back({0, extra, 0});
  EXPECT_EQ(Winding(capsule, inside), before);
  EXPECT_NEAR(before, 1.0, 1e-12);
  EXPECT_TRUE(std::isfinite(Winding(capsule, capsule.welded_positions[extra])));
  EXPECT_TRUE(std::isfinite(Winding(capsule, capsule.welded_positions[0])));
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
