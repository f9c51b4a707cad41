// Profile wires with inertia: the skin's loops lag and overshoot when their part accelerates
// (flesh that jiggles: a mantle on a jet, an arm's flesh on a swing), each a modal wire
// (modal_wire.h) driven by the acceleration of the spine point it sits on.
//
// Each profile of a part with a mass is a ModalWireModel: the whole loop as a wire of its rest
// perimeter clamped at its first point (boundary family clamped over from = 0 to to = 1, as a
// ProfileLoads stretch), EI its own bending stiffness, mass per length the part's mass shared
// out over the total length of its profiles (the skin's wires carry the part's flesh). Its
// support acceleration is that of its origin (the spine point at its spine_v) as a point of the
// part's rigid placement, a = a_root + alpha x r + omega x (omega x r), in the profile's rest
// frame axes (normal, binormal, tangent), the three components each its own load: the uniform
// inertial load -rho A a over the loop. What the evaluation adds is a ProfileLoads entry per
// profile whose extra_displacement is the modal residual and the closed form of that load
// (ModalResidualJob).
//
// Limits: the part's rigid placement only (a deformable part's own bending motion, and its
// turning's ramp loads along the loop, are left out); the loop is a straight wire clamped at its
// first point for its modes, as the paper's profile stretches are.
#pragma once

#include <span>
#include <vector>

#include "wirerig/anim/wire_dynamics.h"
#include "wirerig/rig/result.h"
#include "wirerig/runtime/modal_wire.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {

// How a part's rigid placement moves at one time: the acceleration of its rest spine root
// point (m/s^2), angular velocity (rad/s) and angular acceleration (rad/s^2), world axes, and
// its rotation (rest world axes -> world).
struct RigidMotion {
  Vec3 acceleration = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
  Vec3 angular_acceleration = Vec3::Zero();
  Mat3 rotation = Mat3::Identity();
};

// The acceleration (world) of the point at world offset r from the part's root.
Vec3 PointAcceleration(const RigidMotion& motion, const Vec3& offset);

class ProfileDynamics {
 public:
  // One wire per profile of every part with a mass, advanced by steps of `step` s (options as
  // for the spines: modes 0 is off). Errors name the option or the part.
  static Result<ProfileDynamics> Make(const RigModel& model, const WireDynamicsOptions& options,
                                      double step);

  bool empty() const { return wires_.empty(); }
  std::size_t size() const { return wires_.size(); }

  // Every wire at rest.
  void Reset();
  // Advances every wire by dt with its part moving by motion[part] (one per part) at the
  // step's end. Never allocates.
  Status Step(std::span<const RigidMotion> motion, double dt);
  // Appends one ProfileLoads per wire (the whole profile, clamped, its extra_displacement the
  // wire's motion beyond rest) to `out`, whose capacity must hold them. Never allocates.
  Status Apply(std::vector<ProfileLoads>* out);

  // The modal states, one per wire (for checkpoints: copy out, copy back in).
  std::span<const ModalWireState> states() const { return states_; }
  void Restore(std::span<const ModalWireState> states);

 private:
  struct Wire {
    std::size_t part = 0, profile = 0;
    ModalWireModel model;
    ModalStepTable table;
    Vec3 origin = Vec3::Zero();                // rest world point of the profile's origin
    Mat3 axes = Mat3::Identity();              // its rest frame: columns normal, binormal, tangent
    Vec3 support_acceleration = Vec3::Zero();  // frame axes, of the last step
    std::vector<double> samples, mode_values, mode_slopes;
    std::vector<Vec3> displacement;
  };

  const RigModel* model_ = nullptr;
  std::vector<Wire> wires_;
  std::vector<ModalWireState> states_;
};

}  // namespace wirerig
