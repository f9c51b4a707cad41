// Playback: a clip driving a rig over time. Closed-form wires are evaluated directly at any
// time (random access); rigid-body dynamics is integrated with a fixed step from the clip's
// start, and the states at every `checkpoint_interval` steps are cached, so scrubbing back
// costs at most that many steps. Evaluate never allocates once the playback is made (the
// cache is sized for the whole clip up front).
//
// Rigid parts driven by forces (rigid_part.h): a root part is a free body, a child part turns
// about its joint; each starts at rest in its modelled pose at clip time 0 and its pose is its
// motion from rest. A child's motion is relative to its parent's frame (the evaluation's
// hierarchy rule): its joint rides on the parent, and its dynamics is integrated as if the
// parent's frame were still (the parent's acceleration is not fed back).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "wirerig/anim/articulated_tracking.h"
#include "wirerig/anim/clip.h"
#include "wirerig/anim/clip_reach.h"
#include "wirerig/anim/clip_sampling.h"
#include "wirerig/anim/profile_dynamics.h"
#include "wirerig/anim/rigid_part.h"
#include "wirerig/anim/wire_dynamics.h"
#include "wirerig/io/result.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {

// A force applied live on top of the clip (the viewer's drag): at wire parameter `at` of a
// part's spine, or of one of its profile wires (the whole loop held clamped at its ends), in
// world axes; it is turned into the wire's local axes by the frames of the last evaluation.
struct InteractiveLoad {
  std::uint32_t part = 0;
  int profile = -1;           // -1: the spine; else the profile wire's index
  double at = 1.0;            // v in [0, 1]
  Vec3 force = Vec3::Zero();  // N, world axes
};

struct PlaybackOptions {
  double rigid_step = 1.0 / 240.0;  // s, fixed step of the rigid-body integration
  RigidIntegrator integrator = RigidIntegrator::kRk4;
  // Steps between cached states; widened for a long clip so the cache holds at most
  // kMaxCheckpointBytes.
  std::size_t checkpoint_interval = 24;
  Vec3 gravity = Vec3::Zero();   // m/s^2, on rigid bodies driven by the clip
  bool preserve_volume = false;  // see EvaluateRigJob
  // Keyed poses played through the chain's articulated dynamics (articulated_tracking.h) when
  // tracking.frequency > 0.
  TrackingOptions tracking;
  // Inertia for the deformable spines (wire_dynamics.h) when wires.modes > 0, integrated with
  // the rigid bodies at rigid_step.
  WireDynamicsOptions wires;
  // Inertia for the profile wires (profile_dynamics.h: the skin jiggles) when
  // profile_wires.modes > 0.
  ProfileWireOptions profile_wires;
};

// The most memory the checkpoint cache of one playback takes, bytes.
inline constexpr double kMaxCheckpointBytes = 64.0 * 1024 * 1024;

class Playback {
 public:
  // The model and clip must outlive the playback. Errors name the option at fault.
  static Result<Playback> Make(const RigModel& model, const Clip& clip,
                               const PlaybackOptions& options = {});

  // Positions (and normals, if not empty) of the welded vertices at playback time t (s); the
  // clip's loop mode maps t to clip time. `warnings`, if not empty, gets one entry per part.
  // Every consumer draws or exports floats: an output that is not finite or lies beyond 1e7 m
  // from the origin (a deformation that overflowed; beyond it float normals can overflow) fails
  // alike in both evaluations, naming it ("positions[12]: not finite, or beyond 1e7 m ...").
  Status Evaluate(double t, std::span<Vec3> positions, std::span<Vec3> normals,
                  std::span<PartWarnings> warnings = {});
  // The same into float buffers (EvaluateRigJob's float outputs): vertex i's position at
  // positions[i * position_stride .. + 3), its normal likewise (normals may be empty); output
  // vertex i is welded vertex vertex_order[i] (e.g. the mesh's weld map: the source asset's
  // vertices), or welded vertex i when vertex_order is empty. Non-finite outputs fail likewise.
  struct FloatOutput {
    std::span<float> positions;
    std::size_t position_stride = 3;
    std::span<float> normals;
    std::size_t normal_stride = 3;
    std::span<const std::uint32_t> vertex_order;
  };
  Status Evaluate(double t, const FloatOutput& output, std::span<PartWarnings> warnings = {});

  // Adds `load` to every following Evaluate until cleared with nullopt. Errors name the field
  // (part or profile out of range, `at` outside [0, 1], a force that is not finite).
  Status SetInteractiveLoad(const std::optional<InteractiveLoad>& load);
  // Turns a part's joint by these angles (degrees about its joint axes, clamped to the joint's
  // type and limits) on top of the clip in every following Evaluate; zero angles clear it.
  // Errors name the field (part out of range or the root, angles not finite).
  Status SetInteractiveJointAngles(std::uint32_t part, const Vec3& degrees);
  // The angles set for a part (zero when none).
  Vec3 InteractiveJointAngles(std::uint32_t part) const;

  // After Evaluate: the deformed spines and profiles, and the inputs sampled at that time.
  const RigWorkspace& workspace() const { return workspace_; }
  const ClipSample& sample() const { return sample_; }
  // The articulated dynamics tracking the keyed poses, if the options turned it on.
  const ArticulatedTracking* tracking() const { return tracking_ ? &*tracking_ : nullptr; }
  // After Evaluate: the rigid body of every part at that time (rest state for parts without
  // dynamics). Pinned bodies (child parts) keep their joint as position.
  std::span<const RigidBodyState> bodies() const { return bodies_; }
  // After Evaluate: what each reach target of the clip found (clip_reach.h).
  const ClipReach& reach() const { return reach_; }
  // The wires with inertia (empty when options.wires.modes is 0); after Evaluate, their
  // residuals are those of that time.
  const WireDynamics& wires() const { return wires_; }
  const ProfileDynamics& profile_wires() const { return profiles_; }
  const Clip& clip() const { return *clip_; }
  const RigModel& model() const { return *model_; }

 private:
  Playback() = default;
  // Poses the clip at playback time t and runs `job` (its outputs set by the caller).
  Status Run(double t, EvaluateRigJob& job);
  Status AdvanceBodies(double local_time);
  Status StepBodies(double dt);
  bool HasDynamics() const {
    return !dynamic_parts_.empty() || !wires_.empty() || !profiles_.empty();
  }
  // The offset (world) of the rest point `rest` of dynamic part d's body from the body's
  // reference point (its state's position), now.
  Vec3 BodyPointOffset(std::size_t d, const Vec3& rest) const;
  // The angular velocity (world) of dynamic part d's body, now.
  Vec3 BodyAngularVelocity(std::size_t d) const;
  void ApplyInteractiveLoad();
  // Poses the dynamic rigid parts of `sample` from their bodies (keeping the sampled loads).
  void PoseDynamicParts(ClipSample* sample) const;
  // part_motion_ at the step's end (clock_; step_sample_ holds the clip there) for the bodies
  // moved by forces (their velocities' change over the step dt) and the parts moved by keys
  // (central differences of their placements over one rigid step).
  void PartMotions(double dt);
  void KeyedPartMotions();

  const RigModel* model_ = nullptr;
  const Clip* clip_ = nullptr;
  PlaybackOptions options_;
  RigWorkspace workspace_;
  ClipSample sample_;
  std::vector<std::size_t> dynamic_parts_;           // rigid parts the clip drives by forces
  std::vector<RigidPartBody> dynamic_bodies_;        // their bodies, same order
  std::vector<RigidBodyState> bodies_;               // per part, at the current time
  std::vector<RigidBodyState> checkpoints_;          // #checkpoints x #dynamic parts
  WireDynamics wires_;                               // the deformable spines with inertia
  std::vector<ModalWireState> wire_checkpoints_;     // #checkpoints x #wires
  ClipReach reach_;                                  // the clip's reach targets (wire IK)
  std::vector<double> wire_scale_;                   // per part: its wire's residual's scale
  ProfileDynamics profiles_;                         // the profile wires with inertia
  std::vector<ModalWireState> profile_checkpoints_;  // #checkpoints x #profile wires
  std::vector<ProfileLoads> combined_profiles_;      // the clip's and the profile wires'
  std::vector<RigidMotion> part_motion_;             // per part, at the last step's end
  std::vector<Vec3> velocity_before_;                // per dynamic part, before the step
  std::vector<Vec3> angular_velocity_before_;
  std::vector<std::size_t> keyed_parts_;     // parts whose motion is wanted, moved by keys alone
  std::vector<bool> own_motion_;             // per part: dynamic or keyed (else its parent's)
  ClipSample support_sample_;                // the clip one step before and after
  std::vector<Mat3> placement_rotation_[3];  // per part, at t - h, t, t + h
  std::vector<Vec3> placement_translation_[3];
  std::vector<ClipReach::Kept> reach_checkpoints_;  // #checkpoints x #reaches
  std::size_t checkpoint_count_ = 0;
  std::size_t checkpoints_done_ = 0;
  double clock_ = 0.0;                              // clip time of the dynamic state, s
  ClipSample step_sample_;                          // the clip at a step's end (wires' loads)
  std::vector<int> dynamic_index_;                  // per part: its index in dynamic_parts_, or -1
  std::vector<Vec3> support_acceleration_;          // per part, world axes, of the last step
  std::vector<Vec3> support_angular_velocity_;      // per part, world axes, at the step's end
  std::vector<Vec3> support_angular_acceleration_;  // per part, world axes, of the last step
  std::vector<Mat3> support_rotation_;              // per part: its parent's rotation
  std::optional<ArticulatedTracking> tracking_;
  std::optional<InteractiveLoad> interactive_;
  std::vector<Vec3> interactive_joints_;            // per part, degrees
  std::vector<PointLoad> interactive_points_;       // clip's loads of a part, plus one
  std::vector<ProfileLoads> interactive_profiles_;  // clip's profile loads, plus one
  PointLoad interactive_profile_point_;
  bool evaluated_ =
      false;  // the workspace holds a deformed frame           // how many checkpoints are valid
};

}  // namespace wirerig
