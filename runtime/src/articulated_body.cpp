// The articulated model (building and checking it), its states and workspaces, and the
// measures of a state. The step itself is in articulated_step.cpp.
#include "wirerig/runtime/articulated_body.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>
#include <utility>

#include <Eigen/Eigenvalues>

#include "articulated_internal.h"

namespace wirerig {
namespace {

constexpr double kUnitTolerance = 1e-6;     // of |q|^2 for unit quaternions
constexpr double kInertiaTolerance = 1e-9;  // relative, symmetry and the triangle inequality
constexpr double kDegrees = std::numbers::pi / 180.0;

bool Finite(const Vec3& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}
bool FiniteQuat(const Quat& q) {
  return std::isfinite(q.w()) && std::isfinite(q.x()) && std::isfinite(q.y()) &&
         std::isfinite(q.z());
}
bool UnitQuat(const Quat& q) {
  return FiniteQuat(q) && std::abs(q.w()) <= 2.0 && q.vec().cwiseAbs().maxCoeff() <= 2.0 &&
         std::abs(q.squaredNorm() - 1.0) <= kUnitTolerance;
}

Status BodyError(std::string_view field, int i, std::string_view reason) {
  return Status::InvalidElement(field, i, "", reason);
}

Status CheckInertia(const Mat3& inertia, int i) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(inertia(r, c)) || std::abs(inertia(r, c)) > 1e150)
        return BodyError("inertia", i, "must be finite, within 1e150 (kg m^2)");
  const double scale = inertia.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) return BodyError("inertia", i, "must be positive definite");
  if (!((inertia - inertia.transpose()).cwiseAbs().maxCoeff() <= kInertiaTolerance * scale))
    return BodyError("inertia", i, "must be symmetric");
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(0.5 * (inertia + inertia.transpose()),
                                                   Eigen::EigenvaluesOnly);
  const Vec3 moments = solver.eigenvalues();  // ascending
  if (!(moments(0) > 0.0)) return BodyError("inertia", i, "must be positive definite");
  if (moments(2) > (moments(0) + moments(1)) * (1.0 + kInertiaTolerance))
    return BodyError("inertia", i,
                     "is not physical: a principal moment exceeds the sum of the other two");
  return Status::Ok();
}

Status CheckBody(std::span<const ArticulatedBodyDesc> bodies, int i) {
  const ArticulatedBodyDesc& b = bodies[i];
  if (!(b.parent >= -1 && b.parent < i))
    return BodyError("parent", i, "must be -1 (the world) or an earlier body");
  switch (b.joint) {
    case ArticulatedJointType::kFixed:
    case ArticulatedJointType::kHinge:
    case ArticulatedJointType::kBall:
      break;
    case ArticulatedJointType::kFloating:
      if (b.parent != -1) return BodyError("joint", i, "floating joints must be roots");
      break;
    default:
      return BodyError("joint", i, "unknown joint type");
  }
  if (!Finite(b.joint_position) || b.joint_position.cwiseAbs().maxCoeff() > 1e150)
    return BodyError("joint_position", i, "must be finite, within 1e150 (m)");
  if (!UnitQuat(b.joint_rotation))
    return BodyError("joint_rotation", i, "must be a unit quaternion");
  if (!(std::isfinite(b.mass) && b.mass > 0.0 && b.mass <= 1e150))
    return BodyError("mass", i, "must be positive and finite, within 1e150 (kg)");
  if (!Finite(b.center_of_mass) || b.center_of_mass.cwiseAbs().maxCoeff() > 1e50)
    return BodyError("center_of_mass", i, "must be finite, within 1e50 (m)");
  if (Status s = CheckInertia(b.inertia, i); !s) return s;
  if (!(std::isfinite(b.damping) && b.damping >= 0.0 && b.damping <= 1e150))
    return BodyError("damping", i, "must be finite and >= 0 (N m s/rad)");
  constexpr std::string_view kAxes[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k)
    if (!(std::isfinite(b.min_degrees[k]) && std::isfinite(b.max_degrees[k]) &&
          b.min_degrees[k] <= b.max_degrees[k]))
      return Status::InvalidElement("limits", i, kAxes[k],
                                    "must be finite with min_degrees <= max_degrees");
  if (!(std::isfinite(b.limit_frequency) && b.limit_frequency > 0.0 && b.limit_frequency <= 1e6))
    return BodyError("limit_frequency", i, "must be positive and finite, within 1e6 (Hz)");
  if (!(std::isfinite(b.limit_damping_ratio) && b.limit_damping_ratio >= 0.0 &&
        b.limit_damping_ratio <= 1e6))
    return BodyError("limit_damping_ratio", i, "must be finite and >= 0");
  return Status::Ok();
}

int DofsOf(ArticulatedJointType type) {
  switch (type) {
    case ArticulatedJointType::kHinge:
      return 1;
    case ArticulatedJointType::kBall:
      return 3;
    case ArticulatedJointType::kFloating:
      return 6;
    case ArticulatedJointType::kFixed:
    default:
      return 0;
  }
}

}  // namespace

Status ArticulatedModel::Build(std::span<const ArticulatedBodyDesc> bodies, ArticulatedModel* out) {
  if (out == nullptr) return Status::Invalid("out", "is required");
  if (bodies.empty()) return Status::Invalid("bodies", "needs at least one body");
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i)
    if (Status s = CheckBody(bodies, i); !s) return s;

  ArticulatedModel model;
  const std::size_t n = bodies.size();
  model.bodies_.assign(bodies.begin(), bodies.end());
  model.dofs_.resize(n);
  model.roots_.resize(n);
  model.spatial_inertia_.resize(n);
  model.joint_axes_.resize(n);
  model.lower_limit_.resize(n);
  model.upper_limit_.resize(n);
  model.limited_.resize(n);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    ArticulatedBodyDesc& b = model.bodies_[i];
    b.joint_rotation.normalize();
    b.inertia = 0.5 * (b.inertia + b.inertia.transpose()).eval();
    model.dofs_[i] = DofsOf(b.joint);
    model.dof_count_ += model.dofs_[i];
    model.roots_[i] = b.parent < 0 ? static_cast<int>(i) : model.roots_[b.parent];
    model.total_mass_ += b.mass;
    model.joint_axes_[i] = b.joint_rotation.toRotationMatrix();

    const Mat3 cx = detail::Skew(b.center_of_mass);
    Mat6& s = model.spatial_inertia_[i];
    s.topLeftCorner<3, 3>() = b.inertia - b.mass * cx * cx;
    s.topRightCorner<3, 3>() = b.mass * cx;
    s.bottomLeftCorner<3, 3>() = -b.mass * cx;
    s.bottomRightCorner<3, 3>() = b.mass * Mat3::Identity();

    // Limits: hinge on X only; ball on all three; none for fixed and floating joints.
    const int axes = b.joint == ArticulatedJointType::kHinge  ? 1
                     : b.joint == ArticulatedJointType::kBall ? 3
                                                              : 0;
    Vec3 lower = Vec3::Constant(-kInf), upper = Vec3::Constant(kInf);
    bool limited = false;
    for (int k = 0; k < axes; ++k) {
      if (b.min_degrees[k] > -180.0) {
        lower[k] = b.min_degrees[k] * kDegrees;
        limited = true;
      }
      if (b.max_degrees[k] < 180.0) {
        upper[k] = b.max_degrees[k] * kDegrees;
        limited = true;
      }
    }
    model.lower_limit_[i] = lower;
    model.upper_limit_[i] = upper;
    model.limited_[i] = limited;
  }
  *out = std::move(model);
  return Status::Ok();
}

ArticulatedState MakeArticulatedState(const ArticulatedModel& model) {
  ArticulatedState state;
  state.joints.resize(model.body_count());
  state.bodies.resize(model.body_count());
  EvaluateArticulatedBodies(model, &state);
  return state;
}

ArticulatedWorkspace MakeArticulatedWorkspace(const ArticulatedModel& model) {
  const std::size_t n = model.body_count();
  ArticulatedWorkspace ws;
  ws.bodies.resize(n);
  ws.trees.resize(n);
  ws.q0.resize(n);
  ws.q.resize(n);
  ws.v0.assign(n, Vec6::Zero());
  ws.v.assign(n, Vec6::Zero());
  for (int k = 0; k < 4; ++k) {
    ws.dq[k].resize(n);
    ws.dv[k].assign(n, Vec6::Zero());
  }
  return ws;
}

namespace detail {

Status CheckArticulatedState(const ArticulatedModel& model, const ArticulatedState& state) {
  constexpr std::string_view kField = "state";
  const std::size_t n = model.body_count();
  if (state.joints.size() != n || state.bodies.size() != n)
    return Status::Invalid(kField, "must have one joint and one body per model body");
  if (!std::isfinite(state.time) || std::abs(state.time) > 1e150)
    return Status::InvalidElement(kField, -1, "time", "must be finite, within 1e150 (s)");
  const auto bounded = [](const Vec3& v) { return Finite(v) && v.cwiseAbs().maxCoeff() <= 1e150; };
  for (int i = 0; i < static_cast<int>(n); ++i) {
    const JointState& j = state.joints[i];
    const ArticulatedJointType type = model.body(i).joint;
    if (type == ArticulatedJointType::kFixed) continue;
    if ((type == ArticulatedJointType::kBall || type == ArticulatedJointType::kFloating) &&
        !UnitQuat(j.rotation))
      return Status::InvalidElement(kField, i, "rotation", "must be a unit quaternion");
    if (type == ArticulatedJointType::kHinge &&
        !(std::isfinite(j.angle) && std::abs(j.angle) <= 1e150))
      return Status::InvalidElement(kField, i, "angle", "must be finite, within 1e150 (rad)");
    if (!bounded(j.angular_velocity))
      return Status::InvalidElement(kField, i, "angular_velocity",
                                    "must be finite, within 1e150 (rad/s)");
    if (type == ArticulatedJointType::kFloating) {
      if (!bounded(j.translation))
        return Status::InvalidElement(kField, i, "translation", "must be finite, within 1e150 (m)");
      if (!bounded(j.linear_velocity))
        return Status::InvalidElement(kField, i, "linear_velocity",
                                      "must be finite, within 1e150 (m/s)");
    }
  }
  return Status::Ok();
}

}  // namespace detail

Status EvaluateArticulatedBodies(const ArticulatedModel& model, ArticulatedState* state) {
  if (state == nullptr) return Status::Invalid("state", "is required");
  if (Status s = detail::CheckArticulatedState(model, *state); !s) return s;
  for (int i = 0; i < model.body_count(); ++i) {
    detail::Coordinates c;
    Vec6 nu;
    detail::LoadJoint(model.body(i).joint, state->joints[i], &c, &nu);
    c.quaternion.normalize();
    detail::EvaluateBody(model, i, c, nu, state->bodies);
  }
  return Status::Ok();
}

Status MeasureArticulated(const ArticulatedModel& model, const ArticulatedState& state,
                          const Vec3& gravity, ArticulatedMeasures* out) {
  if (out == nullptr) return Status::Invalid("out", "is required");
  if (state.bodies.size() != static_cast<std::size_t>(model.body_count()))
    return Status::Invalid("state", "must have one body per model body");
  if (!Finite(gravity)) return Status::Invalid("gravity", "must be finite (m/s^2)");
  ArticulatedMeasures m;
  Vec3 first_moment = Vec3::Zero();
  for (int i = 0; i < model.body_count(); ++i) {
    const ArticulatedBodyDesc& b = model.body(i);
    const BodyMotion& motion = state.bodies[i];
    const Mat3 r = motion.rotation.toRotationMatrix();
    const Vec3 arm = r * b.center_of_mass;
    const Vec3 x = motion.translation + arm;
    const Vec3 v = motion.linear_velocity + motion.angular_velocity.cross(arm);
    const Vec3 spin = r * (b.inertia * (r.transpose() * motion.angular_velocity));
    m.mass += b.mass;
    first_moment += b.mass * x;
    m.linear_momentum += b.mass * v;
    m.angular_momentum += spin + x.cross(b.mass * v);
    m.kinetic_energy += 0.5 * (b.mass * v.squaredNorm() + motion.angular_velocity.dot(spin));
    m.potential_energy -= b.mass * gravity.dot(x);
  }
  m.center_of_mass = first_moment / m.mass;
  *out = m;
  return Status::Ok();
}

Vec3 JointAnglesDegrees(ArticulatedJointType type, const JointState& joint) {
  switch (type) {
    case ArticulatedJointType::kHinge:
      return Vec3(joint.angle / kDegrees, 0.0, 0.0);
    case ArticulatedJointType::kBall:
    case ArticulatedJointType::kFloating:
      return detail::EulerXyz(joint.rotation.normalized().toRotationMatrix()) / kDegrees;
    case ArticulatedJointType::kFixed:
    default:
      return Vec3::Zero();
  }
}

void SetJointAnglesDegrees(ArticulatedJointType type, const Vec3& degrees, JointState* joint) {
  const Vec3 a = degrees * kDegrees;
  switch (type) {
    case ArticulatedJointType::kHinge:
      joint->angle = a.x();
      joint->rotation = Quat(Eigen::AngleAxisd(a.x(), Vec3::UnitX()));
      break;
    case ArticulatedJointType::kBall:
    case ArticulatedJointType::kFloating:
      joint->rotation = (Quat(Eigen::AngleAxisd(a.x(), Vec3::UnitX())) *
                         Quat(Eigen::AngleAxisd(a.y(), Vec3::UnitY())) *
                         Quat(Eigen::AngleAxisd(a.z(), Vec3::UnitZ())))
                            .normalized();
      break;
    case ArticulatedJointType::kFixed:
    default:
      break;
  }
}

}  // namespace wirerig
