// Internal to the runtime: the spatial algebra (Featherstone, "Rigid Body Dynamics Algorithms",
// chapter 2) and the joint kinematics shared by the articulated model, its measures and its step.
// Spatial vectors put the angular part first: motion (omega, v_origin), force (moment, force).
// A body's Plucker transform from its parent is held as (R, p): R rotates body axes into parent
// axes and p is the body origin in the parent's frame, so ^iX_parent = [[R^T, 0], [-R^T p x, R^T]].
// Nothing here allocates or raises a floating-point exception on finite inputs.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>

#include "wirerig/runtime/articulated_body.h"

namespace wirerig::detail {

using Coordinates = ArticulatedWorkspace::Coordinates;

inline Mat3 Skew(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// ---------------------------------------------------------------------------------------
// Rotations.

// The rotation matrix of the quaternion with coefficients c = (x, y, z, w), homogeneous in c
// (divided by |c|^2, so RK4's stage quaternions need not be unit); identity if c is ~0.
inline Mat3 RotationOf(const Eigen::Vector4d& c) {
  const double x = c.x(), y = c.y(), z = c.z(), w = c.w();
  const double n2 = w * w + x * x + y * y + z * z;
  if (!(n2 > 1e-30)) return Mat3::Identity();
  Mat3 r;
  r << w * w + x * x - y * y - z * z, 2.0 * (x * y - w * z), 2.0 * (x * z + w * y),
      2.0 * (x * y + w * z), w * w - x * x + y * y - z * z, 2.0 * (y * z - w * x),
      2.0 * (x * z - w * y), 2.0 * (y * z + w * x), w * w - x * x - y * y + z * z;
  return r / n2;
}

inline Mat3 RotationX(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 r;
  r << 1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c;
  return r;
}

// exp of the rotation vector phi: the unit quaternion turning by |phi| about phi.
inline Quat ExpMap(const Vec3& phi) {
  const double angle = phi.norm();
  const double s = angle < 1e-4 ? 0.5 - angle * angle / 48.0 : std::sin(0.5 * angle) / angle;
  return Quat(std::cos(0.5 * angle), s * phi.x(), s * phi.y(), s * phi.z());
}

// The rotation vector of a unit quaternion, the shorter way (angle in [0, pi]).
inline Vec3 LogMap(const Quat& q) {
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  const Vec3 v = sign * q.vec();
  const double w = sign * q.w();
  const double s = v.norm();
  if (s < 1e-8) return (2.0 / std::max(w, 0.5)) * v;  // w ~ 1 here
  return (2.0 * std::atan2(s, w) / s) * v;
}

// The left Jacobian V of SO(3) at phi: exp of the body twist (omega, v) over unit time moves the
// origin by V(omega) v, with V = 1 + (1 - cos a)/a^2 [phi]x + (a - sin a)/a^3 [phi]x^2.
inline Mat3 LeftJacobian(const Vec3& phi) {
  const double a2 = phi.squaredNorm();
  const double a = std::sqrt(a2);
  double b, c;
  if (a < 1e-3) {
    b = 0.5 - a2 / 24.0 + a2 * a2 / 720.0;
    c = 1.0 / 6.0 - a2 / 120.0 + a2 * a2 / 5040.0;
  } else {
    b = (1.0 - std::cos(a)) / a2;
    c = (a - std::sin(a)) / (a2 * a);
  }
  const Mat3 k = Skew(phi);
  return Mat3::Identity() + b * k + c * k * k;
}

// X-Y-Z intrinsic Euler angles (rotation = Rx(x) Ry(y) Rz(z), JointModel's) of a rotation
// matrix: x, z in (-pi, pi], y in [-pi/2, pi/2].
inline Vec3 EulerXyz(const Mat3& r) {
  const double sy = std::clamp(r(0, 2), -1.0, 1.0);
  return Vec3(std::atan2(-r(1, 2), r(2, 2)), std::asin(sy), std::atan2(-r(0, 1), r(0, 0)));
}

// The matrix E with omega_body = E (x', y', z')^T for the angles' rates. Its determinant is
// cos y; near the chart's gimbal lock cos y is held at +-kMinCosY so E stays invertible.
inline constexpr double kMinCosY = 0.05;
inline Mat3 EulerRateMatrix(const Vec3& angles) {
  const double sy = std::sin(angles.y()), cz = std::cos(angles.z()), sz = std::sin(angles.z());
  double cy = std::cos(angles.y());
  cy = cy < 0.0 ? std::min(cy, -kMinCosY) : std::max(cy, kMinCosY);
  Mat3 e;
  e << cy * cz, sz, 0.0, -cy * sz, cz, 0.0, sy, 0.0, 1.0;
  return e;
}

// ---------------------------------------------------------------------------------------
// Spatial algebra.

// A motion vector from the parent's coordinates to the body's: ^iX_parent m.
inline Vec6 MotionToBody(const Mat3& r, const Vec3& p, const Vec6& m) {
  const Vec3 w = m.head<3>();
  Vec6 out;
  out.head<3>() = r.transpose() * w;
  out.tail<3>() = r.transpose() * (m.tail<3>() - p.cross(w));
  return out;
}

// A force vector from the body's coordinates to the parent's: ^iX_parent^T f.
inline Vec6 ForceToParent(const Mat3& r, const Vec3& p, const Vec6& f) {
  Vec6 out;
  out.tail<3>() = r * f.tail<3>();
  out.head<3>() = r * f.head<3>() + p.cross(out.tail<3>());
  return out;
}

// A force vector from world coordinates to the body's, the body at (r, p) in the world.
inline Vec6 ForceToBody(const Mat3& r, const Vec3& p, const Vec6& f) {
  Vec6 out;
  out.tail<3>() = r.transpose() * f.tail<3>();
  out.head<3>() = r.transpose() * (f.head<3>() - p.cross(f.tail<3>()));
  return out;
}

// An inertia from the body's coordinates to the parent's: X^T I X. Rotated block by block, then
// shifted: with I = [[A, B], [B^T, C]] in parent axes and P = [p]x, the result is
// [[A + P B^T - B P - P C P, B + P C], [B^T - C P, C]].
inline Mat6 InertiaToParent(const Mat3& r, const Vec3& p, const Mat6& inertia) {
  const Mat3 a = r * inertia.topLeftCorner<3, 3>() * r.transpose();
  const Mat3 b = r * inertia.topRightCorner<3, 3>() * r.transpose();
  const Mat3 c = r * inertia.bottomRightCorner<3, 3>() * r.transpose();
  const Mat3 px = Skew(p);
  const Mat3 pc = px * c;
  Mat6 out;
  out.topLeftCorner<3, 3>() = a + px * b.transpose() - b * px - pc * px;
  out.topRightCorner<3, 3>() = b + pc;
  out.bottomLeftCorner<3, 3>() = b.transpose() - c * px;
  out.bottomRightCorner<3, 3>() = c;
  return out;
}

// v x m for motion vectors (v x_m) and v x f for force vectors (v x_f).
inline Vec6 CrossMotion(const Vec6& v, const Vec6& m) {
  const Vec3 w = v.head<3>();
  Vec6 out;
  out.head<3>() = w.cross(m.head<3>());
  out.tail<3>() = w.cross(m.tail<3>()) + v.tail<3>().cross(m.head<3>());
  return out;
}
inline Vec6 CrossForce(const Vec6& v, const Vec6& f) {
  const Vec3 w = v.head<3>();
  Vec6 out;
  out.head<3>() = w.cross(f.head<3>()) + v.tail<3>().cross(f.tail<3>());
  out.tail<3>() = w.cross(f.tail<3>());
  return out;
}

// ---------------------------------------------------------------------------------------
// Joint kinematics.

// Body i's transform from its parent at coordinates c: *r body axes -> parent axes, *p its
// origin in the parent's frame.
inline void JointTransform(const ArticulatedModel& model, int i, const Coordinates& c, Mat3* r,
                           Vec3* p) {
  const ArticulatedBodyDesc& body = model.body(i);
  const Mat3& axes = model.joint_axes(i);
  *p = body.joint_position;
  switch (body.joint) {
    case ArticulatedJointType::kHinge:
      *r = axes * RotationX(c.angle);
      break;
    case ArticulatedJointType::kBall:
      *r = axes * RotationOf(c.quaternion);
      break;
    case ArticulatedJointType::kFloating:
      *r = axes * RotationOf(c.quaternion);
      *p += axes * c.translation;
      break;
    case ArticulatedJointType::kFixed:
    default:
      *r = axes;
      break;
  }
}

// The joint's relative spatial velocity S qdot in body coordinates from its generalised
// velocity nu (head(dofs)): S selects the first dofs components (hinge: omega_x; ball: omega;
// floating: (omega, v)).
inline Vec6 JointVelocity(int dofs, const Vec6& nu) {
  Vec6 out = Vec6::Zero();
  out.head(dofs) = nu.head(dofs);
  return out;
}

// Reads a joint's state into coordinates and a generalised velocity (floating: v in body axes).
inline void LoadJoint(ArticulatedJointType type, const JointState& joint, Coordinates* c,
                      Vec6* nu) {
  nu->setZero();
  switch (type) {
    case ArticulatedJointType::kHinge:
      c->angle = joint.angle;
      (*nu)(0) = joint.angular_velocity.x();
      break;
    case ArticulatedJointType::kBall:
      c->quaternion = joint.rotation.coeffs();
      nu->head<3>() = joint.angular_velocity;
      break;
    case ArticulatedJointType::kFloating:
      c->quaternion = joint.rotation.coeffs();
      c->translation = joint.translation;
      nu->head<3>() = joint.angular_velocity;
      nu->tail<3>() = RotationOf(c->quaternion).transpose() * joint.linear_velocity;
      break;
    case ArticulatedJointType::kFixed:
    default:
      break;
  }
}

// Writes coordinates (quaternions assumed unit) and a generalised velocity into a joint state.
inline void StoreJoint(ArticulatedJointType type, const Coordinates& c, const Vec6& nu,
                       JointState* joint) {
  switch (type) {
    case ArticulatedJointType::kHinge:
      joint->angle = c.angle;
      joint->rotation = Quat(Eigen::AngleAxisd(c.angle, Vec3::UnitX()));
      joint->angular_velocity = Vec3(nu(0), 0.0, 0.0);
      break;
    case ArticulatedJointType::kBall:
      joint->rotation.coeffs() = c.quaternion;
      joint->angular_velocity = nu.head<3>();
      break;
    case ArticulatedJointType::kFloating:
      joint->rotation.coeffs() = c.quaternion;
      joint->angular_velocity = nu.head<3>();
      joint->translation = c.translation;
      joint->linear_velocity = RotationOf(c.quaternion) * nu.tail<3>();
      break;
    case ArticulatedJointType::kFixed:
    default:
      joint->rotation = Quat::Identity();
      joint->angular_velocity.setZero();
      break;
  }
}

// Body i's world motion from its coordinates and generalised velocity, its parent's already in
// out[parent] (bodies are evaluated parents first).
inline void EvaluateBody(const ArticulatedModel& model, int i, const Coordinates& c, const Vec6& nu,
                         std::span<BodyMotion> out) {
  Mat3 r;
  Vec3 p;
  JointTransform(model, i, c, &r, &p);
  const int parent = model.body(i).parent;
  Mat3 parent_rotation = Mat3::Identity();
  Vec3 parent_position = Vec3::Zero(), parent_omega = Vec3::Zero(), parent_v = Vec3::Zero();
  if (parent >= 0) {
    const BodyMotion& pm = out[parent];
    parent_rotation = pm.rotation.toRotationMatrix();
    parent_position = pm.translation;
    parent_omega = pm.angular_velocity;
    parent_v = pm.linear_velocity;
  }
  const Mat3 world = parent_rotation * r;
  const Vec3 origin = parent_position + parent_rotation * p;
  const Vec6 joint = JointVelocity(model.dofs(i), nu);
  BodyMotion& m = out[i];
  m.rotation = Quat(world).normalized();
  m.translation = origin;
  m.angular_velocity = parent_omega + world * joint.head<3>();
  m.linear_velocity =
      parent_v + parent_omega.cross(origin - parent_position) + world * joint.tail<3>();
}

// Checks a state against the model (see ArticulatedStepJob::Validate, field "state").
Status CheckArticulatedState(const ArticulatedModel& model, const ArticulatedState& state);

}  // namespace wirerig::detail
