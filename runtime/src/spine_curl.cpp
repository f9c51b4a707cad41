#include "spine_curl.h"

#include <array>
#include <cmath>
#include <numbers>

#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/corotational_wire.h"

namespace wirerig::detail {
namespace {

// The chord from one sample to the next over unit arc length, for tangents a and b at its ends
// (exact for a circular arc between them).
Vec3 UnitChord(const Vec3& a, const Vec3& b) {
  const Vec3 sum = a + b;
  const double sum_norm = sum.norm();
  if (!(sum_norm > 1e-12)) return 0.5 * sum;  // tangents opposite: no arc between them
  const double half_angle = std::atan2((a - b).norm(), sum_norm);
  const double factor = half_angle > 1e-8 ? std::sin(half_angle) / half_angle : 1.0;
  return sum * (factor / sum_norm);
}

}  // namespace

Status CurlSpine(double length, double bending_stiffness, const SpineLoads& loads,
                 std::span<const double> samples, std::span<const Vec3> slope,
                 std::span<Vec3> displacement, std::span<Mat3> turn,
                 const SpineCurlScratch& scratch) {
  if (!IsCantilever(loads.boundary))
    return Status::Invalid("poses", "large_deflection needs a cantilever spine (free or guided)");
  if (loads.bending_point_loads.size() > std::size_t(CorotationalWireJob::kMaxPointLoads) ||
      loads.bending_line_loads.size() > std::size_t(CorotationalWireJob::kMaxLineLoads))
    return Status::Invalid("poses", "large_deflection takes at most 16 point and 8 line loads");
  const std::size_t n = samples.size();
  const Vec3 axis = Vec3::UnitZ();  // the rest tangent in local axes

  // The curl's plane: the rest tangent and the direction of the largest small-deflection
  // displacement. None (a straight wire): the small-deflection turns stand.
  Vec3 largest = Vec3::Zero();
  for (std::size_t k = 0; k < n; ++k)
    if (displacement[k].head<2>().squaredNorm() > largest.squaredNorm())
      largest = Vec3(displacement[k].x(), displacement[k].y(), 0.0);
  if (!(largest.norm() > 1e-12 * length)) {
    for (std::size_t k = 0; k < n; ++k)
      turn[k] = Quat::FromTwoVectors(axis, Vec3(slope[k].x(), slope[k].y(), 1.0).normalized())
                    .toRotationMatrix();
    return Status::Ok();
  }
  const Vec3 across = largest.normalized();  // e1: the curl turns the tangent towards it
  const Vec3 outside = axis.cross(across);   // e2: the plane's normal
  // Loads in the chain's frame: their tangential parts act too (dead, along the rest tangent).
  auto in_plane = [&](const Vec3& f) { return Vec3(f.z(), f.dot(across), 0.0); };

  // The chain in its own frame: X the rest tangent, Y across, Z outside.
  std::array<PointLoad, CorotationalWireJob::kMaxPointLoads> points;
  std::array<LineLoad, CorotationalWireJob::kMaxLineLoads> lines;
  for (std::size_t i = 0; i < loads.bending_point_loads.size(); ++i)
    points[i] = {loads.bending_point_loads[i].at, in_plane(loads.bending_point_loads[i].force)};
  for (std::size_t i = 0; i < loads.bending_line_loads.size(); ++i) {
    const LineLoad& line = loads.bending_line_loads[i];
    lines[i] = {line.from, line.to, in_plane(line.force_per_length)};
  }
  CorotationalWireJob chain;
  chain.boundary = loads.boundary;
  chain.length = length;
  chain.bending_stiffness = bending_stiffness;
  chain.segments = loads.curl_segments;
  chain.tip_force = in_plane(loads.tip_force);
  chain.tip_moment =
      loads.boundary == BoundaryCondition::kCantileverFree ? loads.tip_couple.dot(across) : 0.0;
  chain.point_loads = std::span<const PointLoad>(points.data(), loads.bending_point_loads.size());
  chain.line_loads = std::span<const LineLoad>(lines.data(), loads.bending_line_loads.size());
  chain.samples = samples;
  chain.position = scratch.chain_points.first(n);
  chain.tangent = scratch.chain_tangents.first(n);
  if (Status s = chain.Run(); !s) return Status::Invalid("poses", s.reason);

  // Each sample's tangent: the chain's angle in the plane (unwrapped past half a turn) plus the
  // wire's motion beyond its static shape, and the small turn out of the plane. In the plane,
  // the chain's positions plus the motion's turns integrated over the samples; across it, the
  // small-deflection displacement itself.
  Vec3 position = scratch.chain_points[0];
  Vec3 previous_tangent = Vec3::UnitX(), previous_static = Vec3::UnitX();
  double angle = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& chain_tangent = scratch.chain_tangents[k];
    const double chain_angle = std::atan2(chain_tangent.y(), chain_tangent.x());
    angle += std::remainder(chain_angle - angle, 2.0 * std::numbers::pi);
    const double extra = loads.extra_slope.empty() ? 0.0 : loads.extra_slope[k].dot(across);
    const double in = angle + extra;
    const Vec3 planar_tangent(std::cos(in), std::sin(in), 0.0);
    if (k > 0) {
      const double h = (samples[k] - samples[k - 1]) * length;
      position += scratch.chain_points[k] - scratch.chain_points[k - 1];
      if (extra != 0.0 || previous_tangent != previous_static)
        position += h * (UnitChord(previous_tangent, planar_tangent) -
                         UnitChord(previous_static, chain_tangent));
    }
    previous_tangent = planar_tangent;
    previous_static = chain_tangent;

    // Back to local axes.
    const double out_displacement = displacement[k].dot(outside);
    displacement[k] = loads.start_displacement.dot(across) * across + position.y() * across +
                      out_displacement * outside + (position.x() - samples[k] * length) * axis;
    const Mat3 in_turn = Eigen::AngleAxisd(in, outside).toRotationMatrix();
    const double out = std::atan(slope[k].dot(outside));
    const Vec3 local_tangent = std::cos(out) * (in_turn * axis) + std::sin(out) * outside;
    turn[k] = Quat::FromTwoVectors(in_turn * axis, local_tangent).toRotationMatrix() * in_turn;
  }
  return Status::Ok();
}

}  // namespace wirerig::detail
