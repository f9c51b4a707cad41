#include "wirerig/anim/rigid_part.h"

#include <Eigen/Eigenvalues>

namespace wirerig {
namespace {

// The point of the body that was at `rest` in the modelled pose, now.
Vec3 BodyPoint(const RigidPartBody& body, const RigidBodyState& state, const Vec3& rest) {
  return state.position + state.orientation * (body.axes.transpose() * (rest - body.reference));
}

}  // namespace

RigidPartBody MakeRigidPartBody(const PartModel& part, bool pinned) {
  RigidPartBody body;
  body.pinned = pinned;
  body.mass = part.mass.mass;
  body.center = part.mass.center;
  if (!pinned) {
    body.reference = part.mass.center;
    body.axes = part.mass.principal_axes;
    body.principal_moments = part.mass.principal_moments;
    return body;
  }
  body.reference = part.spine_points.front();
  const Vec3 d = part.mass.center - body.reference;
  const Mat3 inertia =
      part.mass.inertia + part.mass.mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(inertia);
  body.principal_moments = solver.eigenvalues();  // ascending
  body.axes = solver.eigenvectors();
  if (body.axes.determinant() < 0.0) body.axes.col(2) = -body.axes.col(2);
  return body;
}

RigidBodyState RestState(const RigidPartBody& body) {
  RigidBodyState state;
  state.position = body.reference;
  state.orientation = Quat(body.axes).normalized();
  return state;
}

Wrench SampleRigidWrench(const Clip& clip, std::size_t part, const RigidPartBody& body, double t,
                         const RigidBodyState& state, const Vec3& gravity) {
  const PartChannels<Track>& c = clip.parts[part];
  const Vec3 center = BodyPoint(body, state, body.center);
  Vec3 force = body.mass * gravity;
  Vec3 torque = c.rigid_torque.Sample(t);
  for (const RigidForceChannels<Track>& f : c.rigid_forces) {
    const Vec3 applied = f.force.Sample(t);
    force += applied;
    torque += TorqueAbout(state.position, BodyPoint(body, state, f.at), applied);
  }
  // Drag: the centre's velocity (a pinned body's turns about the joint) and the spin.
  const RigidDrag& drag = c.rigid_drag;
  if (!drag.IsZero()) {
    const Vec3 omega = state.orientation * state.angular_velocity;  // world
    const Vec3 v = state.velocity + omega.cross(center - state.position);
    const Vec3 drag_force = -(drag.linear + drag.quadratic * v.norm()) * v;
    force += drag_force;
    torque += TorqueAbout(state.position, center, drag_force) - drag.angular * omega;
  }
  if (body.pinned) {
    // About the joint: gravity's moment too; the joint's reaction takes the force.
    torque += TorqueAbout(state.position, center, body.mass * gravity);
    return {Vec3::Zero(), torque};
  }
  return {force, torque};
}

PartPose PoseOfRigidPart(const RigidPartBody& body, const PartModel& part,
                         const RigidBodyState& state) {
  PartPose pose;
  pose.rotation = (state.orientation * Quat(body.axes).conjugate()).normalized();
  // x_ref = root + R (ref0 - root) + t  =>  t = x_ref - root - R (ref0 - root); zero when pinned
  // at the root.
  const Vec3 root = part.spine_points.front();
  pose.translation = state.position - root - pose.rotation * (body.reference - root);
  return pose;
}

}  // namespace wirerig
