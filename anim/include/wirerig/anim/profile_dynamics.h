// Profile wires with inertia: the skin's loops lag and overshoot when their part accelerates
// (flesh that jiggles: a mantle on a jet, an arm's flesh on a swing), each a modal wire
// (modal_wire.h) driven by the acceleration of the spine point it sits on.
//
// Each profile of a part with a mass is a ModalWireModel: the whole loop as a wire of its rest
// perimeter L clamped at its first point (boundary family clamped over from = 0 to to = 1, as a
// ProfileLoads stretch), mass per length rho A the part's mass shared out over the total length
// of its profiles (the skin's wires carry the part's flesh), and the bending stiffness that
// gives its first mode the flesh's frequency at its size: f_L = f (1 m / L), as an elastic
// solid's frequencies scale inversely with its size, so EI = rho A L^4 (2 pi f_L)^2 / beta_1^4
// (beta_1 = 4.730 for the clamped family). A loop then deflects by about 1.3 a / (2 pi f_L)^2
// under an acceleration a: in proportion to L^2, so a belly swings and a finger barely does.
// The skin strip's own EI (its material and thickness) cannot carry that flesh: on the octopus
// and the human it would sag by metres under 1 g (measured), so the flesh's stiffness is the
// frequency f of a loop of 1 m perimeter, tuned as a jiggle bone's is. Its support
// acceleration is that of its origin (the spine point at its spine_v) as a point of the part's
// rigid placement, a = a_root + alpha x r + omega x (omega x r), in the profile's rest frame
// axes (normal, binormal, tangent), the three components each its own load: the uniform
// inertial load -rho A a over the loop. What the evaluation adds is a ProfileLoads entry per
// profile whose extra_displacement is the modal residual and the closed form of that load
// (ModalResidualJob).
//
// Bounded. A loop never leaves its rest shape by more than `limit` times its mean radius: each
// point's motion d is eased into that bound, d limit_r tanh(|d| / limit_r) / |d| (exact to
// first order for small motion, so the tests' closed forms hold), since flesh cannot slide
// off its bone however jerky a clip's keys are (the keyed walk's knees reach 16 g between keys
// and unbounded loops there would fold the skin).
//
// Held at the joints. Where a part meets another part (or a cap) the flesh moves otherwise, so
// each loop point's motion is weighted: by where its loop sits along the part's loops, u in
// [0, 1] from the first to the last, smoothstep(u / 0.25) smoothstep((1 - u) / 0.25) (full
// over the middle half, nothing at the ends), times smoothstep(d / r) of its rest distance d to
// the nearest loop point of any other part, r its loop's mean radius (a tentacle's root on a
// mantle's side, an arm by a chest). The skin stays whole where parts meet, as flesh is held
// by tendons at a joint.
//
// Limits: the part's rigid placement only (a deformable part's own bending motion, and its
// turning's ramp loads along the loop, are left out); the loop is a straight wire clamped at its
// first point for its modes, as the paper's profile stretches are.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "wirerig/anim/wire_dynamics.h"
#include "wirerig/io/result.h"
#include "wirerig/runtime/clip_asset.h"
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

// The flesh's response: modes per loop (0: off), their damping ratio, and the first mode's
// frequency.
struct ProfileWireOptions {
  int modes = 0;               // 0 (off: static skin) to 32
  double damping_ratio = 0.3;  // in [0, 100]
  double frequency = 3.0;      // Hz, of a loop of 1 m perimeter, in (0, 1000]
  double limit = 0.25;         // of a loop's mean radius, the most its points move; in (0, 1]
  // The parts whose flesh moves (a belly, thighs, a mantle); empty: every part with a mass.
  // Parts whose loops wrap thin features (a hand's fingers) are better left out.
  std::vector<std::string> parts;
};

class ProfileDynamics {
 public:
  // One wire per profile of every part with a mass, advanced by steps of `step` s. Errors name
  // the option or the part.
  static Result<ProfileDynamics> Make(const RigModel& model, const ProfileWireOptions& options,
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

  // What a .wclip records of wire w (clip_asset.h), and its residual as of the last Apply.
  ClipProfileWire Recorded(std::size_t w) const;
  std::span<const ModalResidual> residuals() const { return residuals_; }

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
    double reach = 0.0;           // m, the most a point moves (limit times the mean radius)
    std::vector<double> weights;  // of each point's motion: held at joints (see above)
    std::vector<double> samples, mode_values, mode_slopes;
    std::vector<Vec3> displacement;
  };

  const RigModel* model_ = nullptr;
  std::vector<Wire> wires_;
  std::vector<ModalWireState> states_;
  std::vector<ModalResidual> residuals_;
};

}  // namespace wirerig
