#include "motion_rotation.h"

#include <cmath>
#include <numbers>

#include <Eigen/SVD>

namespace wirerig {

Mat3 SourceUpRotation(UpAxis axis) {
  Mat3 r = Mat3::Identity();
  if (axis == UpAxis::kZ) {
    r << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  } else if (axis == UpAxis::kX) {
    r << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  }
  return r;
}

Mat3 LeastRotation(const Vec3& from, const Vec3& to) {
  return Quat::FromTwoVectors(from, to).toRotationMatrix();
}

Vec3 ContinuousRotationVector(const Mat3& rotation, const std::optional<Vec3>& previous) {
  const Eigen::AngleAxisd turn(rotation);
  const double angle = turn.angle();
  Vec3 axis = turn.axis();
  if (!(angle > 1e-12)) {
    // The identity: zero, or a whole number of turns about the previous axis.
    if (!previous || !(previous->norm() > std::numbers::pi)) return Vec3::Zero();
    axis = previous->normalized();
    const double k = std::round(previous->norm() / (2.0 * std::numbers::pi));
    return (2.0 * std::numbers::pi * k) * axis;
  }
  Vec3 vector = angle * axis;
  if (previous) {
    const double k = std::round((previous->dot(axis) - angle) / (2.0 * std::numbers::pi));
    vector += (2.0 * std::numbers::pi * k) * axis;
  }
  return vector;
}

Vec3 JointAnglesOf(const JointModel& joint, const Mat3& turn) {
  // local = Rx(a) Ry(b) Rz(c): row 0 = (cb cc, -cb sc, sb), column 2 = (sb, -sa cb, ca cb).
  const Mat3 local = joint.axes.transpose() * turn * joint.axes;
  const double b = std::asin(std::clamp(local(0, 2), -1.0, 1.0));
  const double a = std::atan2(-local(1, 2), local(2, 2));
  const double c = std::atan2(-local(0, 1), local(0, 0));
  return Vec3(a, b, c) * (180.0 / std::numbers::pi);
}

Mat3 NearestRotation(const Mat3& m) {
  const double size = m.cwiseAbs().maxCoeff();
  if (!(size > 1e-30)) return Mat3::Identity();
  const Eigen::JacobiSVD<Mat3> svd(m / size, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 u = svd.matrixU();
  if ((u * svd.matrixV().transpose()).determinant() < 0.0) u.col(2) = -u.col(2);
  return u * svd.matrixV().transpose();
}

}  // namespace wirerig
