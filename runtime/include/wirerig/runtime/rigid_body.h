// Rigid spine wires (paper section 4.2, corrected in PHYSICS.md section 7): mass properties of
// the volume a part encloses, and Newton-Euler motion with the gyroscopic term, integrated
// with a fixed step by RK4 or the momentum form. Deterministic; no allocation.
#pragma once

#include <span>

#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

struct MassProperties {
  double volume = 0.0;                  // m^3 (solid) or shell volume area*h
  double mass = 0.0;                    // kg
  Vec3 center = Vec3::Zero();           // centre of mass, m
  Mat3 inertia = Mat3::Zero();          // about the centre, world axes at rest, kg m^2
  Mat3 principal_axes = Mat3::Identity();  // R0: columns are the principal axes (right-handed)
  Vec3 principal_moments = Vec3::Zero();   // I_b: inertia = R0 diag(I_b) R0^T
};

// Solid of uniform density enclosed by a closed, outward-facing surface (signed tetrahedra to
// the origin). Refuses: density not positive and finite, no triangles, an index out of range,
// non-finite positions, a non-positive enclosed volume (open or inward-facing surface).
Status ComputeSolidMassProperties(std::span<const Vec3> positions,
                                  std::span<const Triangle> triangles, double density,
                                  MassProperties* out);

// Thin shell of uniform density and thickness over the surface (need not be closed).
Status ComputeShellMassProperties(std::span<const Vec3> positions,
                                  std::span<const Triangle> triangles, double density,
                                  double thickness, MassProperties* out);

// A body's state. The body frame is the principal frame: world = position + orientation * body.
struct RigidBodyState {
  Vec3 position = Vec3::Zero();          // centre of mass x_c, m
  Vec3 velocity = Vec3::Zero();          // m/s
  Quat orientation = Quat::Identity();   // body (principal) frame -> world, unit
  Vec3 angular_velocity = Vec3::Zero();  // omega in BODY axes, rad/s
  double time = 0.0;                     // s
};

// External force (N, world) and torque about the centre of mass (N m, world).
struct Wrench {
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
};

// The torque about `center` of `force` applied at `point` (all world).
Vec3 TorqueAbout(const Vec3& center, const Vec3& point, const Vec3& force);

enum class RigidIntegrator : int { kRk4 = 0, kMomentum = 1 };

// One fixed step of length dt from state->time. The wrench is sampled by the caller at the
// start, middle and end of the step (keyframed forces: align steps with keys, PHYSICS.md 7).
struct RigidBodyStepJob {
  RigidIntegrator integrator = RigidIntegrator::kRk4;
  double mass = 0.0;                       // kg > 0
  Vec3 principal_moments = Vec3::Zero();   // I_b > 0 each, kg m^2
  double dt = 0.0;                         // s > 0
  Wrench at_start, at_middle, at_end;
  RigidBodyState* state = nullptr;         // in/out

  Status Validate() const;
  Status Run() const;  // validates; advances *state by dt; never allocates, never NaN
};

// Kinetic energy and world angular momentum, for checks and diagnostics.
double KineticEnergy(const RigidBodyState& state, double mass, const Vec3& principal_moments);
Vec3 AngularMomentumWorld(const RigidBodyState& state, const Vec3& principal_moments);

}  // namespace wirerig
