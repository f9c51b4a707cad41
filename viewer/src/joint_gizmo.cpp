#include "wirerig/viewer/joint_gizmo.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "wirerig/runtime/spine_interpolation.h"

namespace wirerig {
namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;

// Distance from `p` to the segment [a, b], pixels.
float SegmentDistance(const Vec2f& p, const Vec2f& a, const Vec2f& b) {
  const Vec2f ab = b - a;
  const float length2 = ab.squaredNorm();
  const float t = length2 > 0.0f ? std::clamp((p - a).dot(ab) / length2, 0.0f, 1.0f) : 0.0f;
  return (a + t * ab - p).norm();
}

// The segment of the ring's closed polyline nearest `pixel`: its first point's index.
std::size_t NearestSegment(const JointGizmoRing& ring, const Vec2f& pixel, float* distance) {
  const std::size_t n = ring.pixels.size();
  std::size_t best = 0;
  float best_distance = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const float d = SegmentDistance(pixel, ring.pixels[i], ring.pixels[(i + 1) % n]);
    if (d < best_distance) {
      best_distance = d;
      best = i;
    }
  }
  *distance = best_distance;
  return best;
}

}  // namespace

PosedJoint PoseJoint(const RigModel& model, const RigWorkspace& workspace, std::size_t part,
                     const PartPose& pose, const Vec3& interactive_degrees) {
  const PartModel& child = model.parts[part];
  // The pose's rotation without the interactive turn it ends with.
  const Quat own =
      (pose.rotation * JointRotation(child.joint, interactive_degrees).conjugate()).normalized();
  Mat3 follow = Mat3::Identity();
  Vec3 rest_origin = Vec3::Zero(), moved_origin = Vec3::Zero();
  if (child.parent >= 0) {
    const auto parent = static_cast<std::size_t>(child.parent);
    const PartModel& p = model.parts[parent];
    const Frame rest =
        InterpolateSpine(p.spine_points, p.spine_frames, child.attachment, &rest_origin);
    const Frame moved =
        InterpolateSpine(workspace.spine_points[parent], workspace.spine_frames[parent],
                         child.attachment, &moved_origin);
    follow = FrameAxes(moved) * FrameAxes(rest).transpose();
  }
  PosedJoint posed;
  posed.center =
      moved_origin + follow * (child.spine_points.front() + pose.translation - rest_origin);
  posed.frame = follow * own.toRotationMatrix() * child.joint.axes;
  return posed;
}

Mat3 JointGizmoAxes(const JointModel& joint, const Mat3& frame, const Vec3& degrees) {
  const Vec3 a = ClampJointAngles(joint, degrees) / kDegrees;
  const Mat3 x = Eigen::AngleAxisd(a.x(), Vec3::UnitX()).toRotationMatrix();
  const Mat3 y = Eigen::AngleAxisd(a.y(), Vec3::UnitY()).toRotationMatrix();
  Mat3 axes;
  axes.col(0) = frame.col(0);
  axes.col(1) = frame * x * Vec3::UnitY();
  axes.col(2) = frame * x * y * Vec3::UnitZ();
  return axes;
}

JointGizmo BuildJointGizmo(const Camera& camera, Size size, const Vec3& center, const Mat3& axes,
                           JointType type, const JointGizmoOptions& options) {
  JointGizmo gizmo;
  gizmo.options = options;
  gizmo.center = center;
  const int count = type == JointType::kBall ? 3 : type == JointType::kHinge ? 1 : 0;
  float depth = 0.0f;
  if (count == 0 || size.height <= 0 ||
      !ProjectToPixel(camera, size, center.cast<float>(), &gizmo.center_pixel, &depth))
    return gizmo;
  // Metres per pixel at the joint's depth: the ring keeps its size on screen.
  const double metres_per_pixel =
      double(depth) * 2.0 * std::tan(0.5 * double(camera.fov_y)) / double(size.height);
  gizmo.radius = double(options.radius_pixels) * metres_per_pixel;
  gizmo.radius_pixels = options.radius_pixels;
  const Vec3 to_eye = (camera.Eye().cast<double>() - center).normalized();
  const int segments = std::max(options.segments, 8);
  gizmo.rings.resize(std::size_t(count));
  for (int k = 0; k < count; ++k) {
    JointGizmoRing& ring = gizmo.rings[std::size_t(k)];
    ring.axis = k;
    ring.world_axis = axes.col(k).normalized();
    const Vec3& u = ring.world_axis;
    ring.facing = u.dot(to_eye);
    // Point 0: nearest the eye; face-on, the ring's top on screen.
    Vec3 e1 = to_eye - ring.facing * u;
    if (e1.norm() < 1e-3) {
      const Vec3 up = camera.Up().cast<double>();
      e1 = up - u.dot(up) * u;
      if (e1.norm() < 1e-3) e1 = u.unitOrthogonal();
    }
    e1.normalize();
    const Vec3 e2 = u.cross(e1);  // e1 x e2 = u: increasing angle is a positive turn about u
    ring.pixels.resize(std::size_t(segments));
    ring.toward_eye.resize(std::size_t(segments));
    for (int i = 0; i < segments; ++i) {
      const double t = 2.0 * std::numbers::pi * double(i) / double(segments);
      const Vec3 offset = gizmo.radius * (std::cos(t) * e1 + std::sin(t) * e2);
      if (!ProjectToPixel(camera, size, (center + offset).cast<float>(),
                          &ring.pixels[std::size_t(i)])) {
        gizmo.rings.clear();
        return gizmo;
      }
      ring.toward_eye[std::size_t(i)] = float(offset.dot(to_eye) / gizmo.radius);
    }
  }
  gizmo.visible = true;
  return gizmo;
}

int HitTestJointGizmo(const JointGizmo& gizmo, const Vec2f& pixel) {
  if (!gizmo.visible) return -1;
  int best = -1;
  float best_score = std::numeric_limits<float>::infinity();
  for (std::size_t r = 0; r < gizmo.rings.size(); ++r) {
    const JointGizmoRing& ring = gizmo.rings[r];
    const std::size_t n = ring.pixels.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;
      const float d = SegmentDistance(pixel, ring.pixels[i], ring.pixels[j]);
      if (d > gizmo.options.pick_pixels) continue;
      const bool front = ring.toward_eye[i] >= -1e-6f || ring.toward_eye[j] >= -1e-6f;
      const float score = d + (front ? 0.0f : 2.0f);
      if (score < best_score) {
        best_score = score;
        best = int(r);
      }
    }
  }
  return best;
}

double SweptRingDegrees(const JointGizmo& gizmo, int ring, const Vec2f& from, const Vec2f& to) {
  if (ring < 0 || std::size_t(ring) >= gizmo.rings.size()) return 0.0;
  const Eigen::Vector2d a = (from - gizmo.center_pixel).cast<double>();
  const Eigen::Vector2d b = (to - gizmo.center_pixel).cast<double>();
  if (a.norm() < 1e-6 || b.norm() < 1e-6) return 0.0;
  // Pixels run y down: a positive cross product here is clockwise on screen. A positive turn
  // about an axis pointing at the eye is anticlockwise on screen, one pointing away clockwise.
  const double clockwise = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
  const double sign = gizmo.rings[std::size_t(ring)].facing >= 0.0 ? 1.0 : -1.0;
  return -sign * clockwise * kDegrees;
}

JointGizmoDrag BeginJointGizmoDrag(const JointGizmo& gizmo, int ring, const Vec2f& pixel,
                                   const Vec3& degrees) {
  JointGizmoDrag drag;
  if (ring < 0 || std::size_t(ring) >= gizmo.rings.size()) return drag;
  const JointGizmoRing& r = gizmo.rings[std::size_t(ring)];
  drag.ring = ring;
  drag.axis = r.axis;
  drag.start_degrees = degrees;
  drag.last_pixel = pixel;
  if (std::abs(r.facing) < double(gizmo.options.edge_on_cosine) && !r.pixels.empty()) {
    float distance = 0.0f;
    const std::size_t i = NearestSegment(r, pixel, &distance);
    const Vec2f step = r.pixels[(i + 1) % r.pixels.size()] - r.pixels[i];
    if (step.norm() > 1e-6f) {
      drag.along_tangent = true;
      drag.tangent = step.normalized();
    }
  }
  return drag;
}

Vec3 UpdateJointGizmoDrag(const JointGizmo& gizmo, const JointModel& joint, const Vec2f& pixel,
                          JointGizmoDrag* drag) {
  if (drag->ring < 0) return ClampJointAngles(joint, drag->start_degrees);
  double delta = 0.0;
  if (drag->along_tangent) {
    const double travel = double((pixel - drag->last_pixel).dot(drag->tangent));
    delta = travel / std::max(double(gizmo.radius_pixels), 1.0) * kDegrees;
  } else {
    delta = SweptRingDegrees(gizmo, drag->ring, drag->last_pixel, pixel);
  }
  drag->swept_degrees += delta;
  drag->last_pixel = pixel;
  return TurnJointAngles(joint, drag->start_degrees, drag->axis, drag->swept_degrees);
}

Vec3 TurnJointAngles(const JointModel& joint, const Vec3& degrees, int axis, double delta) {
  Vec3 turned = degrees;
  if (axis >= 0 && axis < 3) turned[axis] += delta;
  return ClampJointAngles(joint, turned);
}

}  // namespace wirerig
