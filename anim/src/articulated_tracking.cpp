#include "wirerig/anim/articulated_tracking.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "wirerig/io/finite.h"

namespace wirerig {
namespace {

ArticulatedJointType TypeOf(JointType type) {
  switch (type) {
    case JointType::kHinge:
      return ArticulatedJointType::kHinge;
    case JointType::kFixed:
      return ArticulatedJointType::kFixed;
    case JointType::kBall:
      break;
  }
  return ArticulatedJointType::kBall;
}

}  // namespace

Result<ArticulatedTracking> ArticulatedTracking::Make(const RigModel& model, const Clip& clip,
                                                      const TrackingOptions& options) {
  if (!(std::isfinite(options.frequency) && options.frequency > 0.0))
    return Error{"frequency: must be positive and finite (Hz)"};
  if (!(std::isfinite(options.damping_ratio) && options.damping_ratio >= 0.0))
    return Error{"damping_ratio: must be finite and not negative"};
  if (!IsFinite(options.gravity)) return Error{"gravity: must be finite"};
  if (!(std::isfinite(options.step) && options.step > 0.0 && options.step <= 0.1))
    return Error{"step: must be in (0, 0.1] s"};
  if (options.checkpoint_interval == 0) return Error{"checkpoint_interval: must be at least 1"};
  if (model.parts.empty() || clip.parts.size() != model.parts.size())
    return Error{"clip: was built for another rig (part counts differ)"};
  const double steps = std::ceil(clip.duration / options.step);
  if (!(steps < 1e8)) return Error{"step: too small for the clip's duration (over 1e8 steps)"};

  ArticulatedTracking out;
  out.model_ = &model;
  out.clip_ = &clip;
  out.options_ = options;
  const std::size_t n = model.parts.size();
  out.axes_.resize(n, Mat3::Identity());
  std::vector<ArticulatedBodyDesc> bodies(n);
  for (std::size_t p = 0; p < n; ++p) {
    const PartModel& part = model.parts[p];
    if ((p == 0) != (part.parent < 0))
      return Error{"part \"" + part.name + "\": tracking needs one root, the first part"};
    if (!(part.mass.mass > 0.0))
      return Error{"part \"" + part.name + "\": has no mass (its profiles are open)"};
    const Mat3 axes = p == 0 ? Mat3::Identity() : part.joint.axes;
    out.axes_[p] = axes;
    ArticulatedBodyDesc& body = bodies[p];
    body.parent = part.parent;
    const Vec3& root = part.spine_points.front();
    if (p == 0) {
      body.joint = ArticulatedJointType::kFixed;
      body.joint_position = root;
    } else {
      const auto parent = std::size_t(part.parent);
      body.joint = TypeOf(part.joint.type);
      body.joint_position =
          out.axes_[parent].transpose() * (root - model.parts[parent].spine_points.front());
      body.joint_rotation = Quat(out.axes_[parent].transpose() * axes).normalized();
      body.min_degrees = part.joint.min_degrees;
      body.max_degrees = part.joint.max_degrees;
    }
    body.mass = part.mass.mass;
    body.center_of_mass = axes.transpose() * (part.mass.center - root);
    const Mat3 inertia = axes.transpose() * part.mass.inertia * axes;
    body.inertia = 0.5 * (inertia + inertia.transpose());
  }
  if (Status s = ArticulatedModel::Build(bodies, &out.articulated_); !s) {
    const std::string where = s.index >= 0 && std::size_t(s.index) < n
                                  ? "part \"" + model.parts[s.index].name + "\": "
                                  : std::string();
    const std::string member = s.member.empty() ? "" : "." + std::string(s.member);
    return Error{where + std::string(s.field) + member + ": " + std::string(s.reason)};
  }
  out.workspace_ = MakeArticulatedWorkspace(out.articulated_);
  out.state_ = MakeArticulatedState(out.articulated_);

  // The inertia each joint drives: its subtree's, about the joint (world axes at rest).
  out.inertia_.assign(n, 0.0);
  for (std::size_t c = 1; c < n; ++c) {
    const Vec3& joint = model.parts[c].spine_points.front();
    Mat3 total = Mat3::Zero();
    std::vector<bool> in_subtree(n, false);
    in_subtree[c] = true;
    for (std::size_t b = c; b < n; ++b) {
      if (b > c) in_subtree[b] = model.parts[b].parent >= 0 && in_subtree[model.parts[b].parent];
      if (!in_subtree[b]) continue;
      const MassProperties& m = model.parts[b].mass;
      const Vec3 d = m.center - joint;
      total += m.inertia + m.mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
    }
    if (model.parts[c].joint.type == JointType::kHinge) {
      const Vec3 axis = out.axes_[c].col(0);
      out.inertia_[c] = axis.dot(total * axis);
    } else {
      out.inertia_[c] = Eigen::SelfAdjointEigenSolver<Mat3>(total).eigenvalues().maxCoeff();
    }
  }
  out.targets_.resize(n);
  std::size_t wrenches = 0;
  for (std::size_t p = 1; p < n; ++p) {
    const PartChannels<Track>& channels = clip.parts[p];
    wrenches += channels.rigid_forces.size() + (channels.rigid_torque.IsEmpty() ? 0 : 1);
  }
  out.wrenches_.reserve(wrenches);
  out.keyed_ = MakeClipSample(clip, model);
  // The chain starts at rest in the clip's first keyed pose.
  out.SetTargets(0.0);
  for (std::size_t c = 1; c < n; ++c) {
    JointState& joint = out.state_.joints[c];
    joint.rotation = out.targets_[c].rotation;
    joint.angle = out.targets_[c].angle;
  }
  if (Status s = EvaluateArticulatedBodies(out.articulated_, &out.state_); !s)
    return Error{std::string(s.field) + ": " + std::string(s.reason)};
  const auto count = std::size_t(steps / double(options.checkpoint_interval)) + 2;
  out.checkpoints_.assign(count, out.state_);
  out.checkpoints_done_ = 1;
  return out;
}

void ArticulatedTracking::SetTargets(double t) {
  SampleClip(*clip_, t, &keyed_);
  const double w = 2.0 * std::numbers::pi * options_.frequency;
  for (std::size_t c = 1; c < targets_.size(); ++c) {
    const Mat3& axes = axes_[c];
    const Quat local(axes.transpose() * keyed_.poses[c].rotation.toRotationMatrix() * axes);
    JointTarget& target = targets_[c];
    target.rotation = local.normalized();
    target.angle = 2.0 * std::atan2(local.x(), local.w());  // hinges: a turn about X
    target.stiffness = w * w * inertia_[c];
    target.damping = 2.0 * options_.damping_ratio * w * inertia_[c];
  }
  // The root's keyed acceleration, as a fictitious force in its own frame.
  const Track<Vec3>& translation = clip_->parts[0].translation;
  Vec3 acceleration = Vec3::Zero();
  if (!translation.IsEmpty()) {
    const double h = options_.step;
    acceleration = (translation.Sample(t + h) - 2.0 * translation.Sample(t) +
                    translation.Sample(std::max(t - h, 0.0))) /
                   (h * h);
    if (t - h < 0.0) acceleration = Vec3::Zero();
  }
  const Mat3 root = keyed_.poses[0].rotation.toRotationMatrix();
  effective_gravity_ = root.transpose() * (options_.gravity - acceleration);
  // Keyed forces (world axes, at a body point given at rest) and torques, into the root's frame.
  wrenches_.clear();
  for (std::size_t p = 1; p < clip_->parts.size(); ++p) {
    const PartChannels<Track>& channels = clip_->parts[p];
    const BodyMotion& body = state_.bodies[p];
    const Vec3& joint = model_->parts[p].spine_points.front();
    for (const RigidForceChannels<Track>& f : channels.rigid_forces) {
      const Vec3 local = axes_[p].transpose() * (f.at - joint);
      wrenches_.push_back({int(p), root.transpose() * f.force.Sample(t),
                           body.translation + body.rotation * local, Vec3::Zero()});
    }
    if (!channels.rigid_torque.IsEmpty())
      wrenches_.push_back({int(p), Vec3::Zero(), body.translation,
                           root.transpose() * channels.rigid_torque.Sample(t)});
  }
}

Status ArticulatedTracking::Step() {
  SetTargets(double(steps_) * options_.step);
  ArticulatedStepJob job;
  job.model = &articulated_;
  job.dt = options_.step;
  job.gravity = effective_gravity_;
  job.targets = targets_;
  job.wrenches = wrenches_;
  job.workspace = &workspace_;
  job.state = &state_;
  if (Status s = job.Run(); !s) return s;
  ++steps_;
  if (steps_ % options_.checkpoint_interval == 0) {
    const std::size_t k = steps_ / options_.checkpoint_interval;
    if (k == checkpoints_done_ && k < checkpoints_.size()) {
      checkpoints_[k] = state_;
      ++checkpoints_done_;
    }
  }
  return Status::Ok();
}

Status ArticulatedTracking::Apply(double t, std::span<PartPose> poses) {
  if (!std::isfinite(t)) return Status::Invalid("t", "must be finite");
  if (poses.size() != model_->parts.size())
    return Status::Invalid("poses", "one per part of the tracked model");
  const auto target = std::size_t(std::max(0.0, std::floor(t / options_.step + 1e-9)));
  if (target < steps_) {  // back in time: from the last cached state at or before it
    const std::size_t k = std::min(target / options_.checkpoint_interval, checkpoints_done_ - 1);
    state_ = checkpoints_[k];
    steps_ = k * options_.checkpoint_interval;
  }
  while (steps_ < target)
    if (Status s = Step(); !s) return s;
  for (std::size_t c = 1; c < poses.size(); ++c) {
    const JointState& joint = state_.joints[c];
    Quat turn = Quat::Identity();
    switch (articulated_.body(int(c)).joint) {
      case ArticulatedJointType::kBall:
        turn = joint.rotation;
        break;
      case ArticulatedJointType::kHinge:
        turn = Quat(Eigen::AngleAxisd(joint.angle, Vec3::UnitX()));
        break;
      default:
        break;
    }
    poses[c].rotation =
        Quat(axes_[c] * turn.toRotationMatrix() * axes_[c].transpose()).normalized();
  }
  return Status::Ok();
}

Vec3 ArticulatedTracking::JointAngles(std::size_t part) const {
  return JointAnglesDegrees(articulated_.body(int(part)).joint, state_.joints[part]);
}

}  // namespace wirerig
