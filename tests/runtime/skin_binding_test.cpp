// BindToWirePair / ApplyPairBinding against PHYSICS.md section 6: identity at rest, exact
// similarity, locality of a profile edit, the paper's ratio rule and similar triangles
// (checked against an independent 2D construction), every documented fallback and
// degenerate deformation (results stay finite: the test main traps NaN and Inf), and input
// validation naming the field at fault.
#include "wirerig/runtime/skin_binding.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kPi = std::numbers::pi;

bool IsFinite(const Vec3& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

// Max-norm distance.
double Distance(const Vec3& a, const Vec3& b) { return (a - b).cwiseAbs().maxCoeff(); }

// Two adjacent profile wires and their spine points.
struct WirePair {
  std::vector<Vec3> points_i, points_j;
  bool closed_i = true, closed_j = true;
  Vec3 spine_i = Vec3::Zero(), spine_j = Vec3::UnitZ();

  WirePolyline wire_i() const { return {points_i, closed_i}; }
  WirePolyline wire_j() const { return {points_j, closed_j}; }

  // Every point (wires and spine) mapped by f.
  WirePair Mapped(const std::function<Vec3(const Vec3&)>& f) const {
    WirePair out = *this;
    for (Vec3& a : out.points_i) a = f(a);
    for (Vec3& a : out.points_j) a = f(a);
    out.spine_i = f(spine_i);
    out.spine_j = f(spine_j);
    return out;
  }

  // Largest coordinate magnitude of the wires: the model's scale.
  double Extent() const {
    double extent = 0.0;
    for (const Vec3& a : points_i) extent = std::max(extent, a.cwiseAbs().maxCoeff());
    for (const Vec3& a : points_j) extent = std::max(extent, a.cwiseAbs().maxCoeff());
    return extent;
  }
};

// `count` points (rx cos a, ry sin a, z + wobble sin 3a) + center at angles a: equally spaced
// over the full turn from `from` when closed, from `from` to `to` inclusive when open.
std::vector<Vec3> Profile(int count, double rx, double ry, const Vec3& center, bool closed,
                          double from = 0.0, double to = 2.0 * kPi, double wobble = 0.0) {
  std::vector<Vec3> points;
  for (int k = 0; k < count; ++k) {
    const double a = closed ? from + 2.0 * kPi * k / count : from + (to - from) * k / (count - 1);
    points.push_back(center + Vec3(rx * std::cos(a), ry * std::sin(a), wobble * std::sin(3.0 * a)));
  }
  return points;
}

// A generic frustum: a circle of radius 1 at z = 0 and a wavy ellipse near z = 1, with a tilted
// spine and vertices that do not line up in angle.
WirePair GenericFrustum() {
  WirePair pair;
  pair.points_i = Profile(48, 1.0, 1.0, Vec3::Zero(), true);
  pair.points_j = Profile(48, 0.6, 0.5, Vec3(0.1, 0.0, 1.0), true, 0.03, 0.0, 0.05);
  pair.spine_i = Vec3::Zero();
  pair.spine_j = Vec3(0.1, 0.0, 1.0);
  return pair;
}

// Two open arcs of different radii and spans.
WirePair OpenArcs() {
  WirePair pair;
  pair.points_i = Profile(25, 1.0, 1.0, Vec3::Zero(), false, -100.0 * kPi / 180, 100.0 * kPi / 180);
  pair.points_j =
      Profile(31, 0.7, 0.7, Vec3(0.0, 0.05, 1.2), false, -110.0 * kPi / 180, 95.0 * kPi / 180);
  pair.closed_i = pair.closed_j = false;
  pair.spine_i = Vec3::Zero();
  pair.spine_j = Vec3(0.0, 0.05, 1.2);
  return pair;
}

// Random vertices around the spine of `pair`: height h in (0.02, 0.98) of the spine, angle in
// [from, to], distance 0.3 to 1.3 times a radius blended from radius_i to radius_j.
std::vector<Vec3> RandomVertices(const WirePair& pair, int count, double radius_i, double radius_j,
                                 double from, double to, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> height(0.02, 0.98), angle(from, to), factor(0.3, 1.3);
  std::vector<Vec3> vertices;
  for (int n = 0; n < count; ++n) {
    const double h = height(rng), a = angle(rng), f = factor(rng);
    const Vec3 axis = pair.spine_i + h * (pair.spine_j - pair.spine_i);
    const double radius = f * ((1.0 - h) * radius_i + h * radius_j);
    vertices.push_back(axis + radius * Vec3(std::cos(a), std::sin(a), 0.0));
  }
  return vertices;
}

PairBinding Bind(const WirePair& pair, const Vec3& p) {
  PairBinding binding;
  const Status status =
      BindToWirePair(p, pair.wire_i(), pair.wire_j(), pair.spine_i, pair.spine_j, &binding);
  EXPECT_TRUE(status.ok()) << ToString(status);
  return binding;
}

Vec3 Apply(const PairBinding& binding, const WirePair& pair) {
  return ApplyPairBinding(binding, pair.wire_i(), pair.wire_j(), pair.spine_i, pair.spine_j);
}

// Largest |apply(bind(p)) - p| / extent over the vertices; expects no fallback flags.
double IdentityError(const WirePair& pair, const std::vector<Vec3>& vertices) {
  double worst = 0.0;
  for (const Vec3& p : vertices) {
    const PairBinding binding = Bind(pair, p);
    EXPECT_EQ(binding.flags, 0) << p.transpose();
    worst = std::max(worst, Distance(Apply(binding, pair), p) / pair.Extent());
  }
  return worst;
}

// x -> scale * rotation * x + shift.
std::function<Vec3(const Vec3&)> Similarity(double scale, const Vec3& shift) {
  const Mat3 rotation = Eigen::AngleAxisd(1.1, Vec3(1.0, 2.0, 3.0).normalized()).matrix();
  return [=](const Vec3& x) -> Vec3 { return scale * (rotation * x) + shift; };
}

// Largest |apply(bind(p), f(pair)) - f(p)| / extent of f(pair) over the vertices.
double SimilarityError(const WirePair& pair, const std::vector<Vec3>& vertices,
                       const std::function<Vec3(const Vec3&)>& f) {
  const WirePair moved = pair.Mapped(f);
  double worst = 0.0;
  for (const Vec3& p : vertices)
    worst = std::max(worst, Distance(Apply(Bind(pair, p), moved), f(p)) / moved.Extent());
  return worst;
}

TEST(SkinBinding, IdentityAtRestBetweenClosedProfiles) {
  const WirePair pair = GenericFrustum();
  const double error = IdentityError(pair, RandomVertices(pair, 4000, 1.0, 0.55, 0, 2 * kPi, 1));
  std::printf("[ measured ] identity, closed profiles: max relative error %.3g\n", error);
  EXPECT_LT(error, 1e-15);
}

TEST(SkinBinding, IdentityAtRestBetweenOpenArcs) {
  const WirePair pair = OpenArcs();
  const double error =
      IdentityError(pair, RandomVertices(pair, 4000, 1.0, 0.7, -85 * kPi / 180, 85 * kPi / 180, 2));
  std::printf("[ measured ] identity, open arcs: max relative error %.3g\n", error);
  EXPECT_LT(error, 1e-15);
}

TEST(SkinBinding, SimilarityIsReproduced) {
  const auto f = Similarity(2.5, Vec3(3.0, -1.0, 2.0));
  const WirePair frustum = GenericFrustum();
  const WirePair arcs = OpenArcs();
  const double frustum_error =
      SimilarityError(frustum, RandomVertices(frustum, 2000, 1.0, 0.55, 0, 2 * kPi, 3), f);
  const double arcs_error = SimilarityError(
      arcs, RandomVertices(arcs, 2000, 1.0, 0.7, -85 * kPi / 180, 85 * kPi / 180, 4), f);
  std::printf("[ measured ] similarity: max relative error %.3g (closed), %.3g (open)\n",
              frustum_error, arcs_error);
  EXPECT_LT(frustum_error, 2e-15);
  EXPECT_LT(arcs_error, 2e-15);
}

TEST(SkinBinding, TinyAndHugeScalesAreReproduced) {
  // Tiny and huge uniform scales: the binding is scale-free.
  const WirePair pair = GenericFrustum();
  const std::vector<Vec3> vertices = RandomVertices(pair, 200, 1.0, 0.55, 0, 2 * kPi, 5);
  EXPECT_LT(SimilarityError(pair, vertices, Similarity(1e-6, Vec3(1e-6, 0, 0))), 2e-15);
  EXPECT_LT(SimilarityError(pair, vertices, Similarity(1e6, Vec3(0, 0, -3e6))), 2e-15);
}

TEST(SkinBinding, LocalBulgeLeavesFarVerticesUnchanged) {
  const WirePair rest = GenericFrustum();
  const int n = static_cast<int>(rest.points_i.size());
  const std::set<int> moved_points = {n - 1, 0, 1, 2};  // around angle 0
  WirePair bulged = rest;
  for (int k : moved_points)
    bulged.points_i[k] += 0.25 * Vec3(rest.points_i[k].x(), rest.points_i[k].y(), 0);

  const std::vector<Vec3> vertices = RandomVertices(rest, 4000, 1.0, 0.55, 0, 2 * kPi, 6);
  double far_max = 0.0, untouched_max = 0.0;
  int touched = 0, far = 0;
  for (const Vec3& p : vertices) {
    const PairBinding binding = Bind(rest, p);
    const int k = static_cast<int>(binding.k1);
    const bool uses_moved = moved_points.count(k) > 0 || moved_points.count((k + 1) % n) > 0;
    const Vec3 at_rest = Apply(binding, rest);
    const Vec3 after = Apply(binding, bulged);
    const double angle = std::atan2(p.y(), p.x());
    if (std::abs(angle) > kPi / 2) {  // the other side
      EXPECT_FALSE(uses_moved) << p.transpose();
      far_max = std::max(far_max, Distance(after, p));
      ++far;
    }
    if (uses_moved) {
      ++touched;
      EXPECT_GT(Distance(after, p), 0.0) << p.transpose();
    } else {
      // Same material points, same spine points: bit for bit the rest result.
      EXPECT_EQ(after, at_rest) << p.transpose();
      untouched_max = std::max(untouched_max, Distance(after, p));
    }
  }
  EXPECT_GT(far, 1000);
  EXPECT_GT(touched, 50);
  std::printf("[ measured ] bulge: far side moves %.3g, any untouched vertex %.3g (%d touched)\n",
              far_max, untouched_max, touched);
  EXPECT_LT(far_max, 1e-12);
  EXPECT_LT(untouched_max, 1e-12);

  // A vertex next to the bulge, near the moved wire: it follows.
  const Vec3 near = 0.9 * rest.points_i[0] + 0.1 * rest.points_i[1] + Vec3(0, 0, 0.1);
  EXPECT_GT(Distance(Apply(Bind(rest, near), bulged), near), 0.1);
}

// Where the ray from the z axis at `angle` (in the xy plane) crosses the closed polygon.
Vec3 RayHit(const std::vector<Vec3>& polygon, double angle) {
  const double ux = std::cos(angle), uy = std::sin(angle);
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& a = polygon[k];
    const Vec3& b = polygon[(k + 1) % n];
    // a + mu (b - a) = rho u: solve the 2x2 system by Cramer's rule.
    const double dx = b.x() - a.x(), dy = b.y() - a.y();
    const double det = ux * dy - uy * dx;  // det of [u, -(b - a)] up to sign
    if (det == 0.0) continue;
    const double rho = (a.x() * dy - a.y() * dx) / det;
    const double mu = (a.x() * uy - a.y() * ux) / det;
    if (rho > 0.0 && mu >= 0.0 && mu <= 1.0) return a + mu * (b - a);
  }
  ADD_FAILURE() << "ray misses the polygon";
  return Vec3::Zero();
}

// The height's unit (skin_binding.h): the distance from p1 to the pair's spine centre c, with
// a thousandth of the edge, sqrt(|c - p1|^2 + 1e-6 |e|^2).
double HeightUnit(const Eigen::Vector2d& to_center, const Eigen::Vector2d& e) {
  return std::sqrt(to_center.squaredNorm() + 1e-6 * e.squaredNorm());
}

TEST(SkinBinding, RatioRuleAndSectionScaledHeightUnderSpineStretch) {
  // Coaxial frustum; the second wire and its spine point move 0.5 along the axis. The ratio
  // rule places the foot of the perpendicular; the height off the edge scales with the
  // distance from p1 to the spine centre (PHYSICS.md section 6 scales it with |e'| / |e|:
  // wirerig departs there, skin_binding.h).
  WirePair rest;
  rest.points_i = Profile(64, 1.0, 1.0, Vec3::Zero(), true);
  rest.points_j = Profile(64, 0.6, 0.6, Vec3(0, 0, 1), true, kPi / 64);
  const Vec3 shift(0.0, 0.0, 0.5);
  WirePair stretched = rest;
  for (Vec3& a : stretched.points_j) a += shift;
  stretched.spine_j += shift;

  double worst = 0.0;
  for (const Vec3& p : RandomVertices(rest, 500, 1.0, 0.6, 0, 2 * kPi, 7)) {
    // Independent construction in the plane of p and the axis: coordinates (rho, z).
    const double angle = std::atan2(p.y(), p.x());
    const Vec3 u(std::cos(angle), std::sin(angle), 0.0);
    const auto to2d = [&](const Vec3& x) { return Eigen::Vector2d(x.dot(u), x.z()); };
    const auto cross2 = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      return a.x() * b.y() - a.y() * b.x();
    };
    const Eigen::Vector2d p1 = to2d(RayHit(rest.points_i, angle));
    const Eigen::Vector2d p2 = to2d(RayHit(rest.points_j, angle));
    const Eigen::Vector2d po = to2d(p);
    const Eigen::Vector2d e = p2 - p1;
    const double alpha = (po - p1).dot(e) / e.squaredNorm();
    const Eigen::Vector2d p3 = p1 + alpha * e;  // foot of the perpendicular
    const double height = (po - p3).norm();
    const double side = cross2(e, po - p3) >= 0.0 ? 1.0 : -1.0;
    // Deformed: ratio rule for p3', then the height, scaled by the unit's change, on the same
    // side. The spine centre: halfway between the spine points (0, 0) and (0, 1), then 1.5.
    const Eigen::Vector2d p1d = p1, p2d = p2 + Eigen::Vector2d(0.0, shift.z());
    const Eigen::Vector2d ed = p2d - p1d;
    const Eigen::Vector2d p3d = p1d + alpha * ed;
    const Eigen::Vector2d perp = side * Eigen::Vector2d(-ed.y(), ed.x()) / ed.norm();
    const double unit = HeightUnit(Eigen::Vector2d(0.0, 0.5) - p1, e);
    const double unit_d = HeightUnit(Eigen::Vector2d(0.0, 0.75) - p1d, ed);
    const Eigen::Vector2d pod = p3d + (unit_d / unit) * height * perp;
    const Vec3 expected = pod.x() * u + Vec3(0.0, 0.0, pod.y());

    const PairBinding binding = Bind(rest, p);
    EXPECT_NEAR(binding.alpha, alpha, 1e-13);
    const Vec3 got = Apply(binding, stretched);
    worst = std::max(worst, Distance(got, expected));
    // The ratio rule itself: the foot of the perpendicular from p' is p1' + alpha e'.
    const Eigen::Vector2d g = to2d(got);
    EXPECT_NEAR((g - p1d).dot(ed) / ed.squaredNorm(), alpha, 1e-13);
    EXPECT_NEAR(got.dot(Vec3(-u.y(), u.x(), 0.0)), 0.0, 1e-14);  // stays in p's plane
  }
  std::printf("[ measured ] ratio rule vs independent construction: max error %.3g\n", worst);
  EXPECT_LT(worst, 1e-13);
}

TEST(SkinBinding, VertexOnAWireFollowsItsMaterialPoint) {
  const WirePair rest = GenericFrustum();
  const auto f = Similarity(0.7, Vec3(0.2, 0.3, -0.4));
  WirePair deformed = rest.Mapped(f);
  deformed.points_i[5] += Vec3(0.05, -0.02, 0.03);  // the vertex's own wire point moves too

  // On a vertex of wire_i: the d_k = 0 vertex is counted once, lambda = 0, p1 = p.
  const Vec3 on_vertex = rest.points_i[5];
  const PairBinding binding = Bind(rest, on_vertex);
  EXPECT_EQ(binding.flags, 0);
  EXPECT_EQ(binding.k1, 5u);
  EXPECT_EQ(binding.lambda1, 0.0);
  EXPECT_EQ(binding.alpha, 0.0);
  EXPECT_EQ(binding.beta, 0.0);
  EXPECT_EQ(binding.gamma, 0.0);
  EXPECT_EQ(Apply(binding, deformed), deformed.points_i[5]);

  // Inside a segment of wire_i: linear interpolation on the wire.
  const Vec3 on_segment = 0.3 * rest.points_i[9] + 0.7 * rest.points_i[10];
  const PairBinding segment_binding = Bind(rest, on_segment);
  EXPECT_EQ(segment_binding.k1, 9u);
  EXPECT_NEAR(segment_binding.lambda1, 0.7, 1e-12);
  EXPECT_LT(Distance(Apply(segment_binding, deformed),
                     0.3 * deformed.points_i[9] + 0.7 * deformed.points_i[10]),
            1e-12);

  // On a vertex of wire_j: alpha = 1, p2' reproduced.
  const PairBinding on_j = Bind(rest, rest.points_j[7]);
  EXPECT_NEAR(on_j.alpha, 1.0, 1e-15);
  EXPECT_LT(Distance(Apply(on_j, deformed), deformed.points_j[7]), 1e-15);
}

TEST(SkinBinding, SpineAxisVertexUsesTheFirstWirePointsPlane) {
  const WirePair rest = GenericFrustum();
  const auto f = Similarity(1.3, Vec3(-1.0, 0.5, 0.25));
  WirePair bulged = rest;
  for (int k : {0, 1, 2}) bulged.points_i[k] *= 1.3;
  for (const Vec3& p : {Vec3(rest.spine_i + 0.4 * (rest.spine_j - rest.spine_i)), rest.spine_i,
                        rest.spine_j, Vec3(rest.spine_i + 1.3 * (rest.spine_j - rest.spine_i))}) {
    SCOPED_TRACE(::testing::Message() << "p = " << p.transpose());
    const PairBinding binding = Bind(rest, p);
    EXPECT_EQ(binding.flags, kBindingPlaneDegenerate);
    // The plane holds w_i[0] and the hits are on its side.
    const Vec3 p1 = (1 - binding.lambda1) * rest.points_i[binding.k1] +
                    binding.lambda1 * rest.points_i[(binding.k1 + 1) % rest.points_i.size()];
    EXPECT_LT(Distance(p1, rest.points_i[0]), 1e-12);
    EXPECT_LT(Distance(Apply(binding, rest), p), 1e-15);
    EXPECT_LT(Distance(Apply(binding, rest.Mapped(f)), f(p)), 1e-14);
    EXPECT_TRUE(IsFinite(Apply(binding, bulged)));
  }
}

TEST(SkinBinding, WiresOnTheSpineLineWithAnAxisVertexStayFinite) {
  // Every wire point on the spine line: no radial direction exists, a world axis is used.
  WirePair rest;
  rest.points_i = {Vec3(0, 0, 0), Vec3(0, 0, 0.1)};
  rest.points_j = {Vec3(0, 0, 1), Vec3(0, 0, 0.9)};
  rest.closed_i = rest.closed_j = false;
  const Vec3 p(0.0, 0.0, 0.5);
  const PairBinding binding = Bind(rest, p);
  EXPECT_EQ(binding.flags,
            kBindingPlaneDegenerate | kBindingMissedFirstWire | kBindingMissedSecondWire);
  EXPECT_LT(Distance(Apply(binding, rest), p), 1e-15);
  WirePair bent = rest;
  bent.points_i[1] = Vec3(0.2, 0.1, 0.1);
  bent.points_j[0] = Vec3(0.1, 0.0, 1.0);
  EXPECT_TRUE(IsFinite(Apply(binding, bent)));
}

TEST(SkinBinding, OpenArcMissedByThePlaneUsesTheClosestPoint) {
  WirePair rest;
  rest.points_i = Profile(13, 1.0, 1.0, Vec3::Zero(), false, -kPi / 3, kPi / 3);
  rest.points_j = Profile(13, 0.8, 0.8, Vec3(0, 0, 1), false, -kPi / 3, kPi / 3);
  rest.closed_i = rest.closed_j = false;
  WirePair deformed = rest.Mapped(Similarity(0.9, Vec3(0.1, 0.2, 0.3)));
  deformed.points_j[12] += Vec3(0.1, 0.2, -0.1);

  // Behind the arcs: the plane meets them only on the far side of the spine.
  const Vec3 behind(-0.8, 0.1, 0.5);
  const PairBinding binding = Bind(rest, behind);
  EXPECT_EQ(binding.flags, kBindingMissedFirstWire | kBindingMissedSecondWire);
  EXPECT_LT(Distance(Apply(binding, rest), behind), 1e-15);
  EXPECT_TRUE(IsFinite(Apply(binding, deformed)));
  // The closest point: the end of the arc nearer to p (positive y).
  EXPECT_EQ(binding.k1, 11u);
  EXPECT_EQ(binding.lambda1, 1.0);

  // Beyond the first arc's span but within the second's.
  WirePair wider = rest;
  wider.points_j = Profile(13, 0.8, 0.8, Vec3(0, 0, 1), false, -2 * kPi / 3, 2 * kPi / 3);
  const Vec3 side(0.0, 0.9, 0.5);
  const PairBinding one_missed = Bind(wider, side);
  EXPECT_EQ(one_missed.flags, kBindingMissedFirstWire);
  EXPECT_LT(Distance(Apply(one_missed, wider), side), 1e-15);
  EXPECT_TRUE(IsFinite(Apply(one_missed, wider.Mapped(Similarity(2.0, Vec3(1, 1, 1))))));
}

TEST(SkinBinding, SpineOnTheFrameEdgeAtRestUsesTheBindPlane) {
  // Both wires run from their spine point away from p: the plane meets them only on the
  // spine, so p1 = c_i, p2 = c_j and c lies on the edge p1 p2.
  WirePair rest;
  rest.points_i = {Vec3(0, 0, 0), Vec3(-1, 0, 0)};
  rest.points_j = {Vec3(0, 0, 1), Vec3(-1, 0, 1)};
  rest.closed_i = rest.closed_j = false;
  const Vec3 p(0.5, 0.0, 0.5);
  const PairBinding binding = Bind(rest, p);
  EXPECT_EQ(binding.flags, kBindingMissedFirstWire | kBindingMissedSecondWire);
  EXPECT_NEAR(binding.alpha, 0.5, 1e-16);
  // The height 0.5 in units of sqrt(|c - p1|^2 + 1e-6 |e|^2), |c - p1| = 0.5, |e| = 1.
  EXPECT_NEAR(std::abs(binding.beta), 0.5 / std::sqrt(0.25 + 1e-6), 1e-15);
  EXPECT_EQ(binding.gamma, 0.0);
  EXPECT_EQ(Apply(binding, rest), p);
  // A translation keeps the edge direction: the stored normal is used as is.
  const Vec3 shift(0.3, -0.2, 0.1);
  EXPECT_LT(Distance(Apply(binding, rest.Mapped([&](const Vec3& x) -> Vec3 { return x + shift; })),
                     p + shift),
            1e-15);
  // A rotation about the spine's normal turns the edge: the minimal rotation follows it.
  const Mat3 turn = Eigen::AngleAxisd(0.4, Vec3::UnitY()).matrix();
  EXPECT_LT(Distance(Apply(binding, rest.Mapped([&](const Vec3& x) -> Vec3 { return turn * x; })),
                     turn * p),
            1e-15);
  EXPECT_TRUE(IsFinite(Apply(binding, rest.Mapped(Similarity(1.5, Vec3(1, 2, 3))))));
}

TEST(SkinBinding, CollapsingWiresGiveFiniteResults) {
  const WirePair rest = GenericFrustum();
  const std::vector<Vec3> vertices = RandomVertices(rest, 300, 1.0, 0.55, 0, 2 * kPi, 8);

  // Each wire shrinks onto its spine point: c' lies on the line p1' p2'.
  WirePair onto_spine = rest;
  for (Vec3& a : onto_spine.points_i) a = rest.spine_i;
  for (Vec3& a : onto_spine.points_j) a = rest.spine_j;
  // Everything shrinks onto one point: e' = 0, the result is p1'.
  const Vec3 point(0.3, 0.2, 0.1);
  const WirePair onto_point = rest.Mapped([&](const Vec3&) -> Vec3 { return point; });
  // Nearly collinear: c' off the line by ~1e-10 (fallback) and ~1e-6 (regular frame).
  WirePair nearly = onto_spine, slightly = onto_spine;
  nearly.spine_j += Vec3(1e-10, 0, 0);
  slightly.spine_j += Vec3(1e-6, 0, 0);
  for (const Vec3& p : vertices) {
    const PairBinding binding = Bind(rest, p);
    const Vec3 a = Apply(binding, onto_spine);
    EXPECT_TRUE(IsFinite(a));
    EXPECT_LT(Distance(a, 0.5 * (rest.spine_i + rest.spine_j)), 10.0);
    EXPECT_LT(Distance(Apply(binding, onto_point), point), 1e-15);
    EXPECT_TRUE(IsFinite(Apply(binding, nearly)));
    EXPECT_TRUE(IsFinite(Apply(binding, slightly)));
  }
}

TEST(SkinBinding, ReversedDegenerateEdgeGivesAFiniteResult) {
  // The wires trade places (e' = -e exactly) with c' on the edge: the minimal rotation from
  // e to -e is not unique; the documented half turn keeps the rest normal.
  const WirePair rest = GenericFrustum();
  const Vec3 p(0.7, 0.2, 0.4);
  const PairBinding binding = Bind(rest, p);
  const Vec3 p1 = (1 - binding.lambda1) * rest.points_i[binding.k1] +
                  binding.lambda1 * rest.points_i[(binding.k1 + 1) % 48];
  const Vec3 p2 = (1 - binding.lambda2) * rest.points_j[binding.k2] +
                  binding.lambda2 * rest.points_j[(binding.k2 + 1) % 48];
  WirePair swapped = rest;
  for (Vec3& a : swapped.points_i) a = p2;
  for (Vec3& a : swapped.points_j) a = p1;
  swapped.spine_i = p2;
  swapped.spine_j = p1;
  const Vec3 a = Apply(binding, swapped);
  EXPECT_TRUE(IsFinite(a));
  // alpha is kept along the reversed edge; the height is hypot(beta, gamma) units, the unit
  // now sqrt(|c' - p1'|^2 + 1e-6 |e'|^2) with c' halfway along the edge.
  const Vec3 e = p1 - p2;
  EXPECT_NEAR((a - p2).dot(e) / e.squaredNorm(), binding.alpha, 1e-12);
  EXPECT_NEAR((a - p2 - binding.alpha * e).norm(),
              std::sqrt(0.25 + 1e-6) * e.norm() * std::hypot(binding.beta, binding.gamma), 1e-12);
}

TEST(SkinBinding, InvalidInputIsRefusedWithTheFieldNamed) {
  const WirePair pair = GenericFrustum();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Vec3 p(0.7, 0.2, 0.4);
  PairBinding sentinel;
  sentinel.k1 = 12345;
  const auto bind = [&](const Vec3& q, const WirePolyline& wi, const WirePolyline& wj,
                        const Vec3& ci, const Vec3& cj) {
    PairBinding out = sentinel;
    const Status status = BindToWirePair(q, wi, wj, ci, cj, &out);
    EXPECT_EQ(out.k1, 12345u) << "the output changed on failure";
    return status;
  };
  const WirePolyline wi = pair.wire_i(), wj = pair.wire_j();
  const Vec3 ci = pair.spine_i, cj = pair.spine_j;

  EXPECT_EQ(bind(Vec3(nan, 0, 0), wi, wj, ci, cj).field, "p");
  EXPECT_EQ(bind(Vec3(0, inf, 0), wi, wj, ci, cj).field, "p");
  EXPECT_EQ(bind(Vec3(0, 0, 1e101), wi, wj, ci, cj).field, "p");

  std::vector<Vec3> bad = pair.points_i;
  bad[2].y() = -inf;
  const Status bad_point = bind(p, {bad, true}, wj, ci, cj);
  EXPECT_EQ(bad_point.field, "wire_i");
  EXPECT_EQ(bad_point.index, 2);
  EXPECT_EQ(ToString(bad_point), "wire_i[2]: must be finite, with coordinates within 1e100 m");
  bad = pair.points_j;
  bad[40].x() = nan;
  EXPECT_EQ(bind(p, wi, {bad, true}, ci, cj).field, "wire_j");
  const std::vector<Vec3> one = {Vec3::Zero()};
  EXPECT_EQ(bind(p, {one, false}, wj, ci, cj).field, "wire_i");
  EXPECT_EQ(bind(p, wi, {one, true}, ci, cj).field, "wire_j");
  EXPECT_EQ(bind(p, wi, {{}, true}, ci, cj).field, "wire_j");

  EXPECT_EQ(bind(p, wi, wj, Vec3(nan, 0, 0), cj).field, "spine_i");
  EXPECT_EQ(bind(p, wi, wj, ci, Vec3(0, 0, -inf)).field, "spine_j");
  const Status coincident = bind(p, wi, wj, ci, ci);
  EXPECT_EQ(coincident.field, "spine_j");
  EXPECT_EQ(coincident.reason, "must differ from spine_i");

  // Identical wires: p1 == p2, the frame is undefined.
  const Status touching = bind(p, wi, wi, ci, cj);
  EXPECT_EQ(touching.field, "p");
  EXPECT_FALSE(touching.ok());

  EXPECT_EQ(BindToWirePair(p, wi, wj, ci, cj, nullptr).field, "out");
  PairBinding out;
  EXPECT_TRUE(BindToWirePair(p, wi, wj, ci, cj, &out).ok());
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
