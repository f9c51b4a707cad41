#include "wirerig/anim/playback.h"

#include <algorithm>
#include <cmath>

#include "float_finite.h"

namespace wirerig {

Result<Playback> Playback::Make(const RigModel& model, const Clip& clip,
                                const PlaybackOptions& options) {
  if (!(std::isfinite(options.rigid_step) && options.rigid_step > 0.0))
    return Error{"rigid_step: must be finite and positive (s)"};
  if (options.checkpoint_interval == 0) return Error{"checkpoint_interval: must be at least 1"};
  if (!(std::isfinite(options.gravity.x()) && std::isfinite(options.gravity.y()) &&
        std::isfinite(options.gravity.z())))
    return Error{"gravity: must be finite"};
  if (clip.parts.size() != model.parts.size())
    return Error{"clip: was built for another rig (part counts differ)"};
  const double steps = std::ceil(clip.duration / options.rigid_step);
  if (steps > 1e8) return Error{"rigid_step: too small for the clip's duration (over 1e8 steps)"};
  Playback playback;
  playback.model_ = &model;
  playback.clip_ = &clip;
  playback.options_ = options;
  playback.workspace_ = MakeRigWorkspace(model);
  playback.sample_ = MakeClipSample(clip, model);
  playback.bodies_.resize(model.parts.size());
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const PartModel& part = model.parts[p];
    const RigidPartBody body = MakeRigidPartBody(part, part.parent >= 0);
    playback.bodies_[p] = RestState(body);
    const PartChannels<Track>& c = clip.parts[p];
    // With tracking, the chain's articulated dynamics takes the keyed forces instead.
    if (part.kind == SpineKind::kRigid && options.tracking.frequency <= 0.0 &&
        (!c.rigid_forces.empty() || !c.rigid_torque.IsEmpty() || !c.rigid_drag.IsZero() ||
         options.gravity != Vec3::Zero())) {
      if (!(part.mass.mass > 0.0))
        return Error{"part \"" + part.name + "\": a rigid part driven by forces needs a mass"};
      playback.dynamic_parts_.push_back(p);
      playback.dynamic_bodies_.push_back(body);
    }
  }
  playback.dynamic_index_.assign(model.parts.size(), -1);
  for (std::size_t d = 0; d < playback.dynamic_parts_.size(); ++d)
    playback.dynamic_index_[playback.dynamic_parts_[d]] = int(d);
  Result<WireDynamics> wires = WireDynamics::Make(model, clip, options.wires, options.rigid_step);
  if (!wires) return Error{"wires: " + wires.error()};
  playback.wires_ = std::move(wires).value();
  playback.reach_ = ClipReach::Make(model, clip);
  playback.wire_scale_.assign(model.parts.size(), 1.0);
  if (!playback.wires_.empty()) {
    playback.step_sample_ = MakeClipSample(clip, model);
    SampleClip(clip, 0.0, &playback.step_sample_);
    if (Status s = playback.reach_.Apply(0.0, ClipReach::Solve::kStep, &playback.step_sample_); !s)
      return Error{"reach: " + ToString(s)};
    if (Status s = playback.wires_.Reset(playback.step_sample_); !s)
      return Error{"wires: " + ToString(s)};
  }
  Result<ProfileDynamics> profiles =
      ProfileDynamics::Make(model, options.profile_wires, options.rigid_step);
  if (!profiles) return Error{"profile_wires: " + profiles.error()};
  playback.profiles_ = std::move(profiles).value();
  if (!playback.wires_.empty() || !playback.profiles_.empty()) {
    // Whose rigid motion the wires need: the parents of spine wires, the parts of profile
    // wires; of those, the ones moved by keys alone (no ancestor, nor itself, a body moved by
    // forces) get theirs by differencing their placements.
    std::vector<bool> needed(model.parts.size(), false);
    for (std::size_t w = 0; w < playback.wires_.size(); ++w)
      if (const int parent = model.parts[playback.wires_.part(w)].parent; parent >= 0)
        needed[std::size_t(parent)] = true;
    for (std::size_t p = 0; p < model.parts.size(); ++p)
      if (!model.parts[p].profiles.empty() && model.parts[p].mass.mass > 0.0 &&
          !playback.profiles_.empty())
        needed[p] = true;
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
      bool keyed = needed[p];
      for (int a = int(p); a >= 0 && keyed; a = model.parts[std::size_t(a)].parent)
        keyed = playback.dynamic_index_[std::size_t(a)] < 0;
      if (keyed) playback.keyed_parts_.push_back(p);
    }
    if (!playback.keyed_parts_.empty()) {
      playback.support_sample_ = MakeClipSample(clip, model);
      for (int k = 0; k < 3; ++k) {
        playback.placement_rotation_[k].resize(model.parts.size());
        playback.placement_translation_[k].resize(model.parts.size());
      }
    }
    playback.part_motion_.assign(model.parts.size(), RigidMotion{});
    playback.own_motion_.assign(model.parts.size(), false);
    for (const std::size_t p : playback.dynamic_parts_) playback.own_motion_[p] = true;
    for (const std::size_t p : playback.keyed_parts_) playback.own_motion_[p] = true;
    playback.velocity_before_.assign(playback.dynamic_parts_.size(), Vec3::Zero());
    playback.angular_velocity_before_.assign(playback.dynamic_parts_.size(), Vec3::Zero());
    if (playback.step_sample_.poses.empty()) {
      playback.step_sample_ = MakeClipSample(clip, model);
      SampleClip(clip, 0.0, &playback.step_sample_);
    }
    playback.support_acceleration_.assign(model.parts.size(), Vec3::Zero());
    playback.support_angular_velocity_.assign(model.parts.size(), Vec3::Zero());
    playback.support_angular_acceleration_.assign(model.parts.size(), Vec3::Zero());
    playback.support_rotation_.assign(model.parts.size(), Mat3::Identity());
    playback.combined_profiles_.reserve(playback.sample_.profile_loads.size() + 1 +
                                        playback.profiles_.size());
  }
  if (options.tracking.frequency > 0.0) {
    Result<ArticulatedTracking> tracking = ArticulatedTracking::Make(model, clip, options.tracking);
    if (!tracking) return Error{"tracking: " + tracking.error()};
    playback.tracking_ = std::move(tracking).value();
  }
  std::size_t widest = 0;
  for (const PartChannels<Track>& c : clip.parts) widest = std::max(widest, c.point_loads.size());
  playback.interactive_points_.resize(widest + 1);
  playback.interactive_profiles_.resize(playback.sample_.profile_loads.size() + 1);
  if (playback.HasDynamics()) {
    // The cache is bounded: a long clip gets its checkpoints further apart (a 1e5 s clip took
    // 12 GB before its first frame).
    const double per_checkpoint =
        double(playback.dynamic_parts_.size() * sizeof(RigidBodyState) +
               (playback.wires_.states().size() + playback.profiles_.states().size()) *
                   sizeof(ModalWireState) +
               playback.reach_.kept().size() * sizeof(ClipReach::Kept));
    std::size_t& interval = playback.options_.checkpoint_interval;
    const double wanted = steps / static_cast<double>(interval) + 2.0;
    if (wanted * per_checkpoint > kMaxCheckpointBytes)
      interval = static_cast<std::size_t>(
          std::ceil(double(interval) * wanted * per_checkpoint / kMaxCheckpointBytes));
    const auto count = static_cast<std::size_t>(steps / static_cast<double>(interval)) + 2;
    playback.checkpoint_count_ = count;
    playback.checkpoints_.resize(count * playback.dynamic_parts_.size());
    for (std::size_t d = 0; d < playback.dynamic_parts_.size(); ++d)
      playback.checkpoints_[d] = playback.bodies_[playback.dynamic_parts_[d]];
    const std::span<const ModalWireState> wire_states = playback.wires_.states();
    playback.wire_checkpoints_.resize(count * wire_states.size());
    std::copy(wire_states.begin(), wire_states.end(), playback.wire_checkpoints_.begin());
    const std::span<const ModalWireState> profile_states = playback.profiles_.states();
    playback.profile_checkpoints_.resize(count * profile_states.size());
    std::copy(profile_states.begin(), profile_states.end(), playback.profile_checkpoints_.begin());
    const std::span<const ClipReach::Kept> kept = playback.reach_.kept();
    playback.reach_checkpoints_.resize(count * kept.size());
    std::copy(kept.begin(), kept.end(), playback.reach_checkpoints_.begin());
    playback.checkpoints_done_ = 1;
  }
  return playback;
}

Vec3 Playback::BodyPointOffset(std::size_t d, const Vec3& rest) const {
  const RigidPartBody& body = dynamic_bodies_[d];
  const RigidBodyState& state = bodies_[dynamic_parts_[d]];
  return state.orientation * (body.axes.transpose() * (rest - body.reference));
}

Vec3 Playback::BodyAngularVelocity(std::size_t d) const {
  const RigidBodyState& state = bodies_[dynamic_parts_[d]];
  return state.orientation * state.angular_velocity;
}

Status Playback::StepBodies(double dt) {
  const bool wired = !wires_.empty() || !profiles_.empty();
  // The bodies' velocities before the step, for their accelerations over it.
  if (wired)
    for (std::size_t d = 0; d < dynamic_parts_.size(); ++d) {
      velocity_before_[d] = bodies_[dynamic_parts_[d]].velocity;
      angular_velocity_before_[d] = BodyAngularVelocity(d);
    }
  for (std::size_t d = 0; d < dynamic_parts_.size(); ++d) {
    const std::size_t p = dynamic_parts_[d];
    const RigidPartBody& body = dynamic_bodies_[d];
    RigidBodyState& state = bodies_[p];
    const double t0 = state.time;
    const Vec3& g = options_.gravity;
    RigidBodyStepJob step;
    step.integrator = options_.integrator;
    step.mass = body.mass;
    step.principal_moments = body.principal_moments;
    step.dt = dt;
    step.at_start = SampleRigidWrench(*clip_, p, body, t0, state, g);
    step.at_middle = SampleRigidWrench(*clip_, p, body, t0 + 0.5 * dt, state, g);
    step.at_end = SampleRigidWrench(*clip_, p, body, t0 + dt, state, g);
    step.state = &state;
    // Named by part: the step's own field ("dt") says nothing of which body or why.
    if (Status s = step.Run(); !s)
      return Status::InvalidElement("parts", int(p), "rigid body",
                                    "its step cannot go on: the forces and couples keyed on it "
                                    "are too large for its mass and inertia (or the rigid step "
                                    "too long): the motion would overflow");
  }
  clock_ += dt;
  if (!wired) return Status::Ok();
  SampleClip(*clip_, clock_, &step_sample_);
  PartMotions(dt);
  // The spine wires' supports: their parents' motion at their roots.
  for (std::size_t w = 0; w < wires_.size(); ++w) {
    const std::size_t p = wires_.part(w);
    const int parent = model_->parts[p].parent;
    if (parent < 0) continue;
    const RigidMotion& m = part_motion_[std::size_t(parent)];
    const Vec3 r = m.rotation * (model_->parts[p].spine_points.front() -
                                 model_->parts[std::size_t(parent)].spine_points.front());
    support_acceleration_[p] = PointAcceleration(m, r);
    support_angular_velocity_[p] = m.angular_velocity;
    support_angular_acceleration_[p] = m.angular_acceleration;
    support_rotation_[p] = m.rotation;
  }
  if (Status s = profiles_.Step(part_motion_, dt); !s) return s;
  if (wires_.empty()) return Status::Ok();
  if (!reach_.empty()) {
    PoseDynamicParts(&step_sample_);
    if (Status s = reach_.Apply(clock_, ClipReach::Solve::kStep, &step_sample_); !s) return s;
  }
  return wires_.Step(step_sample_, support_acceleration_, support_angular_velocity_,
                     support_angular_acceleration_, support_rotation_, dt);
}

void Playback::PartMotions(double dt) {
  // Bodies moved by forces: the acceleration of the part's root point at the step's end,
  // a_ref + alpha x r + omega x (omega x r) with omega and r at the step's end (differencing
  // the point's own velocity would tilt the centripetal part by half the step's turn).
  for (std::size_t d = 0; d < dynamic_parts_.size(); ++d) {
    const std::size_t p = dynamic_parts_[d];
    RigidMotion& m = part_motion_[p];
    m.angular_velocity = BodyAngularVelocity(d);
    m.angular_acceleration = (m.angular_velocity - angular_velocity_before_[d]) / dt;
    const Vec3 r = BodyPointOffset(d, model_->parts[p].spine_points.front());
    const Vec3 a_ref = (bodies_[p].velocity - velocity_before_[d]) / dt;
    m.acceleration = a_ref + m.angular_acceleration.cross(r) +
                     m.angular_velocity.cross(m.angular_velocity.cross(r));
    m.rotation = PoseOfRigidPart(dynamic_bodies_[d], model_->parts[p], bodies_[p])
                     .rotation.toRotationMatrix();
  }
  if (!keyed_parts_.empty()) KeyedPartMotions();
  // The rest follow their parents rigidly (their own joint motion and bending left out).
  for (std::size_t p = 0; p < model_->parts.size(); ++p) {
    const int parent = model_->parts[p].parent;
    if (own_motion_[p] || parent < 0) continue;
    const RigidMotion& from = part_motion_[std::size_t(parent)];
    RigidMotion& m = part_motion_[p];
    m = from;
    m.acceleration = PointAcceleration(
        from, from.rotation * (model_->parts[p].spine_points.front() -
                               model_->parts[std::size_t(parent)].spine_points.front()));
  }
}

void Playback::KeyedPartMotions() {
  // Parts moved by keys: central differences of their placements over one rigid step h.
  const double h = options_.rigid_step;
  ComposePlacements(*model_, step_sample_.poses, placement_rotation_[1], placement_translation_[1]);
  for (int k : {0, 2}) {
    SampleClip(*clip_, clock_ + double(k - 1) * h, &support_sample_);
    ComposePlacements(*model_, support_sample_.poses, placement_rotation_[k],
                      placement_translation_[k]);
  }
  // The rotation vector of the turn from placement a to placement b of part p (world axes).
  const auto turn = [&](int a, int b, std::size_t p) {
    const Eigen::AngleAxisd aa(placement_rotation_[b][p] * placement_rotation_[a][p].transpose());
    return Vec3(aa.angle() * aa.axis());
  };
  for (const std::size_t p : keyed_parts_) {
    const Vec3& root = model_->parts[p].spine_points.front();
    Vec3 x[3];
    for (int k = 0; k < 3; ++k)
      x[k] = placement_rotation_[k][p] * root + placement_translation_[k][p];
    RigidMotion& m = part_motion_[p];
    m.acceleration = (x[2] - 2.0 * x[1] + x[0]) / (h * h);
    m.angular_velocity = (turn(0, 1, p) + turn(1, 2, p)) / (2.0 * h);
    m.angular_acceleration = (turn(1, 2, p) - turn(0, 1, p)) / (h * h);
    m.rotation = placement_rotation_[1][p];
  }
}

void Playback::PoseDynamicParts(ClipSample* sample) const {
  for (std::size_t d = 0; d < dynamic_parts_.size(); ++d) {
    const std::size_t p = dynamic_parts_[d];
    const SpineLoads loads = sample->poses[p].loads;
    sample->poses[p] = PoseOfRigidPart(dynamic_bodies_[d], model_->parts[p], bodies_[p]);
    sample->poses[p].loads = loads;
  }
}

// Brings the dynamic bodies to clip time t: from the latest checkpoint at or before t (making
// the missing checkpoints on the way), then whole steps, then one partial step to land on t.
Status Playback::AdvanceBodies(double t) {
  const std::size_t parts = dynamic_parts_.size(), wires = wires_.size();
  const std::size_t profiles = profiles_.size();
  const std::size_t reaches = reach_.kept().size();
  const double h = options_.rigid_step;
  const double span = h * static_cast<double>(options_.checkpoint_interval);
  const std::size_t capacity = checkpoint_count_;
  std::size_t wanted = std::min(static_cast<std::size_t>(std::floor(t / span)), capacity - 1);
  // t / span may round up to a whole number whose checkpoint lies just after t.
  if (wanted > 0 && static_cast<double>(wanted) * span > t) --wanted;
  auto load = [&](std::size_t c) {
    for (std::size_t d = 0; d < parts; ++d)
      bodies_[dynamic_parts_[d]] = checkpoints_[c * parts + d];
    wires_.Restore(std::span<const ModalWireState>(wire_checkpoints_).subspan(c * wires, wires));
    profiles_.Restore(
        std::span<const ModalWireState>(profile_checkpoints_).subspan(c * profiles, profiles));
    reach_.Restore(
        std::span<const ClipReach::Kept>(reach_checkpoints_).subspan(c * reaches, reaches));
    clock_ = static_cast<double>(c) * span;
  };
  if (wanted < checkpoints_done_) {
    load(wanted);
  } else {
    load(checkpoints_done_ - 1);
    for (std::size_t c = checkpoints_done_; c <= wanted; ++c) {
      for (std::size_t k = 0; k < options_.checkpoint_interval; ++k)
        if (Status s = StepBodies(h); !s) return s;
      // Fixed step times: restart each checkpoint from its exact time, not a rounded sum.
      for (std::size_t d = 0; d < parts; ++d) {
        bodies_[dynamic_parts_[d]].time = static_cast<double>(c) * span;
        checkpoints_[c * parts + d] = bodies_[dynamic_parts_[d]];
      }
      clock_ = static_cast<double>(c) * span;
      const std::span<const ModalWireState> states = wires_.states();
      std::copy(states.begin(), states.end(),
                wire_checkpoints_.begin() + std::ptrdiff_t(c * wires));
      const std::span<const ModalWireState> profile_states = profiles_.states();
      std::copy(profile_states.begin(), profile_states.end(),
                profile_checkpoints_.begin() + std::ptrdiff_t(c * profiles));
      const std::span<const ClipReach::Kept> kept = reach_.kept();
      std::copy(kept.begin(), kept.end(), reach_checkpoints_.begin() + std::ptrdiff_t(c * reaches));
      checkpoints_done_ = c + 1;
    }
  }
  const double start = static_cast<double>(wanted) * span;
  const auto whole = static_cast<std::size_t>(std::max(0.0, std::floor((t - start) / h)));
  for (std::size_t k = 0; k < whole; ++k)
    if (Status s = StepBodies(h); !s) return s;
  const double rest = t - (start + static_cast<double>(whole) * h);
  if (rest > 1e-12 * h)
    if (Status s = StepBodies(rest); !s) return s;
  return Status::Ok();
}

Status Playback::SetInteractiveJointAngles(std::uint32_t part, const Vec3& degrees) {
  if (part >= model_->parts.size()) return Status::Invalid("part", "is out of range");
  if (model_->parts[part].parent < 0) return Status::Invalid("part", "is the root: no joint");
  if (!degrees.allFinite()) return Status::Invalid("degrees", "must be finite");
  interactive_joints_.resize(model_->parts.size(), Vec3::Zero());
  interactive_joints_[part] = degrees;
  return Status::Ok();
}

Vec3 Playback::InteractiveJointAngles(std::uint32_t part) const {
  return part < interactive_joints_.size() ? interactive_joints_[part] : Vec3::Zero();
}

Status Playback::SetInteractiveLoad(const std::optional<InteractiveLoad>& load) {
  if (load) {
    if (load->part >= model_->parts.size()) return Status::Invalid("part", "is out of range");
    const PartModel& part = model_->parts[load->part];
    if (load->profile < -1 || load->profile >= static_cast<int>(part.profiles.size()))
      return Status::Invalid("profile", "is out of range");
    if (!(load->at >= 0.0 && load->at <= 1.0)) return Status::Invalid("at", "must lie in [0, 1]");
    if (!(std::isfinite(load->force.x()) && std::isfinite(load->force.y()) &&
          std::isfinite(load->force.z())))
      return Status::Invalid("force", "must be finite");
  }
  interactive_ = load;
  return Status::Ok();
}

// Adds the interactive load to the sampled inputs, in the local axes of the frames the last
// evaluation left in the workspace (the rest frames before the first).
void Playback::ApplyInteractiveLoad() {
  const InteractiveLoad& load = *interactive_;
  const PartModel& part = model_->parts[load.part];
  const std::size_t n = part.spine_frames.size();
  auto frame_at = [&](double v) -> const Frame& {
    const auto s = static_cast<std::size_t>(std::lround(v * static_cast<double>(n - 1)));
    return evaluated_ ? workspace_.spine_frames[load.part][s] : part.spine_frames[s];
  };
  auto local = [&](const Frame& f) {
    return Vec3(load.force.dot(f.normal), load.force.dot(f.binormal), load.force.dot(f.tangent));
  };
  if (load.profile < 0) {
    SpineLoads& loads = sample_.poses[load.part].loads;
    std::copy(loads.bending_point_loads.begin(), loads.bending_point_loads.end(),
              interactive_points_.begin());
    interactive_points_[loads.bending_point_loads.size()] = {load.at, local(frame_at(load.at))};
    loads.bending_point_loads = std::span<const PointLoad>(interactive_points_.data(),
                                                           loads.bending_point_loads.size() + 1);
    return;
  }
  const auto profile = static_cast<std::uint32_t>(load.profile);
  interactive_profile_point_ = {load.at, local(frame_at(part.profiles[profile].spine_v))};
  std::copy(sample_.profile_loads.begin(), sample_.profile_loads.end(),
            interactive_profiles_.begin());
  ProfileLoads& extra = interactive_profiles_[sample_.profile_loads.size()];
  extra.part = load.part;
  extra.profile = profile;
  extra.from = 0.0;
  extra.to = 1.0;
  extra.boundary = BoundaryCondition::kClamped;
  extra.point_loads = std::span<const PointLoad>(&interactive_profile_point_, 1);
  extra.line_loads = {};
}

namespace {

// The reason is the same for both evaluations (render and view draw doubles, bake floats).
Status BeyondGeometryRange(std::string_view field, std::size_t vertex) {
  return Status::InvalidElement(field, static_cast<int>(vertex), {},
                                "not finite, or beyond 1e7 m (the deformation overflowed)");
}

}  // namespace

Status Playback::Evaluate(double t, std::span<Vec3> positions, std::span<Vec3> normals,
                          std::span<PartWarnings> warnings) {
  EvaluateRigJob job;
  job.positions = positions;
  job.normals = normals;
  job.warnings = warnings;
  if (Status s = Run(t, job); !s) return s;
  // Every consumer (renderer, export) takes floats: a deformation that overflowed them fails.
  constexpr double kBound = detail::kMaxGeometryCoordinate;
  if (const std::size_t i = detail::FirstBeyond(positions, kBound); i != detail::kAllFinite)
    return BeyondGeometryRange("positions", i);
  if (const std::size_t i = detail::FirstBeyond(normals, kBound); i != detail::kAllFinite)
    return BeyondGeometryRange("normals", i);
  return Status::Ok();
}

Status Playback::Evaluate(double t, const FloatOutput& output, std::span<PartWarnings> warnings) {
  EvaluateRigJob job;
  job.float_positions = output.positions;
  job.float_position_stride = output.position_stride;
  job.float_normals = output.normals;
  job.float_normal_stride = output.normal_stride;
  job.float_vertex_order = output.vertex_order;
  job.warnings = warnings;
  if (Status s = Run(t, job); !s) return s;
  const std::size_t count =
      output.vertex_order.empty() ? model_->vertices.size() : output.vertex_order.size();
  if (const std::size_t i = detail::FirstNonFiniteFloat3(
          output.positions, count, output.position_stride, detail::kMaxGeometryCoordinate);
      i != detail::kAllFinite)
    return BeyondGeometryRange("positions", i);
  if (!output.normals.empty()) {
    if (const std::size_t i =
            detail::FirstNonFiniteFloat3(output.normals, count, output.normal_stride);
        i != detail::kAllFinite)
      return BeyondGeometryRange("normals", i);
  }
  return Status::Ok();
}

Status Playback::Run(double t, EvaluateRigJob& job) {
  if (!std::isfinite(t)) return Status::Invalid("t", "must be finite");
  const double local = clip_->LocalTime(t);
  SampleClip(*clip_, local, &sample_);
  if (tracking_)
    if (Status s = tracking_->Apply(local, sample_.poses); !s) return s;
  if (HasDynamics()) {
    if (Status s = AdvanceBodies(local); !s) return s;
    PoseDynamicParts(&sample_);
  }
  if (Status s = reach_.Apply(local, ClipReach::Solve::kFresh, &sample_); !s) return s;
  if (HasDynamics()) {
    // A reaching part's motion beyond its static shape fades with the reach's weight.
    for (std::size_t j = 0; j < reach_.parts().size(); ++j)
      wire_scale_[reach_.parts()[j]] = 1.0 - reach_.reports()[j].weight;
    if (Status s = wires_.Apply(sample_.poses, wire_scale_); !s) return s;
  }
  for (std::size_t p = 0; p < interactive_joints_.size(); ++p)
    if (!interactive_joints_[p].isZero())
      sample_.poses[p].rotation = (sample_.poses[p].rotation *
                                   JointRotation(model_->parts[p].joint, interactive_joints_[p]))
                                      .normalized();
  std::span<const ProfileLoads> profile_loads = sample_.profile_loads;
  if (interactive_) {
    ApplyInteractiveLoad();
    if (interactive_->profile >= 0) profile_loads = interactive_profiles_;
  }
  if (!profiles_.empty()) {
    // The profile wires' motion as loads of their own, after the clip's (capacity reserved).
    combined_profiles_.assign(profile_loads.begin(), profile_loads.end());
    if (Status s = profiles_.Apply(&combined_profiles_); !s) return s;
    profile_loads = combined_profiles_;
  }
  job.model = model_;
  job.poses = sample_.poses;
  job.profile_loads = profile_loads;
  job.workspace = &workspace_;
  job.preserve_volume = options_.preserve_volume;
  const Status status = job.Run();
  evaluated_ = evaluated_ || status.ok();
  return status;
}

}  // namespace wirerig
