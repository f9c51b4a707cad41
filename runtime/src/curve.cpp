// Curve: see curve.h for the contract.
//
// Parameterisation. Control point i sits at the chord-length parameter knots_[i]
// (knots_[0] = 0, knots_[i + 1] = knots_[i] + |p_{i+1} - p_i|); segment i spans
// [knots_[i], knots_[i + 1]] and has h_i = knots_[i + 1] - knots_[i] > 0. A closed curve has
// one more segment, from the last point back to the first, and knots_ has #P + 1 entries.
//
// Cubic segments. With w = (t - knots_[i]) / h_i, z = 1 - w and M_i the spline's second
// derivatives (second_derivs_),
//   x(t) = z p_i + w p_{i+1} + h_i^2 / 6 ((z^3 - z) M_i + (w^3 - w) M_{i+1}),
// C2 when h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1}
//           = 6 ((p_{i+1} - p_i) / h_i - (p_i - p_{i-1}) / h_{i-1}).
// Open: natural ends (M = 0 at both ends), a tridiagonal system. Closed: indices wrap, a cyclic
// tridiagonal system solved by Sherman-Morrison. Both are strictly diagonally dominant.
//
// Arc-length table. Each segment is cut into substeps_ equal steps of t (16 for cubic, 1 for
// linear); table_t_[j] and table_s_[j] are the parameter and arc length at node j (node
// j < #nodes - 1 lies in segment j / substeps_), the last node is the end of the curve.
// Lengths of cubic steps come from 8-point Gauss-Legendre quadrature of |x'(t)|; linear
// segments have unit speed in t, so s = t. A query finds the table step holding s = v L by
// binary search and solves arc length(t) = s in that step by safeguarded Newton iteration,
// using the same quadrature from the step's start, so the table and queries agree exactly.
//
// Frames. table_frames_ holds rotation-minimizing frames at the nodes, propagated by the
// double reflection method (Wang, Juttler, Zheng, Liu 2008, ACM TOG 27(1)). A query takes
// one double-reflection step from the node at or before v. For a closed curve the frame
// carried once around differs from the start frame by a rotation about the tangent
// (holonomy); holonomy_angle_ is that angle divided by L and the frame at arc length s is
// turned back by holonomy_angle_ * s, so the table stores corrected frames and a query adds
// the part between its node and s. Double reflections commute with rotations about the
// tangent, so this equals correcting the uncorrected rotation-minimizing frame.
#include "wirerig/runtime/curve.h"

#include "vector_math.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

namespace wirerig {
namespace {

constexpr int kCubicSubsteps = 16;
// Consecutive points closer than this fraction of the bounding-box diagonal coincide.
constexpr double kCoincidentFraction = 1e-12;
// ... or closer than this, in metres, whatever the extent.
constexpr double kCoincidentAbsolute = 1e-100;
// Coordinates beyond this (m) are refused: squares of lengths must not overflow.
constexpr double kMaxCoordinate = 1e100;
// Newton stops when the arc-length residual is below this fraction of the table step.
constexpr double kArcLengthTolerance = 1e-13;
constexpr int kMaxNewtonIterations = 60;

// 8-point Gauss-Legendre rule on [-1, 1]: nodes +-kGaussX[k], weights kGaussW[k].
constexpr std::array<double, 4> kGaussX = {0.18343464249564980494, 0.52553240991632898582,
                                           0.79666647741362673959, 0.96028985649753623168};
constexpr std::array<double, 4> kGaussW = {0.36268378337836198297, 0.31370664587788728734,
                                           0.22238103445337447054, 0.10122853629037625915};

using detail::OrthonormalizeAgainst;
using detail::PerpendicularTo;

// Rotates the unit vector r (perpendicular to the unit vector t) by `angle` about t.
Vec3 RotateAbout(const Vec3& r, const Vec3& t, double angle) {
  return std::cos(angle) * r + std::sin(angle) * t.cross(r);
}

// One double-reflection step (Wang et al. 2008, section 4): carries the normal r0 of the
// frame with tangent t0 to the point whose tangent is t1. `secant` is any nonzero multiple of
// the chord between the two points; zero stands for coincident points, where the first
// reflection uses t0 instead (the step is then the minimal rotation taking t0 to t1).
// Returns a unit normal perpendicular to t1.
Vec3 DoubleReflect(const Vec3& secant, const Vec3& t0, const Vec3& r0, const Vec3& t1) {
  // Only the direction of the secant matters: scale it to a max-norm of one, so that
  // neither tiny nor large chords can underflow or overflow.
  const double scale = secant.cwiseAbs().maxCoeff();
  Vec3 v1 = t0;
  if (scale > 0.0 && std::isfinite(scale)) v1 = secant / scale;
  const double c1 = v1.squaredNorm();  // >= 1 (or t0 . t0 = 1)
  const Vec3 r_l = r0 - (2.0 * v1.dot(r0) / c1) * v1;
  const Vec3 t_l = t0 - (2.0 * v1.dot(t0) / c1) * v1;
  const Vec3 v2 = t1 - t_l;
  const double c2 = v2.squaredNorm();  // in [0, 4]
  // c2 ~ 0: the first reflection already took t0 to t1; the second would be undefined.
  const Vec3 r1 = c2 > 1e-24 ? Vec3(r_l - (2.0 * v2.dot(r_l) / c2) * v2) : r_l;
  return OrthonormalizeAgainst(r1, t1);
}

// Solves the tridiagonal system sub[i] x[i-1] + diag[i] x[i] + sup[i] x[i+1] = rhs[i] in place
// (Thomas algorithm; sub[0] and sup[n-1] are ignored). The matrix must be diagonally
// dominant. `scratch` has n entries.
template <typename T>
void SolveTridiagonal(const std::vector<double>& sub, const std::vector<double>& diag,
                      const std::vector<double>& sup, std::vector<T>& rhs,
                      std::vector<double>& scratch) {
  const std::size_t n = diag.size();
  if (n == 0) return;
  double pivot = diag[0];
  rhs[0] = rhs[0] / pivot;
  for (std::size_t i = 1; i < n; ++i) {
    scratch[i] = sup[i - 1] / pivot;
    pivot = diag[i] - sub[i] * scratch[i];
    rhs[i] = (rhs[i] - sub[i] * rhs[i - 1]) / pivot;
  }
  for (std::size_t i = n - 1; i > 0; --i) rhs[i - 1] = rhs[i - 1] - scratch[i] * rhs[i];
}

// Second derivatives of the chord-length C2 cubic spline through `points` (see the top of
// this file), natural when open, periodic when closed. `h` holds the segment lengths.
std::vector<Vec3> SplineSecondDerivatives(std::span<const Vec3> points,
                                          const std::vector<double>& h, bool closed) {
  const std::size_t count = points.size();
  std::vector<Vec3> result(count, Vec3::Zero());
  if (!closed) {
    if (count < 3) return result;     // a single segment: a straight line
    const std::size_t n = count - 2;  // unknowns M_1 .. M_{count-2}
    std::vector<double> sub(n), diag(n), sup(n), scratch(n);
    std::vector<Vec3> rhs(n);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = k + 1;
      sub[k] = h[i - 1];
      diag[k] = 2.0 * (h[i - 1] + h[i]);
      sup[k] = h[i];
      rhs[k] = 6.0 * ((points[i + 1] - points[i]) / h[i] - (points[i] - points[i - 1]) / h[i - 1]);
    }
    SolveTridiagonal(sub, diag, sup, rhs, scratch);
    for (std::size_t k = 0; k < n; ++k) result[k + 1] = rhs[k];
    return result;
  }
  // Closed: cyclic system, corners A[0][n-1] = A[n-1][0] = h[n-1]. Sherman-Morrison
  // (Numerical Recipes, "cyclic"): solve with a modified tridiagonal matrix and correct.
  const std::size_t n = count;
  std::vector<double> sub(n), diag(n), sup(n), scratch(n);
  std::vector<Vec3> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t prev = (i + n - 1) % n;
    const std::size_t next = (i + 1) % n;
    sub[i] = h[prev];
    diag[i] = 2.0 * (h[prev] + h[i]);
    sup[i] = h[i];
    x[i] = 6.0 * ((points[next] - points[i]) / h[i] - (points[i] - points[prev]) / h[prev]);
  }
  const double corner = h[n - 1];
  const double gamma = -diag[0];
  diag[0] -= gamma;
  diag[n - 1] -= corner * corner / gamma;
  std::vector<double> z(n, 0.0);
  z[0] = gamma;
  z[n - 1] = corner;
  SolveTridiagonal(sub, diag, sup, x, scratch);
  SolveTridiagonal(sub, diag, sup, z, scratch);
  const Vec3 numerator = x[0] + (corner / gamma) * x[n - 1];
  const double denominator = 1.0 + z[0] + (corner / gamma) * z[n - 1];
  const Vec3 factor = numerator / denominator;
  for (std::size_t i = 0; i < n; ++i) result[i] = x[i] - z[i] * factor;
  return result;
}

}  // namespace

Status Curve::Build(std::span<const Vec3> points, bool closed, CurveInterpolation interpolation,
                    Curve* out) {
  if (out == nullptr) return Status::Invalid("out", "must not be null");
  if (interpolation != CurveInterpolation::kLinear && interpolation != CurveInterpolation::kCubic) {
    return Status::Invalid("interpolation", "must be kLinear or kCubic");
  }
  if (points.size() < 2) return Status::Invalid("points", "needs at least 2 points");
  if (closed && points.size() < 3) {
    return Status::Invalid("points", "needs at least 3 points when closed");
  }
  if (points.size() > static_cast<std::size_t>(1) << 24) {
    return Status::Invalid("points", "has more than 2^24 points");
  }
  const int count = static_cast<int>(points.size());
  for (int i = 0; i < count; ++i) {
    // (Not Eigen's allFinite(): it computes x - x, which raises FE_INVALID on infinities.)
    const Vec3& p = points[i];
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
      return Status::InvalidElement("points", i, "", "has a non-finite coordinate");
    }
    if (!(p.cwiseAbs().maxCoeff() <= kMaxCoordinate)) {
      return Status::InvalidElement("points", i, "", "has a coordinate beyond 1e100 m");
    }
  }
  Vec3 lo = points[0];
  Vec3 hi = points[0];
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double threshold = std::max(kCoincidentFraction * (hi - lo).norm(), kCoincidentAbsolute);
  const int segments = closed ? count : count - 1;
  std::vector<double> h(segments);
  for (int i = 0; i < segments; ++i) {
    const int next = (i + 1) % count;
    h[i] = (points[next] - points[i]).norm();
    if (!(h[i] > threshold)) {
      return Status::InvalidElement(
          "points", i, "",
          next == 0 ? "coincides with the first point" : "coincides with the next point");
    }
  }

  Curve curve;
  curve.points_.assign(points.begin(), points.end());
  curve.closed_ = closed;
  curve.interpolation_ = interpolation;
  const bool cubic = interpolation == CurveInterpolation::kCubic;
  curve.substeps_ = cubic ? kCubicSubsteps : 1;
  curve.knots_.resize(segments + 1);
  curve.knots_[0] = 0.0;
  for (int i = 0; i < segments; ++i) curve.knots_[i + 1] = curve.knots_[i] + h[i];
  if (cubic) curve.second_derivs_ = SplineSecondDerivatives(points, h, closed);

  // Arc-length table.
  const int substeps = curve.substeps_;
  const int nodes = segments * substeps + 1;
  curve.table_t_.resize(nodes);
  curve.table_s_.resize(nodes);
  for (int i = 0; i < segments; ++i) {
    for (int k = 0; k < substeps; ++k) {
      const double fraction = static_cast<double>(k) / static_cast<double>(substeps);
      curve.table_t_[i * substeps + k] = curve.knots_[i] + fraction * h[i];
    }
  }
  curve.table_t_[nodes - 1] = curve.knots_[segments];
  curve.table_s_[0] = 0.0;
  for (int j = 0; j + 1 < nodes; ++j) {
    curve.table_s_[j + 1] =
        curve.table_s_[j] +
        curve.SegmentArcLength(curve.SegmentOfNode(j), curve.table_t_[j], curve.table_t_[j + 1]);
  }
  curve.length_ = curve.table_s_[nodes - 1];

  // Rotation-minimizing frames at the nodes. The last node belongs to the last segment.
  auto node_tangent = [&curve](int j) {
    const int segment = curve.SegmentOfNode(j);
    const Vec3 d = curve.SegmentDerivative(segment, curve.table_t_[j]);
    const double norm = d.norm();
    if (norm > 0.0) return Vec3(d / norm);
    // Zero speed (a cusp): fall back on the segment's chord.
    const int next = (segment + 1) % static_cast<int>(curve.points_.size());
    return Vec3((curve.points_[next] - curve.points_[segment]).normalized());
  };
  curve.table_frames_.resize(nodes);
  {
    Frame& first = curve.table_frames_[0];
    first.tangent = node_tangent(0);
    first.normal = PerpendicularTo(first.tangent);
    first.binormal = first.tangent.cross(first.normal);
  }
  for (int j = 0; j + 1 < nodes; ++j) {
    const Frame& from = curve.table_frames_[j];
    Frame& to = curve.table_frames_[j + 1];
    const Vec3 secant =
        curve.SegmentSecant(curve.SegmentOfNode(j), curve.table_t_[j], curve.table_t_[j + 1]);
    to.tangent = node_tangent(j + 1);
    to.normal = DoubleReflect(secant, from.tangent, from.normal, to.tangent);
    to.binormal = to.tangent.cross(to.normal);
  }

  if (closed) {
    // Carry the end frame across the seam (same point; for a linear curve the tangent turns
    // from the last segment's to the first's) and measure its angle to the start frame.
    const Frame& start = curve.table_frames_[0];
    const Frame& end = curve.table_frames_[nodes - 1];
    const Vec3 carried = DoubleReflect(Vec3::Zero(), end.tangent, end.normal, start.tangent);
    const double angle =
        std::atan2(start.tangent.dot(start.normal.cross(carried)), start.normal.dot(carried));
    curve.holonomy_angle_ = angle / curve.length_;
    for (int j = 1; j < nodes; ++j) {
      Frame& frame = curve.table_frames_[j];
      const double turn = -curve.holonomy_angle_ * curve.table_s_[j];
      frame.normal =
          OrthonormalizeAgainst(RotateAbout(frame.normal, frame.tangent, turn), frame.tangent);
      frame.binormal = frame.tangent.cross(frame.normal);
    }
  }

  *out = std::move(curve);
  return Status::Ok();
}

bool Curve::closed() const { return closed_; }
CurveInterpolation Curve::interpolation() const { return interpolation_; }
double Curve::length() const { return length_; }
std::span<const Vec3> Curve::control_points() const { return points_; }

Vec3 Curve::Position(double v) const {
  if (table_s_.size() < 2) return points_.empty() ? Vec3::Zero() : points_.front();
  const double s = WrapOrClamp(v) * length_;
  const int node = NodeAt(s);
  return SegmentPosition(SegmentOfNode(node), ParameterAt(node, s));
}

Vec3 Curve::Tangent(double v) const {
  if (table_s_.size() < 2) return Vec3::UnitX();
  const double s = WrapOrClamp(v) * length_;
  const int node = NodeAt(s);
  const Vec3 d = SegmentDerivative(SegmentOfNode(node), ParameterAt(node, s));
  const double norm = d.norm();
  return norm > 0.0 ? Vec3(d / norm) : table_frames_[node].tangent;
}

Frame Curve::FrameAt(double v) const {
  if (table_s_.size() < 2) return Frame{};
  const double s = WrapOrClamp(v) * length_;
  const int node = NodeAt(s);
  const int segment = SegmentOfNode(node);
  const double t = ParameterAt(node, s);
  const Frame& base = table_frames_[node];
  Frame frame;
  const Vec3 d = SegmentDerivative(segment, t);
  const double norm = d.norm();
  frame.tangent = norm > 0.0 ? Vec3(d / norm) : base.tangent;
  Vec3 normal = DoubleReflect(SegmentSecant(segment, table_t_[node], t), base.tangent, base.normal,
                              frame.tangent);
  if (closed_) {
    const double turn = -holonomy_angle_ * (s - table_s_[node]);
    normal = OrthonormalizeAgainst(RotateAbout(normal, frame.tangent, turn), frame.tangent);
  }
  frame.normal = normal;
  frame.binormal = frame.tangent.cross(frame.normal);
  return frame;
}

void Curve::Resample(std::span<Vec3> out) const {
  const std::size_t n = out.size();
  if (n == 0) return;
  if (n == 1) {
    out[0] = Position(0.0);
    return;
  }
  const double divisor = static_cast<double>(closed_ ? n : n - 1);
  for (std::size_t i = 0; i < n; ++i) out[i] = Position(static_cast<double>(i) / divisor);
}

int Curve::SegmentCount() const { return static_cast<int>(knots_.size()) - 1; }

int Curve::SegmentOfNode(int node) const { return std::min(node / substeps_, SegmentCount() - 1); }

Vec3 Curve::SegmentPosition(int segment, double t) const {
  const int count = static_cast<int>(points_.size());
  const int next = (segment + 1) % count;
  const double h = knots_[segment + 1] - knots_[segment];
  const double w = std::clamp((t - knots_[segment]) / h, 0.0, 1.0);
  const double z = 1.0 - w;
  Vec3 x = z * points_[segment] + w * points_[next];
  if (interpolation_ == CurveInterpolation::kCubic) {
    x += (h * h / 6.0) *
         ((z * z * z - z) * second_derivs_[segment] + (w * w * w - w) * second_derivs_[next]);
  }
  return x;
}

Vec3 Curve::SegmentDerivative(int segment, double t) const {
  const int count = static_cast<int>(points_.size());
  const int next = (segment + 1) % count;
  const double h = knots_[segment + 1] - knots_[segment];
  Vec3 d = (points_[next] - points_[segment]) / h;
  if (interpolation_ == CurveInterpolation::kCubic) {
    const double w = std::clamp((t - knots_[segment]) / h, 0.0, 1.0);
    const double z = 1.0 - w;
    d += (h / 6.0) * ((1.0 - 3.0 * z * z) * second_derivs_[segment] +
                      (3.0 * w * w - 1.0) * second_derivs_[next]);
  }
  return d;
}

// x(t1) - x(t0) = (w1 - w0) * SegmentSecant(segment, t0, t1), with the polynomial differences
// factored so that the direction stays accurate (and tends to the tangent) as t1 -> t0.
Vec3 Curve::SegmentSecant(int segment, double t0, double t1) const {
  const int count = static_cast<int>(points_.size());
  const int next = (segment + 1) % count;
  Vec3 d = points_[next] - points_[segment];
  if (interpolation_ == CurveInterpolation::kCubic) {
    const double h = knots_[segment + 1] - knots_[segment];
    const double w0 = std::clamp((t0 - knots_[segment]) / h, 0.0, 1.0);
    const double w1 = std::clamp((t1 - knots_[segment]) / h, 0.0, 1.0);
    const double z0 = 1.0 - w0;
    const double z1 = 1.0 - w1;
    d += (h * h / 6.0) * ((w1 * w1 + w1 * w0 + w0 * w0 - 1.0) * second_derivs_[next] -
                          (z1 * z1 + z1 * z0 + z0 * z0 - 1.0) * second_derivs_[segment]);
  }
  return d;
}

double Curve::SegmentArcLength(int segment, double t0, double t1) const {
  if (interpolation_ == CurveInterpolation::kLinear) return t1 - t0;  // unit speed in t
  const double half = 0.5 * (t1 - t0);
  const double mid = 0.5 * (t0 + t1);
  double sum = 0.0;
  for (std::size_t k = 0; k < kGaussX.size(); ++k) {
    const double dt = half * kGaussX[k];
    sum += kGaussW[k] * (SegmentDerivative(segment, mid - dt).norm() +
                         SegmentDerivative(segment, mid + dt).norm());
  }
  return half * sum;
}

double Curve::WrapOrClamp(double v) const {
  if (!std::isfinite(v)) return 0.0;
  if (closed_) {
    const double wrapped = v - std::floor(v);
    return wrapped < 1.0 ? wrapped : 0.0;  // rounding can give exactly 1
  }
  return std::clamp(v, 0.0, 1.0);
}

// The table node at or before arc length s, never the last node.
int Curve::NodeAt(double s) const {
  const auto it = std::upper_bound(table_s_.begin(), table_s_.end(), s);
  const int node = static_cast<int>(it - table_s_.begin()) - 1;
  return std::clamp(node, 0, static_cast<int>(table_s_.size()) - 2);
}

// The curve parameter at arc length s, which lies in the table step starting at `node`.
double Curve::ParameterAt(int node, double s) const {
  const double ta = table_t_[node];
  const double tb = table_t_[node + 1];
  const double target = s - table_s_[node];
  if (interpolation_ == CurveInterpolation::kLinear) return std::clamp(ta + target, ta, tb);
  const double span = table_s_[node + 1] - table_s_[node];
  if (!(target > 0.0) || !(span > 0.0)) return ta;
  if (target >= span) return tb;
  const int segment = SegmentOfNode(node);
  const double tolerance = kArcLengthTolerance * span;
  double lo = ta;
  double hi = tb;
  double t = ta + (tb - ta) * (target / span);
  for (int iteration = 0; iteration < kMaxNewtonIterations; ++iteration) {
    const double residual = SegmentArcLength(segment, ta, t) - target;
    if (std::abs(residual) <= tolerance) break;
    if (residual > 0.0) {
      hi = t;
    } else {
      lo = t;
    }
    const double speed = SegmentDerivative(segment, t).norm();
    double next = 0.5 * (lo + hi);
    // Newton's step when it stays inside the bracket (tested without dividing first).
    if (std::abs(residual) < speed * (hi - lo)) {
      const double newton = t - residual / speed;
      if (newton > lo && newton < hi) next = newton;
    }
    if (next == t) break;
    t = next;
  }
  return t;
}

}  // namespace wirerig
