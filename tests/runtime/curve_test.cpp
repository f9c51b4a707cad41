// Tests for wirerig::Curve against analytic references: straight lines and polylines (exact),
// circles and helices (the cubic spline converges to them), planar curves (whose
// rotation-minimizing frame keeps a constant angle to the plane) and the defining property of
// a rotation-minimizing frame (the normal turns only about the tangent's perpendicular:
// dN/ds . B = 0).
#include "wirerig/runtime/curve.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kPi = std::numbers::pi;

bool IsFinite(const Vec3& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

// Max-norm distance between two vectors.
double Distance(const Vec3& a, const Vec3& b) { return (a - b).cwiseAbs().maxCoeff(); }

// `count` points on a circle of radius `radius` about `center` in the plane spanned by the
// orthonormal vectors `e1`, `e2`, starting on e1.
std::vector<Vec3> CirclePoints(int count, double radius, const Vec3& center, const Vec3& e1,
                               const Vec3& e2) {
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    const double angle = 2.0 * kPi * i / count;
    points.push_back(center + radius * (std::cos(angle) * e1 + std::sin(angle) * e2));
  }
  return points;
}

// Helix (r cos a, r sin a, pitch a), a = 0 .. turns * 2 pi, at `count` angles
// a_i = turns * 2 pi * (i / (count - 1))^spread: unequal spacing (spread > 1) makes the
// spline's own parameter differ from arc length.
std::vector<Vec3> HelixPoints(int count, double radius, double pitch, double turns,
                              double spread = 1.0) {
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    const double u = static_cast<double>(i) / (count - 1);
    const double angle = 2.0 * kPi * turns * std::pow(u, spread);
    points.emplace_back(radius * std::cos(angle), radius * std::sin(angle), pitch * angle);
  }
  return points;
}

Curve MustBuild(const std::vector<Vec3>& points, bool closed, CurveInterpolation interpolation) {
  Curve curve;
  const Status status = Curve::Build(points, closed, interpolation, &curve);
  EXPECT_TRUE(status.ok()) << status.field << "[" << status.index << "]: " << status.reason;
  return curve;
}

void ExpectOrthonormalRightHanded(const Frame& f, double v) {
  EXPECT_NEAR(f.tangent.norm(), 1.0, 1e-12) << "v = " << v;
  EXPECT_NEAR(f.normal.norm(), 1.0, 1e-12) << "v = " << v;
  EXPECT_NEAR(f.binormal.norm(), 1.0, 1e-12) << "v = " << v;
  EXPECT_NEAR(f.tangent.dot(f.normal), 0.0, 1e-12) << "v = " << v;
  EXPECT_NEAR(f.tangent.dot(f.binormal), 0.0, 1e-12) << "v = " << v;
  EXPECT_NEAR(f.normal.dot(f.binormal), 0.0, 1e-12) << "v = " << v;
  EXPECT_LT(Distance(f.tangent.cross(f.normal), f.binormal), 1e-12) << "v = " << v;
}

// dN/ds . B by central differences of width 2 h (in v) around v.
double NormalTwistRate(const Curve& curve, double v, double h) {
  const Vec3 dn =
      (curve.FrameAt(v + h).normal - curve.FrameAt(v - h).normal) / (2.0 * h * curve.length());
  return dn.dot(curve.FrameAt(v).binormal);
}

// The v in [lo, hi] where (Position(v) - p) . Tangent(v) changes sign from - to +: the
// parameter of the curve point closest to p, found by bisection (to full precision).
double ClosestParameter(const Curve& curve, const Vec3& p, double lo, double hi) {
  auto g = [&](double v) { return (curve.Position(v) - p).dot(curve.Tangent(v)); };
  EXPECT_LT(g(lo), 0.0);
  EXPECT_GT(g(hi), 0.0);
  for (int i = 0; i < 200 && hi - lo > 1e-16; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// ---------------------------------------------------------------------------------------------
// Straight lines and polylines: exact.

TEST(Curve, StraightPolylineLengthPositionAndTangent) {
  // Unevenly spaced collinear points along (1, 2, 2) / 3, total length 6.
  const std::vector<Vec3> points = {{1, 1, 1}, {1.5, 2, 2}, {3, 5, 5}};
  const Vec3 direction = Vec3(1, 2, 2) / 3.0;
  for (const CurveInterpolation interpolation :
       {CurveInterpolation::kLinear, CurveInterpolation::kCubic}) {
    const Curve curve = MustBuild(points, false, interpolation);
    EXPECT_NEAR(curve.length(), 6.0, 1e-12);
    for (const double v : {0.0, 0.1, 0.25, 0.5, 0.9, 1.0}) {
      EXPECT_LT(Distance(curve.Position(v), points[0] + 6.0 * v * direction), 1e-12) << v;
      EXPECT_LT(Distance(curve.Tangent(v), direction), 1e-12) << v;
    }
  }
}

TEST(Curve, LinearLShapeIsParameterisedByArcLength) {
  // Legs of length 1, 1 and 2: L = 4.
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 2}};
  const Curve curve = MustBuild(points, false, CurveInterpolation::kLinear);
  EXPECT_DOUBLE_EQ(curve.length(), 4.0);
  EXPECT_LT(Distance(curve.Position(0.125), Vec3(0.5, 0, 0)), 1e-15);
  EXPECT_LT(Distance(curve.Position(0.25), Vec3(1, 0, 0)), 1e-15);
  EXPECT_LT(Distance(curve.Position(0.375), Vec3(1, 0.5, 0)), 1e-15);
  EXPECT_LT(Distance(curve.Position(0.5), Vec3(1, 1, 0)), 1e-15);
  EXPECT_LT(Distance(curve.Position(0.75), Vec3(1, 1, 1)), 1e-15);
  EXPECT_LT(Distance(curve.Position(1.0), Vec3(1, 1, 2)), 1e-15);
  EXPECT_LT(Distance(curve.Tangent(0.1), Vec3::UnitX()), 1e-15);
  EXPECT_LT(Distance(curve.Tangent(0.4), Vec3::UnitY()), 1e-15);
  EXPECT_LT(Distance(curve.Tangent(0.8), Vec3::UnitZ()), 1e-15);
}

TEST(Curve, ClosedLinearSquareHasPerimeterLength) {
  const std::vector<Vec3> points = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  const Curve curve = MustBuild(points, true, CurveInterpolation::kLinear);
  EXPECT_DOUBLE_EQ(curve.length(), 8.0);
  EXPECT_LT(Distance(curve.Position(0.875), Vec3(0, 1, 0)), 1e-15);  // on the closing edge
  EXPECT_LT(Distance(curve.Tangent(0.875), -Vec3::UnitY()), 1e-15);
  EXPECT_LT(Distance(curve.Position(1.0), points[0]), 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Cubic splines against circles and helices.

TEST(Curve, ClosedCubicCircleHasLength2PiR) {
  const double r = 0.3;
  const Vec3 center(0.1, -0.2, 0.5);
  const Vec3 e1 = Vec3(1, 1, 0).normalized();
  const Vec3 e2 = Vec3(-1, 1, 1).normalized();
  const Curve curve =
      MustBuild(CirclePoints(64, r, center, e1, e2), true, CurveInterpolation::kCubic);
  EXPECT_TRUE(curve.closed());
  EXPECT_EQ(curve.interpolation(), CurveInterpolation::kCubic);
  // The spline's radial error is ~(5/384) (h/r)^4 r ~ 1e-6 r for h = 2 pi r / 64.
  EXPECT_NEAR(curve.length(), 2.0 * kPi * r, 1e-6 * 2.0 * kPi * r);
}

TEST(Curve, ClosedCubicCircleSamplesLieOnTheCircle) {
  const double r = 0.3;
  const Vec3 center(0.1, -0.2, 0.5);
  const Vec3 e1 = Vec3(1, 1, 0).normalized();
  const Vec3 e2 = Vec3(-1, 1, 1).normalized();
  const Vec3 plane_normal = e1.cross(e2);
  const std::vector<Vec3> points = CirclePoints(64, r, center, e1, e2);
  const Curve curve = MustBuild(points, true, CurveInterpolation::kCubic);
  for (int i = 0; i <= 1000; ++i) {
    const double v = i / 1000.0;
    const Vec3 radial = curve.Position(v) - center;
    EXPECT_NEAR(radial.norm(), r, 1e-6 * r) << v;
    EXPECT_NEAR(radial.dot(plane_normal), 0.0, 1e-14) << v;
    const Vec3 t = curve.Tangent(v);
    EXPECT_NEAR(t.norm(), 1.0, 1e-14) << v;
    EXPECT_NEAR(t.dot(radial.normalized()), 0.0, 2e-5) << v;
    // Counter-clockwise about e1 x e2, like the points.
    EXPECT_GT(radial.cross(t).dot(plane_normal), 0.0) << v;
  }
  EXPECT_LT(Distance(curve.Position(0.0), points[0]), 1e-15);
  EXPECT_LT(Distance(curve.Position(1.0), curve.Position(0.0)), 1e-15);
  // Arc length on a (near) circle is proportional to the angle: a quarter of the length
  // is a quarter turn, and v = 0.25 lands on control point 16.
  EXPECT_LT(Distance(curve.Position(0.25), points[16]), 1e-9);
  EXPECT_LT(Distance(curve.Position(0.5), points[32]), 1e-9);
}

TEST(Curve, CubicIsParameterisedByArcLength) {
  // Unequally spaced points, so the spline's own (chord-length) parameter is not arc length.
  // The speed |dPosition/dv| must equal L everywhere (central differences: the chord of a
  // step 2 h L differs from the arc by (kappa 2 h L)^2 / 24 ~ 1e-9 relative here).
  const Curve curve =
      MustBuild(HelixPoints(25, 0.3, 0.1, 2.0, 1.6), false, CurveInterpolation::kCubic);
  const double h = 1e-5;
  for (int i = 1; i < 500; ++i) {
    const double v = i / 500.0;
    const double speed = (curve.Position(v + h) - curve.Position(v - h)).norm() / (2.0 * h);
    EXPECT_NEAR(speed, curve.length(), 1e-8 * curve.length()) << v;
  }
}

TEST(Curve, OpenCubicHelixInterpolatesControlPoints) {
  const int count = 41;
  const double spread = 1.3;
  const std::vector<Vec3> points = HelixPoints(count, 0.3, 0.1, 2.0, spread);
  const Curve curve = MustBuild(points, false, CurveInterpolation::kCubic);
  EXPECT_FALSE(curve.closed());
  ASSERT_EQ(curve.control_points().size(), points.size());
  EXPECT_EQ(curve.control_points()[7], points[7]);
  // Helix length sqrt(r^2 + c^2) * angle; the natural spline's ends deviate slightly.
  const double helix_length = std::sqrt(0.3 * 0.3 + 0.1 * 0.1) * 4.0 * kPi;
  EXPECT_NEAR(curve.length(), helix_length, 1e-3 * helix_length);
  EXPECT_LT(Distance(curve.Position(0.0), points.front()), 1e-15);
  EXPECT_LT(Distance(curve.Position(1.0), points.back()), 1e-15);
  // On the helix, point k sits at the fraction u_k^spread of the length: search between
  // the neighbours' fractions for the curve point closest to it.
  auto fraction = [&](int k) { return std::pow(static_cast<double>(k) / (count - 1), spread); };
  for (int k = 1; k + 1 < count; ++k) {
    const double lo = 0.5 * (fraction(k - 1) + fraction(k));
    const double hi = 0.5 * (fraction(k) + fraction(k + 1));
    const double v = ClosestParameter(curve, points[k], lo, hi);
    EXPECT_LT(Distance(curve.Position(v), points[k]), 1e-12) << k;
    EXPECT_NEAR(v, fraction(k), 1e-3) << k;
  }
}

TEST(Curve, OpenCubicHelixResamplesAtEqualChords) {
  const double r = 0.3;
  const double c = 0.1;
  const Curve curve = MustBuild(HelixPoints(41, r, c, 2.0, 1.3), false, CurveInterpolation::kCubic);
  const int n = 101;
  std::vector<Vec3> samples(n);
  curve.Resample(samples);
  for (int i = 0; i < n; ++i) {
    EXPECT_LT(Distance(samples[i], curve.Position(i / (n - 1.0))), 1e-15) << i;
  }
  EXPECT_LT(Distance(samples.front(), curve.control_points().front()), 1e-15);
  EXPECT_LT(Distance(samples.back(), curve.control_points().back()), 1e-15);
  // Equal arcs on a helix subtend equal chords: 2 sqrt(r^2 sin^2(da/2) + (c da/2)^2) for the
  // angle da = arc / sqrt(r^2 + c^2). The spline follows the helix to ~1e-5 away from its
  // natural ends; within a few control points of them its curvature differs, and chords
  // only stay within 0.2% of the arc.
  const double arc = curve.length() / (n - 1);
  const double da = arc / std::sqrt(r * r + c * c);
  const double helix_chord = 2.0 * std::hypot(r * std::sin(0.5 * da), 0.5 * c * da);
  ASSERT_LT(helix_chord, arc * (1.0 - 5e-4));  // so the next checks can tell them apart
  for (int i = 1; i < n; ++i) {
    const double chord = (samples[i] - samples[i - 1]).norm();
    EXPECT_LE(chord, arc * (1.0 + 1e-12)) << i;  // a chord never exceeds its arc
    EXPECT_GE(chord, arc * (1.0 - 2e-3)) << i;
    if (i > 15 && i < n - 15) {
      EXPECT_NEAR(chord, helix_chord, 1e-4 * arc) << i;
    }
  }
}

TEST(Curve, ClosedResampleDoesNotRepeatTheFirstPoint) {
  const Curve curve = MustBuild(CirclePoints(64, 0.3, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()),
                                true, CurveInterpolation::kCubic);
  std::vector<Vec3> samples(8);
  curve.Resample(samples);
  for (int i = 0; i < 8; ++i) {
    const double angle = 2.0 * kPi * i / 8.0;
    EXPECT_LT(Distance(samples[i], 0.3 * Vec3(std::cos(angle), std::sin(angle), 0.0)), 1e-6) << i;
  }
}

// ---------------------------------------------------------------------------------------------
// Rotation-minimizing frames.

TEST(Curve, PlanarPolylineBinormalIsPlaneNormal) {
  // In the z = 0 plane, first leg along +x: the initial normal is +y (least aligned axis,
  // ties to the lower one), so the binormal is +z, and rotation-minimizing frames of a
  // planar curve keep it there through every corner.
  const std::vector<Vec3> points = {
      {0, 0, 0}, {1, 0, 0}, {1.5, 0.8, 0}, {0.7, 1.4, 0}, {0.2, 1.0, 0}};
  const Curve curve = MustBuild(points, false, CurveInterpolation::kLinear);
  for (int i = 0; i <= 200; ++i) {
    const double v = i / 200.0;
    const Frame f = curve.FrameAt(v);
    ExpectOrthonormalRightHanded(f, v);
    EXPECT_LT(Distance(f.binormal, Vec3::UnitZ()), 1e-12) << v;
    EXPECT_LT(Distance(f.tangent, curve.Tangent(v)), 1e-15) << v;
  }
}

TEST(Curve, PlanarCubicFrameKeepsItsAngleToThePlane) {
  // A wiggly open curve in a tilted plane: the frame rotates with the curve within the
  // plane, so the normal's and binormal's components along the plane normal are constant.
  const Vec3 e1 = Vec3(2, 1, -1).normalized();
  const Vec3 e2 = Vec3(1, -1, 1).normalized();
  const Vec3 plane_normal = e1.cross(e2);
  std::vector<Vec3> points;
  for (int i = 0; i < 12; ++i) {
    const double x = 0.1 * i;
    points.push_back(Vec3(0.3, 0.2, 0.1) + x * e1 + 0.2 * std::sin(5.0 * x) * e2);
  }
  const Curve curve = MustBuild(points, false, CurveInterpolation::kCubic);
  const Frame start = curve.FrameAt(0.0);
  // The start normal is not in the plane, so this test sees a rotation about the tangent.
  EXPECT_GT(std::abs(start.normal.dot(plane_normal)), 0.1);
  for (int i = 0; i <= 300; ++i) {
    const double v = i / 300.0;
    const Frame f = curve.FrameAt(v);
    ExpectOrthonormalRightHanded(f, v);
    EXPECT_NEAR(f.tangent.dot(plane_normal), 0.0, 1e-14) << v;
    EXPECT_NEAR(f.normal.dot(plane_normal), start.normal.dot(plane_normal), 1e-12) << v;
    EXPECT_NEAR(f.binormal.dot(plane_normal), start.binormal.dot(plane_normal), 1e-12) << v;
  }
}

TEST(Curve, HelixFramesAreRotationMinimizing) {
  // Helix r = 0.3, pitch 0.1: torsion c / (r^2 + c^2) = 1 / m, so the Frenet normal has
  // dN/ds . B = 1 / m; a rotation-minimizing normal has 0.
  const Curve curve = MustBuild(HelixPoints(41, 0.3, 0.1, 3.0), false, CurveInterpolation::kCubic);
  const Frame start = curve.FrameAt(0.0);
  EXPECT_LT(Distance(start.tangent, curve.Tangent(0.0)), 1e-15);
  for (int i = 0; i <= 500; ++i) {
    const double v = i / 500.0;
    const Frame f = curve.FrameAt(v);
    ExpectOrthonormalRightHanded(f, v);
    EXPECT_LT(Distance(f.tangent, curve.Tangent(v)), 1e-15) << v;
  }
  for (int i = 1; i < 100; ++i) {
    const double v = i / 100.0 + 0.0013;  // also between table nodes
    EXPECT_NEAR(NormalTwistRate(curve, v, 1e-5), 0.0, 1e-5) << v;
  }
}

TEST(Curve, ClosedCurveFramesAreContinuousAtTheSeam) {
  // A closed non-planar curve (saddle-shaped loop) whose rotation-minimizing frame does not
  // close up by itself: the holonomy is spread evenly, so the normal twists about the tangent
  // at one constant rate, and the frames meet at the seam.
  std::vector<Vec3> points;
  for (int i = 0; i < 48; ++i) {
    const double a = 2.0 * kPi * i / 48;
    points.emplace_back(0.4 * std::cos(a), 0.25 * std::sin(a), 0.2 * std::sin(2.0 * a) + 0.1);
  }
  const Curve curve = MustBuild(points, true, CurveInterpolation::kCubic);
  const Frame f0 = curve.FrameAt(0.0);
  const Frame f1 = curve.FrameAt(1.0);
  EXPECT_LT(Distance(f0.tangent, f1.tangent), 1e-15);
  EXPECT_LT(Distance(f0.normal, f1.normal), 1e-15);
  EXPECT_LT(Distance(f0.binormal, f1.binormal), 1e-15);
  const Frame before = curve.FrameAt(1.0 - 1e-6);
  const Frame after = curve.FrameAt(1e-6);
  // Frames 2e-6 L apart differ by about 2e-6 L |dN/ds| ~ 1e-5, and if the frame is smooth
  // across the seam their mean is the frame at the seam to second order.
  EXPECT_LT(Distance(before.tangent, after.tangent), 3e-5);
  EXPECT_LT(Distance(before.normal, after.normal), 3e-5);
  EXPECT_LT(Distance(before.binormal, after.binormal), 3e-5);
  EXPECT_LT(Distance(0.5 * (before.tangent + after.tangent), f0.tangent), 1e-9);
  EXPECT_LT(Distance(0.5 * (before.normal + after.normal), f0.normal), 1e-9);
  EXPECT_LT(Distance(0.5 * (before.binormal + after.binormal), f0.binormal), 1e-9);

  const double twist = NormalTwistRate(curve, 0.5, 1e-5);
  EXPECT_GT(std::abs(twist * curve.length()), 0.05);  // the correction is not trivial here
  for (int i = 0; i < 50; ++i) {
    const double v = i / 50.0 + 0.007;
    ExpectOrthonormalRightHanded(curve.FrameAt(v), v);
    EXPECT_NEAR(NormalTwistRate(curve, v, 1e-5), twist, 1e-5) << v;
  }
  EXPECT_NEAR(NormalTwistRate(curve, 1e-5, 1e-5), twist, 1e-5);  // straddling the seam
}

TEST(Curve, ClosedPolylineFramesMeetAtTheSeam) {
  // A non-planar closed polyline: frames turn only at corners, and close up at v = 1.
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 1}};
  const Curve curve = MustBuild(points, true, CurveInterpolation::kLinear);
  const Frame f0 = curve.FrameAt(0.0);
  const Frame f1 = curve.FrameAt(1.0);
  EXPECT_LT(Distance(f0.normal, f1.normal), 1e-15);
  for (int i = 0; i <= 100; ++i) ExpectOrthonormalRightHanded(curve.FrameAt(i / 100.0), i / 100.0);
  // Just before the seam the frame is the closing edge's, turned by the last corner only:
  // its normal is f0's normal carried back across the seam corner (a minimal rotation).
  const Frame last = curve.FrameAt(1.0 - 1e-9);
  const Vec3 axis = last.tangent.cross(f0.tangent).normalized();
  const double angle = std::acos(last.tangent.dot(f0.tangent));
  const Vec3 carried = Eigen::AngleAxisd(angle, axis) * last.normal;
  EXPECT_LT(Distance(carried, f0.normal), 1e-7);
}

// ---------------------------------------------------------------------------------------------
// Invalid input: refused with a reason, output untouched.

class CurveBuildRefuses : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(Curve::Build(original_points_, false, CurveInterpolation::kLinear, &out_).ok());
  }
  void ExpectUntouched() const {
    EXPECT_FALSE(out_.closed());
    EXPECT_EQ(out_.interpolation(), CurveInterpolation::kLinear);
    EXPECT_DOUBLE_EQ(out_.length(), 3.0);
    ASSERT_EQ(out_.control_points().size(), 2u);
    EXPECT_EQ(out_.control_points()[1], original_points_[1]);
    EXPECT_LT(Distance(out_.Position(0.5), Vec3(1.5, 0, 0)), 1e-15);
  }
  std::vector<Vec3> original_points_ = {{0, 0, 0}, {3, 0, 0}};
  Curve out_;
};

TEST_F(CurveBuildRefuses, OpenCurveWithOnePoint) {
  const std::vector<Vec3> points = {{1, 2, 3}};
  const Status status = Curve::Build(points, false, CurveInterpolation::kCubic, &out_);
  EXPECT_FALSE(status.ok());
  EXPECT_EQ(status.field, "points");
  EXPECT_EQ(status.index, -1);
  EXPECT_FALSE(status.reason.empty());
  ExpectUntouched();
  EXPECT_FALSE(Curve::Build({}, false, CurveInterpolation::kLinear, &out_).ok());
  ExpectUntouched();
}

TEST_F(CurveBuildRefuses, ClosedCurveWithTwoPoints) {
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}};
  const Status status = Curve::Build(points, true, CurveInterpolation::kCubic, &out_);
  EXPECT_FALSE(status.ok());
  EXPECT_EQ(status.field, "points");
  EXPECT_EQ(status.index, -1);
  ExpectUntouched();
  // The same points make a valid open curve.
  Curve open;
  EXPECT_TRUE(Curve::Build(points, false, CurveInterpolation::kCubic, &open).ok());
}

TEST_F(CurveBuildRefuses, NonFiniteCoordinate) {
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()}) {
    std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 1, 0}};
    points[2].y() = bad;
    const Status status = Curve::Build(points, false, CurveInterpolation::kCubic, &out_);
    EXPECT_FALSE(status.ok());
    EXPECT_EQ(status.field, "points");
    EXPECT_EQ(status.index, 2);
    ExpectUntouched();
  }
}

TEST_F(CurveBuildRefuses, HugeCoordinate) {
  const std::vector<Vec3> points = {{0, 0, 0}, {1e300, 0, 0}, {-1e300, 1, 0}};
  const Status status = Curve::Build(points, false, CurveInterpolation::kCubic, &out_);
  EXPECT_FALSE(status.ok());
  EXPECT_EQ(status.index, 1);
  ExpectUntouched();
}

TEST_F(CurveBuildRefuses, CoincidentConsecutivePoints) {
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 1, 0}};
  for (const bool closed : {false, true}) {
    const Status status = Curve::Build(points, closed, CurveInterpolation::kCubic, &out_);
    EXPECT_FALSE(status.ok());
    EXPECT_EQ(status.field, "points");
    EXPECT_EQ(status.index, 1);
    EXPECT_FALSE(status.reason.empty());
    ExpectUntouched();
  }
  // Nearly coincident: 1e-14 apart on a curve about 2 m across.
  const std::vector<Vec3> near = {{0, 0, 0}, {1, 0, 0}, {1, 1e-14, 0}, {2, 1, 0}};
  const Status status = Curve::Build(near, false, CurveInterpolation::kLinear, &out_);
  EXPECT_FALSE(status.ok());
  EXPECT_EQ(status.index, 1);
  ExpectUntouched();
}

TEST_F(CurveBuildRefuses, ClosedCurveWhoseLastPointRepeatsTheFirst) {
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}};
  const Status status = Curve::Build(points, true, CurveInterpolation::kCubic, &out_);
  EXPECT_FALSE(status.ok());
  EXPECT_EQ(status.field, "points");
  EXPECT_EQ(status.index, 3);
  ExpectUntouched();
  // Open, the same points are fine.
  Curve open;
  EXPECT_TRUE(Curve::Build(points, false, CurveInterpolation::kCubic, &open).ok());
}

// ---------------------------------------------------------------------------------------------
// Parameters outside [0, 1].

TEST(Curve, OpenCurveClampsParameter) {
  const Curve curve = MustBuild(HelixPoints(9, 0.3, 0.1, 1.0), false, CurveInterpolation::kCubic);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(curve.Position(-0.5), curve.Position(0.0));
  EXPECT_EQ(curve.Position(-1e300), curve.Position(0.0));
  EXPECT_EQ(curve.Position(1.7), curve.Position(1.0));
  EXPECT_EQ(curve.Tangent(2.0), curve.Tangent(1.0));
  EXPECT_EQ(curve.FrameAt(3.0).normal, curve.FrameAt(1.0).normal);
  // Non-finite v means v = 0, never NaN.
  for (const double bad : {nan, inf, -inf}) {
    EXPECT_EQ(curve.Position(bad), curve.Position(0.0));
    EXPECT_EQ(curve.Tangent(bad), curve.Tangent(0.0));
    EXPECT_EQ(curve.FrameAt(bad).normal, curve.FrameAt(0.0).normal);
  }
}

TEST(Curve, ClosedCurveWrapsParameter) {
  const Curve curve = MustBuild(CirclePoints(16, 0.3, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitZ()),
                                true, CurveInterpolation::kCubic);
  EXPECT_LT(Distance(curve.Position(1.25), curve.Position(0.25)), 1e-15);
  EXPECT_LT(Distance(curve.Position(-0.25), curve.Position(0.75)), 1e-15);
  EXPECT_LT(Distance(curve.Position(7.0), curve.Position(0.0)), 1e-15);
  EXPECT_LT(Distance(curve.Tangent(-2.6), curve.Tangent(0.4)), 1e-12);
  EXPECT_LT(Distance(curve.FrameAt(3.3).normal, curve.FrameAt(0.3).normal), 1e-12);
  // A tiny negative v wraps to just below 1, which is the seam.
  EXPECT_LT(Distance(curve.Position(-1e-17), curve.Position(0.0)), 1e-15);
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    EXPECT_EQ(curve.Position(bad), curve.Position(0.0));
  }
}

TEST(Curve, DefaultConstructedCurveIsSafeToQuery) {
  const Curve curve;
  EXPECT_EQ(curve.length(), 0.0);
  EXPECT_TRUE(curve.control_points().empty());
  EXPECT_TRUE(IsFinite(curve.Position(0.5)));
  EXPECT_TRUE(IsFinite(curve.FrameAt(0.5).normal));
  std::vector<Vec3> samples(3, Vec3::Ones());
  curve.Resample(samples);
  for (const Vec3& p : samples) EXPECT_TRUE(IsFinite(p));
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
