// How a rigid part moves under the clip's forces (PHYSICS.md section 7). A root part is a free
// body: Newton-Euler about its centre of mass. A child part is pinned at its joint, the root of
// its spine: it only turns about that point, with the inertia about the joint (parallel-axis
// theorem, I_j = I_c + m (|d|^2 1 - d d^T), d from the joint to the centre), so an arm driven
// by torques swings from its shoulder instead of drifting away from it.
//
// Either way the body is integrated by RigidBodyStepJob in its principal frame (about the
// centre, or about the joint); its pose for the evaluation is the motion from rest.
#pragma once

#include <cstddef>

#include "wirerig/anim/clip.h"
#include "wirerig/runtime/rig_evaluation.h"
#include "wirerig/runtime/rigid_body.h"

namespace wirerig {

struct RigidPartBody {
  bool pinned = false;
  Vec3 reference = Vec3::Zero();          // rest centre (free) or joint (pinned), world, m
  Vec3 center = Vec3::Zero();             // rest centre of mass, world, m
  Mat3 axes = Mat3::Identity();           // R0: principal axes about the reference, at rest
  Vec3 principal_moments = Vec3::Zero();  // about the reference, kg m^2
  double mass = 0.0;                      // kg
};

// Free when `pinned` is false; pinned at the spine's first point otherwise.
RigidPartBody MakeRigidPartBody(const PartModel& part, bool pinned);

// At rest in the modelled pose: position = reference, orientation = Quat(axes), still.
RigidBodyState RestState(const RigidPartBody& body);

// The wrench at clip time t on `body` (part `part` of the clip) in `state`: forces at body
// points (given at rest, carried by the motion), the torque track and gravity at the centre.
// Free bodies get the force and the torque about the centre; pinned bodies no force (the joint
// takes it) and the torque about the joint.
Wrench SampleRigidWrench(const Clip& clip, std::size_t part, const RigidPartBody& body, double t,
                         const RigidBodyState& state, const Vec3& gravity);

// The part's pose for EvaluateRigJob: rotation q R0^-1 about the spine's root, and for a free
// body the translation that carries the centre to its place.
PartPose PoseOfRigidPart(const RigidPartBody& body, const PartModel& part,
                         const RigidBodyState& state);

}  // namespace wirerig
