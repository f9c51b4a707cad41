#include "wirerig/anim/profile_dynamics.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "wirerig/runtime/spine_interpolation.h"

namespace wirerig {
namespace {

double Perimeter(const ProfileModel& profile) {
  const std::size_t m = profile.local_points.size();
  double length = 0.0;
  for (std::size_t q = 1; q < m; ++q)
    length += (profile.local_points[q] - profile.local_points[q - 1]).norm();
  if (profile.closed && m > 1)
    length += (profile.local_points[0] - profile.local_points[m - 1]).norm();
  return length;
}

}  // namespace

Vec3 PointAcceleration(const RigidMotion& motion, const Vec3& offset) {
  const Vec3& w = motion.angular_velocity;
  return motion.acceleration + motion.angular_acceleration.cross(offset) + w.cross(w.cross(offset));
}

Result<ProfileDynamics> ProfileDynamics::Make(const RigModel& model,
                                              const WireDynamicsOptions& options, double step) {
  if (!(options.modes >= 0 && options.modes <= ModalBasis::kMaxModes))
    return Error{"modes: must be in [0, " + std::to_string(ModalBasis::kMaxModes) + "]"};
  if (!(std::isfinite(options.damping_ratio) && options.damping_ratio >= 0.0 &&
        options.damping_ratio <= ModalWireModel::kMaxDampingRatio))
    return Error{"damping_ratio: must be in [0, 100]"};
  ProfileDynamics out;
  out.model_ = &model;
  if (options.modes == 0) return out;
  ModalBasis basis;
  if (Status s = BuildModalBasis(BoundaryCondition::kClamped, options.modes, &basis); !s)
    return Error{ToString(s)};
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const PartModel& part = model.parts[p];
    if (!(part.mass.mass > 0.0)) continue;
    double total = 0.0;
    for (const ProfileModel& profile : part.profiles) total += Perimeter(profile);
    if (!(total > 0.0)) continue;
    const std::string where = "part \"" + part.name + "\": ";
    for (std::size_t i = 0; i < part.profiles.size(); ++i) {
      const ProfileModel& profile = part.profiles[i];
      const std::size_t m = profile.local_points.size();
      const double length = Perimeter(profile);
      if (m < 2 || !(length > 0.0) || !(profile.stiffness.bending > 0.0)) continue;
      Wire wire;
      wire.part = p;
      wire.profile = i;
      wire.model.basis = basis;
      wire.model.length = length;
      wire.model.bending_stiffness = profile.stiffness.bending;
      wire.model.mass_per_length = part.mass.mass / total;
      wire.model.damping_ratio = options.damping_ratio;
      if (Status s = PrecomputeModalStep(wire.model, step, &wire.table); !s)
        return Error{where + "profile " + std::to_string(i) + ": " + ToString(s)};
      Vec3 origin;
      wire.axes = FrameAxes(
          InterpolateSpine(part.spine_points, part.spine_frames, profile.spine_v, &origin));
      wire.origin = origin;
      // The profile's points as EvaluateRigJob samples a whole stretch: q / m closed, q / (m - 1)
      // open.
      const double segments = double(profile.closed ? m : m - 1);
      wire.samples.resize(m);
      for (std::size_t q = 0; q < m; ++q) wire.samples[q] = double(q) / segments;
      wire.mode_values.resize(m * std::size_t(options.modes));
      wire.mode_slopes.resize(m * std::size_t(options.modes));
      if (Status s = TabulateModes(basis, wire.samples, wire.mode_values, wire.mode_slopes); !s)
        return Error{where + ToString(s)};
      wire.displacement.resize(m);
      out.wires_.push_back(std::move(wire));
    }
  }
  out.states_.resize(out.wires_.size());
  out.Reset();
  return out;
}

void ProfileDynamics::Reset() {
  for (std::size_t w = 0; w < wires_.size(); ++w) {
    wires_[w].support_acceleration = Vec3::Zero();
    (void)InitializeModalWireAtRest(wires_[w].model, &states_[w]);  // a valid model
  }
}

Status ProfileDynamics::Step(std::span<const RigidMotion> motion, double dt) {
  if (dt < ModalWireStepJob::kMinTimeStep) return Status::Ok();
  for (std::size_t w = 0; w < wires_.size(); ++w) {
    Wire& wire = wires_[w];
    const RigidMotion& m = motion[wire.part];
    const Vec3& root = model_->parts[wire.part].spine_points.front();
    const Vec3 a = PointAcceleration(m, m.rotation * (wire.origin - root));
    // Into the profile's frame axes: world -> rest world -> (normal, binormal, tangent).
    wire.support_acceleration = wire.axes.transpose() * (m.rotation.transpose() * a);
    ModalWireStepJob step;
    step.model = &wire.model;
    step.loads.support_acceleration = wire.support_acceleration;
    step.dt = dt;
    step.step_table = dt == wire.table.dt ? &wire.table : nullptr;
    step.state = &states_[w];
    if (Status s = step.Run(); !s) return s;
  }
  return Status::Ok();
}

Status ProfileDynamics::Apply(std::vector<ProfileLoads>* out) {
  for (std::size_t w = 0; w < wires_.size(); ++w) {
    Wire& wire = wires_[w];
    const ModalWireState& state = states_[w];
    ModalResidual r;
    r.modes = wire.model.basis.modes;
    for (int n = 0; n < r.modes; ++n) r.coordinates[n] = state.q[n] - state.q_static[n];
    r.uniform_load = -wire.model.mass_per_length * wire.support_acceleration;
    ModalResidualJob job;
    job.boundary = BoundaryCondition::kClamped;
    job.length = wire.model.length;
    job.bending_stiffness = wire.model.bending_stiffness;
    job.residual = &r;
    job.samples = wire.samples;
    job.mode_values = wire.mode_values;
    job.displacement = wire.displacement;
    if (Status s = job.Run(); !s) return s;
    ProfileLoads loads;
    loads.part = std::uint32_t(wire.part);
    loads.profile = std::uint32_t(wire.profile);
    loads.boundary = BoundaryCondition::kClamped;
    loads.extra_displacement = wire.displacement;
    out->push_back(loads);
  }
  return Status::Ok();
}

void ProfileDynamics::Restore(std::span<const ModalWireState> states) {
  std::copy(states.begin(), states.end(), states_.begin());
}

}  // namespace wirerig
