#include "wirerig/runtime/joint.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wirerig {

Status ValidateJoint(const JointModel& joint) {
  if (!joint.axes.allFinite() ||
      !(joint.axes.transpose() * joint.axes).isApprox(Mat3::Identity(), 1e-9) ||
      !(joint.axes.determinant() > 0.0))
    return Status::Invalid("axes", "must be finite, orthonormal and right-handed");
  for (int k = 0; k < 3; ++k)
    if (!(std::isfinite(joint.min_degrees[k]) && std::isfinite(joint.max_degrees[k]) &&
          joint.min_degrees[k] <= joint.max_degrees[k]))
      return Status::Invalid("limits", "must be finite with the lower limit <= the upper");
  if (!joint.parent_axis.allFinite() || std::abs(joint.parent_axis.norm() - 1.0) > 1e-9)
    return Status::Invalid("parent_axis", "must be a finite unit vector");
  if (!(std::isfinite(joint.blend_length) && joint.blend_length >= 0.0))
    return Status::Invalid("blend_length", "must be finite and >= 0");
  if (!(std::isfinite(joint.radius) && joint.radius >= 0.0))
    return Status::Invalid("radius", "must be finite and >= 0");
  if (!(std::isfinite(joint.parent_radius) && joint.parent_radius >= 0.0))
    return Status::Invalid("parent_radius", "must be finite and >= 0");
  for (double growth : joint.growth_scales)
    if (!(std::isfinite(growth) && growth >= kMinGrowthScale && growth <= kMaxGrowthScale))
      return Status::Invalid("growth_scales", "growth_scales must each be in [-2, 4]");
  return Status::Ok();
}

Vec3 ClampJointAngles(const JointModel& joint, const Vec3& degrees) {
  Vec3 out = degrees.cwiseMax(joint.min_degrees).cwiseMin(joint.max_degrees);
  if (joint.type == JointType::kHinge) out.tail<2>().setZero();
  if (joint.type == JointType::kFixed) out.setZero();
  return out;
}

Quat JointRotation(const JointModel& joint, const Vec3& degrees) {
  const Vec3 a = ClampJointAngles(joint, degrees) * (std::numbers::pi / 180.0);
  const Quat local = Quat(Eigen::AngleAxisd(a.x(), Vec3::UnitX())) *
                     Quat(Eigen::AngleAxisd(a.y(), Vec3::UnitY())) *
                     Quat(Eigen::AngleAxisd(a.z(), Vec3::UnitZ()));
  const Quat frame(joint.axes);
  return (frame * local * frame.conjugate()).normalized();
}

void SwingTwist(const Quat& rotation, const Vec3& axis, Quat* swing, Quat* twist) {
  const double along = rotation.vec().dot(axis);
  Quat t(rotation.w(), along * axis.x(), along * axis.y(), along * axis.z());
  const double norm = t.norm();
  t = norm > 1e-12 ? Quat(t.coeffs() / norm) : Quat::Identity();
  *twist = t;
  *swing = (rotation * t.conjugate()).normalized();
}

double BendGrowthScale(const JointModel& joint, const Quat& swing) {
  // sin^2 of half of 5 degrees: the weight of the directions' mean at small bends.
  constexpr double kRestWeight = 0.0019;
  const Vec3 axis = swing.w() < 0.0 ? Vec3(-swing.vec()) : Vec3(swing.vec());
  const double x = axis.dot(joint.axes.col(0)), y = axis.dot(joint.axes.col(1));
  const double along_x = joint.growth_scales[x >= 0.0 ? kGrowPlusX : kGrowMinusX];
  const double along_y = joint.growth_scales[y >= 0.0 ? kGrowPlusY : kGrowMinusY];
  const std::array<double, 4>& g = joint.growth_scales;
  const double mean = 0.25 * (g[0] + g[1] + g[2] + g[3]);
  return (x * x * along_x + y * y * along_y + kRestWeight * mean) / (x * x + y * y + kRestWeight);
}

Quat ScaleRotation(const Quat& rotation, double t) {
  Quat q = rotation.w() < 0.0 ? Quat(-rotation.coeffs()) : rotation;
  const double s = q.vec().norm();
  if (s < 1e-15) return Quat::Identity();
  const double half = std::atan2(s, q.w()) * t;
  const Vec3 axis = q.vec() / s;
  return Quat(std::cos(half), std::sin(half) * axis.x(), std::sin(half) * axis.y(),
              std::sin(half) * axis.z());
}

}  // namespace wirerig
