// Curve: the geometry of a wire. A curve through control points, open or closed, linear or
// C2 cubic (chord-length parameterised natural spline when open, periodic when closed),
// reparameterised by arc length: v in [0, 1] with s = L v, L the physical length in metres.
// Gives positions, unit tangents and rotation-minimizing frames at any v, and resampling at
// equal arc length. Build allocates; every query is const, allocation-free and thread-safe.
#pragma once

#include <span>
#include <vector>

#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

enum class CurveInterpolation : int { kLinear = 0, kCubic = 1 };

// An orthonormal, right-handed frame: binormal = tangent x normal.
struct Frame {
  Vec3 tangent = Vec3::UnitX();
  Vec3 normal = Vec3::UnitY();
  Vec3 binormal = Vec3::UnitZ();
};

class Curve {
 public:
  Curve() = default;

  // Builds the curve through `points` (#P by 3, metres). Refuses (and leaves *out untouched):
  // fewer than 2 points (3 when closed) or more than 2^24, non-finite coordinates (or beyond
  // 1e100 m), consecutive coincident points (closer than 1e-12 of the bounding-box diagonal,
  // or than 1e-100 m).
  // A closed curve joins the last point back to the first; do not repeat the first point.
  static Status Build(std::span<const Vec3> points, bool closed, CurveInterpolation interpolation,
                      Curve* out);

  bool closed() const;
  CurveInterpolation interpolation() const;
  double length() const;  // L, m
  std::span<const Vec3> control_points() const;

  // v is clamped to [0, 1] (wrapped for closed curves). Position in m.
  Vec3 Position(double v) const;
  // Unit tangent d(position)/ds.
  Vec3 Tangent(double v) const;
  // Rotation-minimizing frame (double reflection, Wang et al. 2008). For closed curves the
  // holonomy is spread evenly along the length so that Frame(0) == Frame(1). The normal at
  // v = 0 is the world axis least aligned with the tangent (ties: x before y before z), made
  // perpendicular to it. On a linear curve the frame turns at the corners, like the tangent.
  Frame FrameAt(double v) const;

  // Writes out.size() points at equal arc length: v_i = i/(n-1) when open, i/n when closed
  // (the first point is not repeated). Needs out.size() >= 2.
  void Resample(std::span<Vec3> out) const;

 private:
  // Filled by Build; see curve.cpp for the tables' meaning. Segment i joins control point i
  // to i + 1 (to 0 for the closing segment of a closed curve). The arc-length table has
  // substeps_ nodes per segment plus a final node at the end of the curve.
  int SegmentCount() const;
  int SegmentOfNode(int node) const;
  Vec3 SegmentPosition(int segment, double t) const;
  Vec3 SegmentDerivative(int segment, double t) const;
  Vec3 SegmentSecant(int segment, double t0, double t1) const;
  double SegmentArcLength(int segment, double t0, double t1) const;
  double WrapOrClamp(double v) const;
  int NodeAt(double s) const;
  double ParameterAt(int node, double s) const;

  std::vector<Vec3> points_;
  bool closed_ = false;
  CurveInterpolation interpolation_ = CurveInterpolation::kLinear;
  int substeps_ = 1;                 // table sub-steps per segment
  std::vector<double> knots_;        // chord-length parameter at each segment end, m
  std::vector<Vec3> second_derivs_;  // spline second derivatives at control points (cubic)
  std::vector<double> table_t_;      // curve parameter at arc-length table nodes
  std::vector<double> table_s_;      // arc length at table nodes, m
  std::vector<Frame> table_frames_;  // rotation-minimizing frames at table nodes (corrected)
  double holonomy_angle_ = 0.0;      // closed curves: twist removed per unit length (rad/m)
  double length_ = 0.0;
};

}  // namespace wirerig
