#include "wirerig/anim/profile_dynamics.h"

#include "wirerig/io/name_hint.h"

#include <algorithm>
#include <cmath>
#include <numbers>
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

// 0 at x <= 0, 1 at x >= 1, smooth between.
double SmoothStep(double x) {
  const double c = std::clamp(x, 0.0, 1.0);
  return c * c * (3.0 - 2.0 * c);
}

// A loop's weight at u along its part's loops (u in [0, 1]): full over the middle half.
double JointFade(double u) { return SmoothStep(u / 0.25) * SmoothStep((1.0 - u) / 0.25); }

// Every part's loops' rest points, world axes: [part][profile][point].
std::vector<std::vector<std::vector<Vec3>>> RestLoopPoints(const RigModel& model) {
  std::vector<std::vector<std::vector<Vec3>>> out(model.parts.size());
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    for (std::size_t i = 0; i < model.parts[p].profiles.size(); ++i)
      out[p].push_back(RestProfilePoints(model.parts[p], i));
  return out;
}

// The weights of loop i of part p's points: the loop's JointFade times, per point, smoothstep of
// its distance to the nearest loop point of another part over `radius` (no motion where another
// part's skin lies against this one: a tentacle's root on a mantle's side, an arm by a chest).
std::vector<double> PointWeights(const RigModel& model,
                                 const std::vector<std::vector<std::vector<Vec3>>>& rest,
                                 std::size_t p, std::size_t i, double radius) {
  const std::vector<ProfileModel>& profiles = model.parts[p].profiles;
  const double first = profiles.front().spine_v, last = profiles.back().spine_v;
  const double along =
      last > first ? JointFade((profiles[i].spine_v - first) / (last - first)) : 1.0;
  std::vector<double> out;
  for (const Vec3& x : rest[p][i]) {
    double nearest = radius;
    for (std::size_t o = 0; o < rest.size(); ++o)
      if (o != p)
        for (const std::vector<Vec3>& loop : rest[o])
          for (const Vec3& y : loop) nearest = std::min(nearest, (x - y).norm());
    out.push_back(along * SmoothStep(nearest / radius));
  }
  return out;
}

}  // namespace

Vec3 PointAcceleration(const RigidMotion& motion, const Vec3& offset) {
  const Vec3& w = motion.angular_velocity;
  return motion.acceleration + motion.angular_acceleration.cross(offset) + w.cross(w.cross(offset));
}

Result<ProfileDynamics> ProfileDynamics::Make(const RigModel& model,
                                              const ProfileWireOptions& options, double step) {
  if (std::string bad = ModalOptionsError(options.modes, options.damping_ratio); !bad.empty())
    return Error{bad};
  if (!(std::isfinite(options.frequency) && options.frequency > 0.0 && options.frequency <= 1000.0))
    return Error{"frequency: must be in (0, 1000] Hz"};
  if (!(std::isfinite(options.limit) && options.limit > 0.0 && options.limit <= 1.0))
    return Error{"limit: must be in (0, 1] (of a loop's mean radius)"};
  std::vector<bool> chosen(model.parts.size(), options.parts.empty());
  for (std::size_t i = 0; i < options.parts.size(); ++i) {
    const auto named = std::find_if(model.parts.begin(), model.parts.end(),
                                    [&](const PartModel& p) { return p.name == options.parts[i]; });
    if (named == model.parts.end()) {
      std::vector<std::string> names;
      for (const PartModel& part : model.parts) names.push_back(part.name);
      return Error{"parts[" + std::to_string(i) + "]: the rig has no part named \"" +
                   options.parts[i] + "\"" + NameHint(options.parts[i], names, "parts")};
    }
    chosen[std::size_t(named - model.parts.begin())] = true;
  }
  ProfileDynamics out;
  out.model_ = &model;
  if (options.modes == 0) return out;
  ModalBasis basis;
  if (Status s = BuildModalBasis(BoundaryCondition::kClamped, options.modes, &basis); !s)
    return Error{ToString(s)};
  const std::vector<std::vector<std::vector<Vec3>>> rest = RestLoopPoints(model);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const PartModel& part = model.parts[p];
    if (!chosen[p] || !(part.mass.mass > 0.0)) continue;
    double total = 0.0;
    for (const ProfileModel& profile : part.profiles) total += Perimeter(profile);
    if (!(total > 0.0)) continue;
    const std::string where = "part \"" + part.name + "\": ";
    for (std::size_t i = 0; i < part.profiles.size(); ++i) {
      const ProfileModel& profile = part.profiles[i];
      const std::size_t m = profile.local_points.size();
      const double length = Perimeter(profile);
      if (m < 2 || !(length > 0.0)) continue;
      Wire wire;
      wire.part = p;
      wire.profile = i;
      wire.model.basis = basis;
      wire.model.length = length;
      wire.model.mass_per_length = part.mass.mass / total;
      const double omega = 2.0 * std::numbers::pi * options.frequency / length;  // L in m
      wire.model.bending_stiffness = wire.model.mass_per_length * std::pow(length, 4) * omega *
                                     omega / std::pow(basis.beta[0], 4);
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
      double radius = 0.0;
      for (const Vec3& x : profile.local_points) radius += x.norm() / double(m);
      radius = std::max(radius, 1e-9);
      wire.reach = options.limit * radius;
      wire.weights = PointWeights(model, rest, p, i, radius);
      out.wires_.push_back(std::move(wire));
    }
  }
  out.states_.resize(out.wires_.size());
  out.residuals_.resize(out.wires_.size());
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
    ModalResidual& r = residuals_[w];
    r.modes = wire.model.basis.modes;
    for (int n = 0; n < r.modes; ++n) r.coordinates[n] = state.q[n] - state.q_static[n];
    r.uniform_load = -wire.model.mass_per_length * wire.support_acceleration;
    if (Status s =
            EvaluateLoopMotion(r, wire.model.length, wire.model.bending_stiffness, wire.samples,
                               wire.mode_values, wire.weights, wire.reach, wire.displacement);
        !s)
      return s;
    ProfileLoads loads;
    loads.part = std::uint32_t(wire.part);
    loads.profile = std::uint32_t(wire.profile);
    loads.boundary = BoundaryCondition::kClamped;
    loads.extra_displacement = wire.displacement;
    out->push_back(loads);
  }
  return Status::Ok();
}

ClipProfileWire ProfileDynamics::Recorded(std::size_t w) const {
  const Wire& wire = wires_[w];
  const ProfileModel& profile = model_->parts[wire.part].profiles[wire.profile];
  return {std::uint32_t(wire.part),
          std::uint32_t(wire.profile),
          std::uint32_t(wire.model.basis.modes),
          profile.closed,
          wire.model.length,
          wire.model.bending_stiffness,
          wire.reach,
          wire.weights};
}

void ProfileDynamics::Restore(std::span<const ModalWireState> states) {
  std::copy(states.begin(), states.end(), states_.begin());
}

}  // namespace wirerig
