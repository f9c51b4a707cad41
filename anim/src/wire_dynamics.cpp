#include "wirerig/anim/wire_dynamics.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace wirerig {

std::string ModalOptionsError(int modes, double damping_ratio) {
  if (!(modes >= 0 && modes <= ModalBasis::kMaxModes))
    return "modes: must be in [0, " + std::to_string(ModalBasis::kMaxModes) + "]";
  if (!(std::isfinite(damping_ratio) && damping_ratio >= 0.0 &&
        damping_ratio <= ModalWireModel::kMaxDampingRatio))
    return "damping_ratio: must be in [0, 100]";
  return {};
}

Result<WireDynamics> WireDynamics::Make(const RigModel& model, const Clip& clip,
                                        const WireDynamicsOptions& options, double step) {
  if (std::string bad = ModalOptionsError(options.modes, options.damping_ratio); !bad.empty())
    return Error{bad};
  WireDynamics out;
  out.model_ = &model;
  if (options.modes == 0) return out;
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const PartModel& part = model.parts[p];
    if (part.kind != SpineKind::kDeformable || !(part.mass.mass > 0.0)) continue;
    Wire wire;
    wire.part = p;
    const std::vector<BoundaryKey>& keys = clip.parts[p].boundary;
    const BoundaryCondition boundary =
        keys.empty() ? BoundaryCondition::kCantileverFree : keys.front().boundary;
    const std::string where = "part \"" + part.name + "\": ";
    if (Status s = BuildModalBasis(boundary, options.modes, &wire.model.basis); !s)
      return Error{where + ToString(s)};
    wire.model.length = part.spine_length;
    wire.model.bending_stiffness = part.spine_stiffness.bending;
    wire.model.mass_per_length = part.mass.mass / part.spine_length;
    wire.model.damping_ratio = options.damping_ratio;
    if (Status s = PrecomputeModalStep(wire.model, step, &wire.table); !s)
      return Error{where + ToString(s)};
    const std::size_t n = part.spine_points.size();
    wire.samples.resize(n);
    for (std::size_t k = 0; k < n; ++k) wire.samples[k] = double(k) / double(n - 1);
    wire.mode_values.resize(n * std::size_t(options.modes));
    wire.mode_slopes.resize(n * std::size_t(options.modes));
    if (Status s =
            TabulateModes(wire.model.basis, wire.samples, wire.mode_values, wire.mode_slopes);
        !s)
      return Error{where + ToString(s)};
    wire.extra_displacement.resize(n);
    wire.extra_slope.resize(n);
    out.wires_.push_back(std::move(wire));
  }
  out.states_.resize(out.wires_.size());
  out.residuals_.resize(out.wires_.size());
  out.scratch_.resize(std::size_t(options.modes));
  return out;
}

ModalWireLoads WireDynamics::LoadsOf(const Wire& wire, const SpineLoads& loads) const {
  ModalWireLoads out;
  out.start_displacement = loads.start_displacement;
  out.end_displacement = loads.end_displacement;
  out.tip_force = IsCantilever(wire.model.basis.boundary) ? loads.tip_force : Vec3::Zero();
  out.tip_couple = wire.model.basis.boundary == BoundaryCondition::kCantileverFree
                       ? loads.tip_couple
                       : Vec3::Zero();
  out.point_loads = loads.bending_point_loads;
  out.line_loads = loads.bending_line_loads;
  out.support_acceleration = wire.support_acceleration;
  out.support_angular_velocity = wire.support_angular_velocity;
  out.support_angular_acceleration = wire.support_angular_acceleration;
  return out;
}

Status WireDynamics::Reset(const ClipSample& sample) {
  for (std::size_t w = 0; w < wires_.size(); ++w) {
    wires_[w].support_acceleration = Vec3::Zero();
    wires_[w].support_angular_velocity = Vec3::Zero();
    wires_[w].support_angular_acceleration = Vec3::Zero();
    const ModalWireLoads loads = LoadsOf(wires_[w], sample.poses[wires_[w].part].loads);
    if (Status s = InitializeModalWireAtStatic(wires_[w].model, loads, &states_[w]); !s) return s;
  }
  return Status::Ok();
}

Status WireDynamics::Step(const ClipSample& sample, std::span<const Vec3> support_acceleration,
                          std::span<const Vec3> support_angular_velocity,
                          std::span<const Vec3> support_angular_acceleration,
                          std::span<const Mat3> support_rotation, double dt) {
  // A sliver of a step (landing on a frame time within 1 ns) leaves the wires as they are.
  if (dt < ModalWireStepJob::kMinTimeStep) return Status::Ok();
  for (std::size_t w = 0; w < wires_.size(); ++w) {
    Wire& wire = wires_[w];
    const PartModel& part = model_->parts[wire.part];
    // The support's acceleration in the wire's local axes (those of its middle sample, as
    // world-axes line loads are turned).
    const Frame& f = part.spine_frames[part.spine_frames.size() / 2];
    const Mat3 to_rest = support_rotation[wire.part].transpose();
    const Vec3 a = to_rest * support_acceleration[wire.part];
    wire.support_acceleration = Vec3(a.dot(f.normal), a.dot(f.binormal), 0.0);
    // Angular vectors in the right-handed (normal, binormal, tangent) axes, tangent = local z.
    const auto local = [&f](const Vec3& x) {
      return Vec3(x.dot(f.normal), x.dot(f.binormal), x.dot(f.tangent));
    };
    wire.support_angular_velocity = local(to_rest * support_angular_velocity[wire.part]);
    wire.support_angular_acceleration = local(to_rest * support_angular_acceleration[wire.part]);
    ModalWireStepJob step;
    step.model = &wire.model;
    step.loads = LoadsOf(wire, sample.poses[wire.part].loads);
    step.dt = dt;
    step.step_table = dt == wire.table.dt ? &wire.table : nullptr;  // whole steps
    step.state = &states_[w];
    if (Status s = step.Run(); !s) return s;
  }
  return Status::Ok();
}

Status WireDynamics::Apply(std::span<PartPose> poses, std::span<const double> residual_scale) {
  for (std::size_t w = 0; w < wires_.size(); ++w) {
    Wire& wire = wires_[w];
    const ModalWireState& state = states_[w];
    const double scale = residual_scale.empty() ? 1.0 : residual_scale[wire.part];
    // Beyond the clip's loads (the rig's own closed form): the modal residual and the
    // support's inertial loads, the uniform one of its acceleration and the linear one of its
    // turning, from zero at the support to -rho A L r_support at the far end.
    ModalResidual& r = residuals_[w];
    r.modes = wire.model.basis.modes;
    for (int m = 0; m < r.modes; ++m) r.coordinates[m] = scale * (state.q[m] - state.q_static[m]);
    const double rho_a = wire.model.mass_per_length;
    r.uniform_load = -scale * rho_a * wire.support_acceleration;
    r.turning_load = -scale * rho_a * wire.model.length *
                     TurningAccelerationPerLength(wire.support_angular_velocity,
                                                  wire.support_angular_acceleration);
    SpineLoads& loads = poses[wire.part].loads;
    ModalResidualJob job;
    job.boundary = loads.boundary;
    job.length = wire.model.length;
    job.bending_stiffness = wire.model.bending_stiffness;
    job.residual = &r;
    job.samples = wire.samples;
    job.mode_values = wire.mode_values;
    job.mode_slopes = wire.mode_slopes;
    job.displacement = wire.extra_displacement;
    job.slope = wire.extra_slope;
    if (Status s = job.Run(); !s) return s;
    loads.extra_displacement = wire.extra_displacement;
    loads.extra_slope = wire.extra_slope;
  }
  return Status::Ok();
}

void WireDynamics::Restore(std::span<const ModalWireState> states) {
  std::copy(states.begin(), states.end(), states_.begin());
}

}  // namespace wirerig
