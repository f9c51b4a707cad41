// Rigid spine wires (paper section 4.2, corrected in PHYSICS.md section 7): mass properties of
// the volume a part encloses, and Newton-Euler motion with the gyroscopic term, integrated
// with a fixed step by RK4 or the momentum form. Deterministic; no allocation.
#pragma once

#include <span>

#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

struct MassProperties {
  double volume = 0.0;                     // m^3 (solid) or shell volume area*h
  double mass = 0.0;                       // kg
  Vec3 center = Vec3::Zero();              // centre of mass, m
  Mat3 inertia = Mat3::Zero();             // about the centre, world axes at rest, kg m^2
  Mat3 principal_axes = Mat3::Identity();  // R0: columns are the principal axes (right-handed)
  Vec3 principal_moments = Vec3::Zero();   // I_b: inertia = R0 diag(I_b) R0^T
};
// The principal moments are in ascending order; R0 has det +1, its first two columns have
// their largest component positive. A body at rest in its modelled pose has orientation
// Quat(R0) and position `center` (see RigidBodyState).

// Solid of uniform density enclosed by a closed, outward-facing surface (signed tetrahedra to
// the centre of the bounding box, for precision far from the origin). Vertices may be
// duplicated (glTF seams): closure is checked geometrically. Refuses, naming the field:
//   "out"        null;
//   "density"    not positive and finite, or so large (small) that the inertia overflows
//                (the mass underflows);
//   "triangles"  none, or an index out of range (index = the triangle);
//   "positions"  not finite, or beyond 1e50 m (index = the vertex);
//   "volume"     the surface is open (its vector area exceeds 1e-6 of its area), faces inward,
//                or encloses no volume.
// Writes *out only on success.
Status ComputeSolidMassProperties(std::span<const Vec3> positions,
                                  std::span<const Triangle> triangles, double density,
                                  MassProperties* out);

// Thin shell of uniform density and thickness over the surface (need not be closed, either
// orientation); volume = area * thickness. Refuses as above, plus "thickness" not positive
// and finite, and "triangles" of zero total area.
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
//   kRk4       classic RK4 on (x, v, q, omega_b), wrench at the stage times; q normalised after
//              the step. Most accurate; exact translation for a force quadratic in t.
//   kMomentum  v += dt F_mid/m, x += dt (v_old + v_new)/2, L += dt tau_mid, q turned by the
//              exp map of the midpoint angular velocity (3 fixed-point iterations). L is
//              conserved up to round-off when tau = 0; energy drifts at second order.
// Validate() refuses, naming the field: "integrator" unknown; "mass", "principal_moments"
// (index = axis), "dt" not positive and finite; "at_start"/"at_middle"/"at_end" with member
// "force" or "torque" not finite; "state" null, or member "position", "velocity",
// "angular_velocity", "time" not finite or beyond 1e150, "orientation" not finite or |q|^2
// not within 1e-6 of 1; "dt" again when an a-priori bound on the step (positions, velocities,
// momenta, energies, and for RK4 its stages) exceeds 1e150: a step far too long for the
// motion (for RK4, dt |omega| I_max/I_min far beyond 1) is refused rather than overflow.
struct RigidBodyStepJob {
  RigidIntegrator integrator = RigidIntegrator::kRk4;
  double mass = 0.0;                      // kg > 0
  Vec3 principal_moments = Vec3::Zero();  // I_b > 0 each, kg m^2
  double dt = 0.0;                        // s > 0
  Wrench at_start, at_middle, at_end;
  RigidBodyState* state = nullptr;  // in/out

  Status Validate() const;
  Status Run() const;  // validates; advances *state by dt; never allocates, never NaN;
                       // leaves *state untouched when refused
};

// Kinetic energy (translational + rotational) and the world angular momentum about the centre
// of mass, R I_b omega_b (R of the orientation scaled to unit), for checks and diagnostics.
// Neither guards against overflow of absurd inputs.
double KineticEnergy(const RigidBodyState& state, double mass, const Vec3& principal_moments);
Vec3 AngularMomentumWorld(const RigidBodyState& state, const Vec3& principal_moments);

}  // namespace wirerig
