// Wire dynamics in playback: the deformable spines of a rig given inertia (modal_wire.h), so
// they lag, swing and settle instead of snapping to the static shape of their loads.
//
// Each deformable part's spine is a ModalWireModel: its length and EI, mass per length = the
// part's mass (its enclosed volume times its material's density) over its spine length, the
// options' damping ratio and mode count, and the boundary family its clip starts with. Each
// fixed step takes the clip's loads at the step's end and the motion of the part's support
// (its parent, a rigid body moved by dynamics or a part moved by keys): the acceleration a of the
// attachment point, and the parent's angular velocity omega and angular acceleration alpha,
// and advances every mode exactly. What the evaluation adds to the static closed form is the
// modal residual sum (q_n - q_n_static) phi_n and the static shape of the support's inertial
// loads (SpineLoads::extra_displacement / extra_slope): the uniform -rho A a plus the linear
// -rho A s [alpha x t + (omega . t) omega] (lateral parts, s from the attachment; modal_wire.h
// "Turning supports").
//
// A parent moved by keys (no ancestor of it a body moved by forces) gives its support motion by
// central differences of its placement over one rigid step (Playback::KeyedSupportMotion; with
// articulated tracking, the keyed targets' motion, not the tracked bodies').
//
// Limits: a family change during the clip keeps the first family's modes (the static part
// follows the clip exactly; the residual is projected on the old modes); a keyed part below a
// body moved by forces gives no support motion; the support's motion is taken in the local
// axes of the spine's middle frame and the spine as straight along that frame's tangent (a
// curved spine's lever arms are its chord's); the child's own joint rotation relative to its
// parent adds no inertial load; the turning support's axial (centrifugal) load and the Coriolis
// load of the wire's own motion are left out (modal_wire.h).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "wirerig/anim/clip_sampling.h"
#include "wirerig/io/result.h"
#include "wirerig/runtime/modal_wire.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {

struct WireDynamicsOptions {
  int modes = 0;               // bending modes per spine, 0 (off: static wires) to 32
  double damping_ratio = 0.1;  // of every mode, in [0, 100]
};

// What is wrong with a mode count and damping ratio ("modes: ..." or "damping_ratio: ..."), or
// empty when both are valid (for the spines' and the profile wires' options alike).
std::string ModalOptionsError(int modes, double damping_ratio);

class WireDynamics {
 public:
  // One wire per deformable part whose spine has a mass, for `clip` on `model` (both outlive
  // it), advanced by steps of `step` s. Errors name the option or the part.
  static Result<WireDynamics> Make(const RigModel& model, const Clip& clip,
                                   const WireDynamicsOptions& options, double step);

  bool empty() const { return wires_.empty(); }
  std::size_t size() const { return wires_.size(); }

  // Every wire resting at the static shape of its loads in `sample` (clip time 0).
  Status Reset(const ClipSample& sample);
  // Advances every wire by dt to the loads of `sample` (taken at the step's end), its support
  // accelerating by support_acceleration[part] (m/s^2, world axes, one per part) and turning
  // with support_angular_velocity[part] (rad/s, world axes, at the step's end) and
  // support_angular_acceleration[part] (rad/s^2, world axes) in the rotation
  // `support_rotation[part]` (rest world axes -> world) of its parent. Never allocates.
  Status Step(const ClipSample& sample, std::span<const Vec3> support_acceleration,
              std::span<const Vec3> support_angular_velocity,
              std::span<const Vec3> support_angular_acceleration,
              std::span<const Mat3> support_rotation, double dt);
  // Points each wire part's SpineLoads::extra_displacement / extra_slope at its residual for
  // the loads in `poses` (the same loads the wires were last stepped to), times
  // residual_scale[part] if given (one per part; e.g. a reaching arm held by its muscles).
  // Never allocates.
  Status Apply(std::span<PartPose> poses, std::span<const double> residual_scale = {});

  // Wire w's part and model (w < size()).
  std::size_t part(std::size_t w) const { return wires_[w].part; }
  const ModalWireModel& model(std::size_t w) const { return wires_[w].model; }
  // What the last Apply added to each wire's static shape, one per wire (scaled): the numbers
  // a runtime clip records (runtime/clip_asset.h).
  std::span<const ModalResidual> residuals() const { return residuals_; }

  // The modal states, one per wire (for checkpoints: copy out, copy back in).
  std::span<const ModalWireState> states() const { return states_; }
  void Restore(std::span<const ModalWireState> states);

 private:
  struct Wire {
    std::size_t part = 0;
    ModalWireModel model;
    ModalStepTable table;
    Vec3 support_acceleration = Vec3::Zero();          // local axes, of the last step
    Vec3 support_angular_velocity = Vec3::Zero();      // local axes, of the last step
    Vec3 support_angular_acceleration = Vec3::Zero();  // local axes, of the last step
    std::vector<double> samples, mode_values, mode_slopes;
    std::vector<Vec3> extra_displacement, extra_slope;
  };
  ModalWireLoads LoadsOf(const Wire& wire, const SpineLoads& loads) const;

  const RigModel* model_ = nullptr;
  std::vector<Wire> wires_;
  std::vector<ModalWireState> states_;
  std::vector<ModalResidual> residuals_;
  std::vector<Vec3> scratch_;  // q - q_static per mode
};

}  // namespace wirerig
