// Keyed poses played through the articulated rigid-body dynamics of the whole bone chain
// (runtime/articulated_body.h): every joint is driven by PD tracking of its keyed rotation, so
// an animator keys poses and the physics adds the lag, overshoot and follow-through of real
// limbs under gravity and the body's own accelerations.
//
// The clip's keyed rigid forces (at a body point) and torques act on the parts' bodies.
// The root part follows its keyed motion exactly; the chain's dynamics is solved in the root's
// frame, where gravity and the root's keyed acceleration (finite differences of its translation
// track) act as one effective gravity, R_root^T (g - a_root) (the root's own turning adds no
// fictitious force: a documented simplification). Each part is a rigid body with its profile
// solid's mass properties; joints keep their type, axes and limits (JointModel). Gains scale
// with the inertia a joint drives, I (its subtree's inertia about the joint: about the hinge
// axis, or the largest principal moment for a ball), so every joint tracks with the same
// natural frequency f and damping ratio zeta: kp = (2 pi f)^2 I, kd = 2 zeta (2 pi f) I.
// Fixed steps from the clip's start with the semi-implicit integrator, states cached every
// `checkpoint_interval` steps (scrubbing back costs at most that many steps); allocation-free
// once made; deterministic.
#pragma once

#include <vector>

#include "wirerig/anim/clip.h"
#include "wirerig/anim/clip_sampling.h"
#include "wirerig/io/result.h"
#include "wirerig/runtime/articulated_body.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {

struct TrackingOptions {
  double frequency = 0.0;                // Hz, > 0 turns tracking on; 0: keyed poses as they are
  double damping_ratio = 1.0;            // >= 0; below 1 the limbs overshoot their keys
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);  // m/s^2, world
  double step = 1.0 / 240.0;             // s
  std::size_t checkpoint_interval = 48;  // steps between cached states
};

class ArticulatedTracking {
 public:
  // The model and clip must outlive the tracking. Errors name the option or part at fault
  // ("frequency: ...", "part \"hand_l\": has no mass (its profiles are open)").
  static Result<ArticulatedTracking> Make(const RigModel& model, const Clip& clip,
                                          const TrackingOptions& options);

  // Advances the dynamics to clip-local time t (from the nearest cached state at or before it)
  // and replaces every child part's rotation in `poses` (its turn about its joint, as
  // EvaluateRigJob reads it) by the simulated one. Other pose fields stay as keyed.
  Status Apply(double t, std::span<PartPose> poses);

  // After Apply: each part's joint angles in degrees (JointModel's X-Y-Z convention), and the
  // state of the chain (bodies in the root's frame).
  Vec3 JointAngles(std::size_t part) const;
  const ArticulatedState& state() const { return state_; }
  const ArticulatedModel& model() const { return articulated_; }

 private:
  ArticulatedTracking() = default;
  Status Step();
  void SetTargets(double t);

  const RigModel* model_ = nullptr;
  const Clip* clip_ = nullptr;
  TrackingOptions options_;
  ArticulatedModel articulated_;
  ArticulatedWorkspace workspace_;
  ArticulatedState state_;
  std::vector<Mat3> axes_;       // per part: its joint's rest axes (identity for the root)
  std::vector<double> inertia_;  // per part: the inertia its joint drives, kg m^2
  std::vector<JointTarget> targets_;
  std::vector<ExternalWrench> wrenches_;  // the clip's keyed forces and torques, this step
  ClipSample keyed_;                      // scratch: the clip sampled at a step's time
  std::vector<ArticulatedState> checkpoints_;
  std::size_t checkpoints_done_ = 0;  // valid cached states
  std::size_t steps_ = 0;             // steps taken to reach state_
  Vec3 effective_gravity_ = Vec3::Zero();
};

}  // namespace wirerig
