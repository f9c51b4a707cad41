#include "wirerig/runtime/spine_interpolation.h"

#include "wirerig/runtime/rig_model.h"

#include <algorithm>
#include <cmath>

namespace wirerig {

Mat3 FrameAxes(const Frame& frame) {
  Mat3 m;
  m.col(0) = frame.normal;
  m.col(1) = frame.binormal;
  m.col(2) = frame.tangent;
  return m;
}

Frame InterpolateSpine(std::span<const Vec3> points, std::span<const Frame> frames, double v,
                       Vec3* point) {
  const std::size_t n = points.size();
  const double x = std::clamp(std::isfinite(v) ? v : 0.0, 0.0, 1.0) * double(n - 1);
  const std::size_t k = std::min(static_cast<std::size_t>(x), n - 2);
  const double f = x - double(k);
  *point = (1.0 - f) * points[k] + f * points[k + 1];
  auto quaternion = [](const Frame& frame) { return Quat(FrameAxes(frame)); };
  const Mat3 r = quaternion(frames[k]).slerp(f, quaternion(frames[k + 1])).toRotationMatrix();
  return {r.col(2), r.col(0), r.col(1)};
}

void PropagateSpineFrames(std::span<const Vec3> points, const Frame& start,
                          std::span<Frame> frames) {
  const std::size_t n = points.size();
  auto direction = [&](std::size_t k) {
    const Vec3 d = points[std::min(k + 1, n - 1)] - points[k == n - 1 ? k - 1 : k];
    const double length = d.norm();
    return length > 0.0 ? Vec3(d / length) : start.tangent;
  };
  Frame current = start;
  const Vec3 t0 = direction(0);
  const Quat turn = Quat::FromTwoVectors(start.tangent, t0);
  current = Frame{turn * start.tangent, turn * start.normal, turn * start.binormal};
  frames[0] = current;
  for (std::size_t k = 1; k < n; ++k) {
    const Vec3 v1 = points[k] - points[k - 1];
    const double c1 = v1.squaredNorm();
    const Vec3 t_next = direction(k);
    if (c1 <= 0.0) {
      frames[k] = current;
      continue;
    }
    const Vec3 r_l = current.normal - (2.0 / c1) * v1.dot(current.normal) * v1;
    const Vec3 t_l = current.tangent - (2.0 / c1) * v1.dot(current.tangent) * v1;
    const Vec3 v2 = t_next - t_l;
    const double c2 = v2.squaredNorm();
    Vec3 normal = c2 > 0.0 ? Vec3(r_l - (2.0 / c2) * v2.dot(r_l) * v2) : r_l;
    normal -= normal.dot(t_next) * t_next;
    const double length = normal.norm();
    if (length > 0.0)
      normal /= length;
    else
      normal = current.normal;
    current = {t_next, normal, t_next.cross(normal)};
    frames[k] = current;
  }
}

bool ProfilesCross(std::span<const Vec3> a_points, const Vec3& a_origin, const Vec3& a_normal,
                   std::span<const Vec3> b_points, const Vec3& b_origin, const Vec3& b_normal) {
  for (const Vec3& p : a_points)
    if ((p - b_origin).dot(b_normal) > 0.0) return true;
  for (const Vec3& p : b_points)
    if ((p - a_origin).dot(a_normal) < 0.0) return true;
  return false;
}

std::vector<Vec3> RestProfilePoints(const PartModel& part, std::size_t profile, Vec3* origin) {
  const ProfileModel& loop = part.profiles[profile];
  Vec3 point;
  const Mat3 axes =
      FrameAxes(InterpolateSpine(part.spine_points, part.spine_frames, loop.spine_v, &point));
  std::vector<Vec3> out;
  out.reserve(loop.local_points.size());
  for (const Vec3& x : loop.local_points) out.push_back(point + axes * x);
  if (origin != nullptr) *origin = point;
  return out;
}

}  // namespace wirerig
