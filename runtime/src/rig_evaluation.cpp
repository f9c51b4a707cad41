#include "wirerig/runtime/rig_evaluation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "spine_curl.h"
#include "vertex_stage.h"
#include "wirerig/runtime/spine_interpolation.h"

namespace wirerig {
namespace {

Frame RotateFrame(const Mat3& r, const Frame& f) {
  return {r * f.tangent, r * f.normal, r * f.binormal};
}

// The rotation a spine's frame at v has turned by (rest world axes -> world), and its point.
Mat3 SpineTurn(const PartModel& part, const RigWorkspace& w, std::size_t i, double v,
               Vec3* rest_point, Vec3* point, Vec3* rest_tangent, Vec3* tangent) {
  const Frame rest = InterpolateSpine(part.spine_points, part.spine_frames, v, rest_point);
  const Frame moved = InterpolateSpine(w.spine_points[i], w.spine_frames[i], v, point);
  if (rest_tangent) *rest_tangent = rest.tangent;
  if (tangent) *tangent = moved.tangent;
  return FrameAxes(moved) * FrameAxes(rest).transpose();
}

// How part i's flesh at spine coordinate v in [0, 1] is strained: stretched along the spine by
// 1 + axial strain (a deformable part's; else 1) and, with preserve_volume, scaled across it by
// 1 / sqrt(stretch) (its volume kept; else 1).
struct SectionStrain {
  double stretch = 1.0, scale = 1.0;
};
SectionStrain SectionStrainAt(const RigModel& model, const RigWorkspace& w, std::size_t i, double v,
                              bool preserve_volume) {
  if (model.parts[i].kind != SpineKind::kDeformable) return {};
  const std::vector<double>& strain = w.strain[i];
  const double x = std::clamp(v, 0.0, 1.0) * double(strain.size() - 1);
  const std::size_t k = std::min(static_cast<std::size_t>(x), strain.size() - 2);
  const double f = x - double(k);
  const double stretch = std::max(1.0 + (1.0 - f) * strain[k] + f * strain[k + 1], 1e-6);
  return {stretch, preserve_volume ? 1.0 / std::sqrt(stretch) : 1.0};
}

// Each bridged joint's skin bridge for this frame, and the spine samples' undo matrices the
// vertices on bridges go back to rest space through (their turn, stretch and scale undone).
void SampleBridges(const RigModel& model, RigWorkspace& w, bool preserve_volume) {
  const RigEvaluationLayout& layout = w.plan->layout;
  if (layout.joint_vertices.empty()) return;
  for (std::uint32_t c : layout.bridged_parts) {
    const PartModel& child = model.parts[c];
    const PartModel& parent = model.parts[child.parent];
    const double h = child.joint.blend_length;
    Vec3 unused;
    const Mat3 parent_turn =
        SpineTurn(parent, w, child.parent, child.attachment, &unused, &unused, nullptr, nullptr);
    BridgeEnds posed;
    const double end_v = std::min(h / std::max(child.spine_length, 1e-12), 1.0);
    Vec3 rest_end, rest_end_tangent;
    const Mat3 child_turn =
        SpineTurn(child, w, c, end_v, &rest_end, &posed.end, &rest_end_tangent, &posed.end_tangent);
    // The flesh at the parent's end: a skinless parent's (a clavicle's) skinned ancestor's,
    // where the bone hangs from it.
    std::size_t flesh = std::size_t(child.parent);
    double flesh_v = child.attachment;
    while (model.parts[flesh].parent >= 0 && IsSkinless(model.parts[flesh])) {
      flesh_v = model.parts[flesh].attachment;
      flesh = std::size_t(model.parts[flesh].parent);
    }
    const SectionStrain parent_strain = SectionStrainAt(model, w, flesh, flesh_v, preserve_volume);
    // A skinless child (the clavicle) carries its ancestor's flesh as it is at the bone's root.
    const SectionStrain child_strain = IsSkinless(child)
                                           ? SectionStrain{1.0, parent_strain.scale}
                                           : SectionStrainAt(model, w, c, end_v, preserve_volume);
    posed.start_tangent = parent_turn * child.joint.parent_axis;
    posed.start = w.spine_points[c].front() - h * posed.start_tangent;
    posed.start_scale = parent_strain.scale;
    posed.end_stretch = child_strain.stretch, posed.end_scale = child_strain.scale;
    SampleJointBridge(child.joint, w.plan->rest_bridges[c], posed, parent_turn, child_turn,
                      &w.bridges[c]);
  }
  for (const auto& [part, sample] : layout.undo_samples) {
    const double v = double(sample) / double(model.parts[part].spine_points.size() - 1);
    const SectionStrain strain = SectionStrainAt(model, w, part, v, preserve_volume);
    w.spine_undo[part][sample] =
        FrameAxes(model.parts[part].spine_frames[sample]) *
        Vec3(1.0 / strain.scale, 1.0 / strain.scale, 1.0 / strain.stretch).asDiagonal() *
        FrameAxes(w.spine_frames[part][sample]).transpose();
  }
}

Status ValidateLoads(const SpineLoads& loads, std::size_t samples) {
  for (const PointLoad& p : loads.bending_point_loads)
    if (!(std::isfinite(p.at) && std::isfinite(p.force.x()) && std::isfinite(p.force.y())))
      return Status::Invalid("poses", "spine bending loads must be finite");
  for (const std::span<const Vec3> extra : {loads.extra_displacement, loads.extra_slope}) {
    if (!extra.empty() && extra.size() != samples)
      return Status::Invalid("poses", "extra spine bending must be empty or one per spine sample");
    for (const Vec3& x : extra)
      if (!x.allFinite()) return Status::Invalid("poses", "extra spine bending must be finite");
  }
  return Status::Ok();
}

}  // namespace

std::shared_ptr<const RigEvaluationPlan> MakeRigEvaluationPlan(const RigModel& model) {
  auto plan = std::make_shared<RigEvaluationPlan>();
  plan->parts = model.parts.size();
  plan->vertices = model.vertices.size();
  plan->triangles = model.triangles.size();
  RigEvaluationLayout& layout = plan->layout;
  std::uint32_t profiles = 0, points = 0;  // global profiles, wire points
  for (const PartModel& part : model.parts) {
    layout.profile_base.push_back(profiles);
    for (const ProfileModel& profile : part.profiles) {
      layout.point_base.push_back(points);
      points += static_cast<std::uint32_t>(profile.local_points.size());
      ++profiles;
    }
  }
  using JointBase = RigEvaluationLayout::JointBase;
  auto base_of = [&](std::uint32_t part, std::int32_t joint) {
    if (std::int32_t(part) == joint) return JointBase::kOwn;
    return IsBelowPart(model, part, std::size_t(joint)) ? JointBase::kChild : JointBase::kParent;
  };
  for (std::size_t v = 0; v < model.vertices.size(); ++v)
    for (const JointInfluence& j : model.vertices[v].joints)
      if (j.joint >= 0)
        layout.joint_vertices.push_back({static_cast<std::uint32_t>(v),
                                         static_cast<std::uint32_t>(j.joint),
                                         model.vertices[v].part, j.sample, j.u, j.weight, j.bridge,
                                         j.section, base_of(model.vertices[v].part, j.joint)});
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const PartModel& part = model.parts[i];
    if (part.parent >= 0 && part.joint.blend_length > 0.0)
      layout.bridged_parts.push_back(static_cast<std::uint32_t>(i));
  }
  // The spine samples the entries undo through.
  for (const RigEvaluationLayout::JointVertex& j : layout.joint_vertices)
    layout.undo_samples.emplace_back(j.part, j.sample);
  std::sort(layout.undo_samples.begin(), layout.undo_samples.end());
  layout.undo_samples.erase(std::unique(layout.undo_samples.begin(), layout.undo_samples.end()),
                            layout.undo_samples.end());
  plan->rest_bridges.resize(model.parts.size());
  for (std::uint32_t c : layout.bridged_parts)
    plan->rest_bridges[c] = MakeRestBridge(RestBridgeEnds(model.parts[c]));
  MakeVertexStagePlan(model, layout, &plan->stage64);
  MakeVertexStagePlan(model, layout, &plan->stage32);
  return plan;
}

RigWorkspace MakeRigWorkspace(const RigModel& model) {
  return MakeRigWorkspace(model, MakeRigEvaluationPlan(model));
}

RigWorkspace MakeRigWorkspace(const RigModel& model,
                              std::shared_ptr<const RigEvaluationPlan> plan) {
  RigWorkspace w;
  w.plan = std::move(plan);
  std::size_t longest = 2;
  for (const PartModel& part : model.parts) {
    w.strain.emplace_back(part.spine_points.size(), 0.0);
    w.profile_scale.emplace_back(part.profiles.size(), 1.0);
    w.spine_points.emplace_back(part.spine_points.size());
    w.spine_frames.emplace_back(part.spine_frames.size());
    std::vector<std::vector<Vec3>> profiles;
    for (const ProfileModel& profile : part.profiles)
      profiles.emplace_back(profile.local_points.size());
    w.profile_points.push_back(std::move(profiles));
    w.profile_origins.emplace_back(part.profiles.size());
    w.profile_normals.emplace_back(part.profiles.size());
    longest = std::max(longest, part.spine_points.size());
  }
  w.samples.resize(longest);
  w.bending.resize(longest);
  w.slope.resize(longest);
  w.axial.resize(longest);
  w.curl_points.resize(longest);
  w.curl_tangents.resize(longest);
  w.spine_turns.resize(longest);
  std::size_t widest = 1;
  for (const PartModel& part : model.parts)
    for (const ProfileModel& profile : part.profiles)
      widest = std::max(widest, profile.local_points.size());
  w.profile_samples.resize(widest + 1);
  w.profile_displacement.resize(widest + 1);
  w.cap_axes.resize(w.plan->layout.point_base.size(), Mat3::Identity());
  w.bridges.resize(model.parts.size());
  for (const PartModel& part : model.parts)
    w.spine_undo.emplace_back(part.spine_points.size(), Mat3::Identity());
  MakeVertexStage(model, w.plan->layout, w.plan->stage64, &w.stage64);
  MakeVertexStage(model, w.plan->layout, w.plan->stage32, &w.stage32);
  return w;
}

BridgeEnds RestBridgeEnds(const PartModel& child) {
  const double h = child.joint.blend_length;
  BridgeEnds rest;
  const double end_v = std::min(h / std::max(child.spine_length, 1e-12), 1.0);
  rest.end_tangent =
      InterpolateSpine(child.spine_points, child.spine_frames, end_v, &rest.end).tangent;
  rest.start_tangent = child.joint.parent_axis;
  rest.start = child.spine_points.front() - h * rest.start_tangent;
  return rest;
}

RigidBodyState RestRigidBodyState(const PartModel& part) {
  RigidBodyState state;
  state.position = part.mass.center;
  state.orientation = Quat(part.mass.principal_axes);
  return state;
}

PartPose PoseFromRigidBody(const PartModel& part, const RigidBodyState& state) {
  PartPose pose;
  const Quat rest(part.mass.principal_axes);
  pose.rotation = (state.orientation * rest.conjugate()).normalized();
  // x_c = root + R (c0 - root) + t  =>  t = x_c - root - R (c0 - root)
  const Vec3 root = part.spine_points.front();
  pose.translation = state.position - root - pose.rotation * (part.mass.center - root);
  return pose;
}

Status EvaluateRigJob::Validate() const {
  if (!model) return Status::Invalid("model", "is required");
  if (!workspace) return Status::Invalid("workspace", "is required");
  if (poses.size() != model->parts.size())
    return Status::Invalid("poses", "needs one pose per part");
  const std::size_t vertex_count = model->vertices.size();
  const bool doubles = !positions.empty();
  if (doubles == !float_positions.empty())
    return Status::Invalid("positions", "give either positions or float_positions");
  if (doubles) {
    if (positions.size() != vertex_count)
      return Status::Invalid("positions", "needs one element per vertex");
    if (!normals.empty() && normals.size() != vertex_count)
      return Status::Invalid("normals", "must be empty or have one element per vertex");
    if (!float_normals.empty())
      return Status::Invalid("float_normals", "go with float_positions, not positions");
    if (!float_vertex_order.empty())
      return Status::Invalid("float_vertex_order", "goes with float_positions, not positions");
  } else {
    // A strided buffer holds output vertex i's three floats at [i * stride, i * stride + 3).
    const std::size_t outputs =
        float_vertex_order.empty() ? vertex_count : float_vertex_order.size();
    // (outputs - 1) * stride + 3 <= size, without the product wrapping: a stride picked so
    // that it wrapped passed and the stage wrote far outside the buffer.
    auto fits = [&](std::span<float> buffer, std::size_t stride) {
      return stride >= 3 && buffer.size() >= 3 && (outputs - 1) <= (buffer.size() - 3) / stride;
    };
    for (const std::uint32_t w : float_vertex_order)
      if (w >= vertex_count)
        return Status::Invalid("float_vertex_order", "names a vertex the model does not have");
    if (outputs > 0 && !fits(float_positions, float_position_stride))
      return Status::Invalid("float_positions",
                             "needs a stride of at least 3 and room for every vertex");
    if (outputs > 0 && !float_normals.empty() && !fits(float_normals, float_normal_stride))
      return Status::Invalid(
          "float_normals",
          "must be empty, or have a stride of at least 3 and room for every vertex");
    if (!normals.empty())
      return Status::Invalid("normals", "go with positions, not float_positions");
  }
  if (!warnings.empty() && warnings.size() != model->parts.size())
    return Status::Invalid("warnings", "must be empty or have one element per part");
  if (!workspace->plan || workspace->plan->parts != model->parts.size() ||
      workspace->plan->vertices != vertex_count ||
      workspace->plan->triangles != model->triangles.size() ||
      workspace->spine_points.size() != model->parts.size())
    return Status::Invalid("workspace", "was made for another model");
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const PartPose& pose = poses[i];
    const Eigen::Vector4d q = pose.rotation.coeffs();
    if (!(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]) &&
          std::isfinite(q[3]) && std::abs(q.squaredNorm() - 1.0) < 1e-6))
      return Status::Invalid("poses", "rotations must be finite unit quaternions");
    // Bounded so that the float stage's squares stay finite (1e36 gave NaN positions).
    if (!(pose.translation.allFinite() &&
          pose.translation.cwiseAbs().maxCoeff() <= kMaxTranslation))
      return Status::Invalid("poses", "translations must be finite, within 1e6 m");
    if (Status s = ValidateLoads(pose.loads, model->parts[i].spine_points.size()); !s) return s;
  }
  for (const ProfileLoads& loads : profile_loads) {
    if (loads.part >= model->parts.size() ||
        loads.profile >= model->parts[loads.part].profiles.size())
      return Status::Invalid("profile_loads", "names a profile the model does not have");
    if (!(loads.from >= 0.0 && loads.to <= 1.0 && loads.from < loads.to))
      return Status::Invalid("profile_loads", "needs 0 <= from < to <= 1");
    if (!loads.extra_displacement.empty()) {
      const std::size_t points =
          model->parts[loads.part].profiles[loads.profile].local_points.size();
      if (loads.from != 0.0 || loads.to != 1.0 || loads.extra_displacement.size() != points)
        return Status::Invalid("profile_loads",
                               "extra_displacement needs the whole profile, one per point");
      for (const Vec3& x : loads.extra_displacement)
        if (!x.allFinite())
          return Status::Invalid("profile_loads", "extra_displacement must be finite");
    }
  }
  return Status::Ok();
}

Status EvaluateRigJob::Run() const {
  if (Status s = Validate(); !s) return s;
  RigWorkspace& w = *workspace;
  for (std::size_t i = 0; i < model->parts.size(); ++i) {
    const PartModel& part = model->parts[i];
    const PartPose& pose = poses[i];
    const std::size_t n = part.spine_points.size();
    std::span<Vec3> points(w.spine_points[i]);
    std::span<Frame> frames(w.spine_frames[i]);
    std::copy(part.spine_points.begin(), part.spine_points.end(), points.begin());

    // 1. Deformation in the spine's rest local frames.
    if (part.kind == SpineKind::kDeformable) {
      for (std::size_t k = 0; k < n; ++k) w.samples[k] = double(k) / double(n - 1);
      const std::span<const double> samples(w.samples.data(), n);
      BendingJob bending;
      bending.boundary = pose.loads.boundary;
      bending.length = part.spine_length;
      bending.bending_stiffness = part.spine_stiffness.bending;
      bending.tip_force = pose.loads.tip_force;
      bending.tip_couple = pose.loads.tip_couple;
      bending.start_displacement = pose.loads.start_displacement;
      bending.end_displacement = pose.loads.end_displacement;
      bending.point_loads = pose.loads.bending_point_loads;
      bending.line_loads = pose.loads.bending_line_loads;
      bending.samples = samples;
      bending.displacement = std::span<Vec3>(w.bending.data(), n);
      bending.slope = std::span<Vec3>(w.slope.data(), n);
      if (Status s = bending.Run(); !s) return Status::Invalid("poses", s.reason);
      for (std::size_t k = 0; k < pose.loads.extra_displacement.size(); ++k)
        w.bending[k] += pose.loads.extra_displacement[k];
      for (std::size_t k = 0; k < pose.loads.extra_slope.size(); ++k)
        w.slope[k] += pose.loads.extra_slope[k];
      AxialJob axial;
      axial.length = part.spine_length;
      axial.axial_stiffness = part.spine_stiffness.axial;
      axial.fixed_at = pose.loads.axial_fixed_at;
      axial.point_loads = pose.loads.axial_point_loads;
      axial.line_loads = pose.loads.axial_line_loads;
      axial.samples = samples;
      axial.displacement = std::span<double>(w.axial.data(), n);
      axial.normal_force = w.strain[i];
      if (Status s = axial.Run(); !s) return Status::Invalid("poses", s.reason);
      for (double& strain : w.strain[i]) strain /= part.spine_stiffness.axial;
      const std::span<Vec3> displacement(w.bending.data(), n);
      const std::span<Mat3> turns(w.spine_turns.data(), n);
      if (pose.loads.large_deflection) {
        const detail::SpineCurlScratch scratch{w.curl_points, w.curl_tangents};
        if (Status s =
                detail::CurlSpine(part.spine_length, part.spine_stiffness.bending, pose.loads,
                                  samples, w.slope, displacement, turns, scratch);
            !s)
          return s;
      } else {
        // Each frame turns minimally onto the exact deformed tangent (closed-form slope).
        for (std::size_t k = 0; k < n; ++k)
          turns[k] = Quat::FromTwoVectors(Vec3::UnitZ(),
                                          Vec3(w.slope[k].x(), w.slope[k].y(), 1.0).normalized())
                         .toRotationMatrix();
      }
      if (!warnings.empty()) {
        PartWarnings& warn = warnings[i];
        warn = PartWarnings{};
        for (std::size_t k = 0; k < n; ++k) {
          const Vec3 tangent = turns[k].col(2);
          warn.max_slope =
              std::max(warn.max_slope, std::atan2(tangent.head<2>().norm(), tangent.z()));
          warn.max_deflection_ratio = std::max(
              warn.max_deflection_ratio, displacement[k].head<2>().norm() / part.spine_length);
        }
        warn.beyond_small_deflection = !pose.loads.large_deflection &&
                                       (warn.max_slope > 0.3 || warn.max_deflection_ratio > 0.1);
      }
      for (std::size_t k = 0; k < n; ++k) {
        const Frame& f = part.spine_frames[k];
        const Mat3 axes = FrameAxes(f);
        points[k] += axes * (displacement[k] + w.axial[k] * Vec3::UnitZ());
        frames[k] = RotateFrame(axes * turns[k] * axes.transpose(), f);
      }
    } else {
      std::copy(part.spine_frames.begin(), part.spine_frames.end(), frames.begin());
      if (!warnings.empty()) warnings[i] = PartWarnings{};
    }

    // 2. The part's own rigid pose, about its rest root point.
    const Mat3 rotation = pose.rotation.toRotationMatrix();
    const Vec3 root = part.spine_points.front();
    for (std::size_t k = 0; k < n; ++k) {
      points[k] = root + rotation * (points[k] - root) + pose.translation;
      frames[k] = RotateFrame(rotation, frames[k]);
    }

    // 3. Follow the parent: its deformed frame at the attachment replaces its rest frame there.
    if (part.parent >= 0) {
      const PartModel& parent = model->parts[part.parent];
      Vec3 rest_origin, moved_origin;
      const Frame rest =
          InterpolateSpine(parent.spine_points, parent.spine_frames, part.attachment, &rest_origin);
      const Frame moved = InterpolateSpine(w.spine_points[part.parent], w.spine_frames[part.parent],
                                           part.attachment, &moved_origin);
      const Mat3 follow = FrameAxes(moved) * FrameAxes(rest).transpose();
      for (std::size_t k = 0; k < n; ++k) {
        points[k] = moved_origin + follow * (points[k] - rest_origin);
        frames[k] = RotateFrame(follow, frames[k]);
      }
    }

    // 4. Profiles ride on the spine frames (scaled in their plane to keep the volume).
    for (std::size_t p = 0; p < part.profiles.size(); ++p) {
      const ProfileModel& profile = part.profiles[p];
      Vec3 origin;
      const Frame frame = InterpolateSpine(points, frames, profile.spine_v, &origin);
      Mat3 axes = FrameAxes(frame);
      w.profile_scale[i][p] = 1.0;
      if (preserve_volume && part.kind == SpineKind::kDeformable) {
        const double scale = SectionStrainAt(*model, w, i, profile.spine_v, true).scale;
        w.profile_scale[i][p] = scale;
        axes.col(0) *= scale;
        axes.col(1) *= scale;
      }
      w.profile_origins[i][p] = origin;
      w.profile_normals[i][p] = frame.tangent;
      // The end caps' frame: in-plane like the profile, and 1/scale^2 along the tangent, so a
      // cap keeps its volume and meets the profile's plane continuously.
      const std::size_t g = w.plan->layout.profile_base[i] + p;
      w.cap_axes[g] = axes;
      w.cap_axes[g].col(2) /= w.profile_scale[i][p] * w.profile_scale[i][p];
      std::vector<Vec3>& out = w.profile_points[i][p];
      for (std::size_t q = 0; q < profile.local_points.size(); ++q)
        out[q] = origin + axes * profile.local_points[q];
    }
  }

  // 5. Profile wires bend under their own loads, in their spine frames.
  for (const ProfileLoads& loads : profile_loads) {
    const PartModel& part = model->parts[loads.part];
    const ProfileModel& profile = part.profiles[loads.profile];
    std::vector<Vec3>& points = w.profile_points[loads.part][loads.profile];
    const std::size_t m = profile.local_points.size();
    if (loads.point_loads.empty() && loads.line_loads.empty()) {
      // Motion alone (a profile wire's, over the whole profile): nothing to solve.
      if (loads.extra_displacement.empty()) continue;
      Vec3 origin;
      const Mat3 axes = FrameAxes(InterpolateSpine(
          w.spine_points[loads.part], w.spine_frames[loads.part], profile.spine_v, &origin));
      for (std::size_t q = 0; q < m; ++q) points[q] += axes * loads.extra_displacement[q];
      continue;
    }
    const double segments = double(profile.closed ? m : m - 1);
    // The stretch's points (and their parameter on the stretch) and its rest arc length.
    std::size_t count = 0;
    double length = 0.0;
    for (std::size_t q = 0; q <= (profile.closed ? m : m - 1); ++q) {
      const double u = double(q) / segments;
      if (q > 0 && u > loads.from && double(q - 1) / segments < loads.to)
        length += (profile.local_points[q % m] - profile.local_points[q - 1]).norm() *
                  (std::min(u, loads.to) - std::max(double(q - 1) / segments, loads.from)) *
                  segments;
      if (u >= loads.from && u <= loads.to && !(profile.closed && q == m && loads.from == 0.0))
        w.profile_samples[count++] = (u - loads.from) / (loads.to - loads.from);
    }
    if (count == 0 || !(length > 0.0)) continue;
    BendingJob bending;
    bending.boundary = loads.boundary;
    bending.length = length;
    bending.bending_stiffness = profile.stiffness.bending;
    bending.point_loads = loads.point_loads;
    bending.line_loads = loads.line_loads;
    bending.samples = std::span<const double>(w.profile_samples.data(), count);
    bending.displacement = std::span<Vec3>(w.profile_displacement.data(), count);
    if (Status s = bending.Run(); !s) return Status::Invalid("profile_loads", s.reason);
    Vec3 origin;
    const Mat3 axes = FrameAxes(InterpolateSpine(
        w.spine_points[loads.part], w.spine_frames[loads.part], profile.spine_v, &origin));
    // The whole profile (from 0 to 1) has its points in order as the stretch's samples.
    for (std::size_t q = 0; q < loads.extra_displacement.size(); ++q)
      w.profile_displacement[q] += loads.extra_displacement[q];
    std::size_t k = 0;
    for (std::size_t q = 0; q <= (profile.closed ? m : m - 1) && k < count; ++q) {
      const double u = double(q) / segments;
      if (u >= loads.from && u <= loads.to && !(profile.closed && q == m && loads.from == 0.0))
        points[q % m] += axes * w.profile_displacement[k++];
    }
  }

  // Warnings: tight bends (radius of curvature below the spine-to-surface distance) and
  // crossing adjacent profiles, on the final geometry.
  for (std::size_t i = 0; i < warnings.size(); ++i) {
    const PartModel& part = model->parts[i];
    const std::vector<Vec3>& points = w.spine_points[i];
    const std::vector<Frame>& frames = w.spine_frames[i];
    for (std::size_t k = 1; k < points.size(); ++k) {
      const double step = (points[k] - points[k - 1]).norm();
      const double turn =
          std::acos(std::clamp(frames[k].tangent.dot(frames[k - 1].tangent), -1.0, 1.0));
      if (turn * part.max_radius > step) ++warnings[i].tight_bends;
    }
    for (std::size_t p = 0; p + 1 < part.profiles.size(); ++p) {
      warnings[i].crossing_profiles += ProfilesCross(
          w.profile_points[i][p], w.profile_origins[i][p], w.profile_normals[i][p],
          w.profile_points[i][p + 1], w.profile_origins[i][p + 1], w.profile_normals[i][p + 1]);
    }
  }

  // 6-8. Vertices follow the profiles, then the skin bridges near joints; normals.
  SampleBridges(*model, w, preserve_volume);
  if (!positions.empty()) {
    StageOutput<double> out{positions.data()->data(), 3,
                            normals.empty() ? nullptr : normals.data()->data(), 3};
    out.normal_mode = normal_mode;
    RunVertexStage(*model, w, w.stage64, out, parallel);
  } else {
    const StageOutput<float> out{float_positions.data(),
                                 float_position_stride,
                                 float_normals.empty() ? nullptr : float_normals.data(),
                                 float_normal_stride,
                                 float_vertex_order.empty() ? nullptr : float_vertex_order.data(),
                                 float_vertex_order.size(),
                                 allow_avx2,
                                 normal_mode};
    RunVertexStage(*model, w, w.stage32, out, parallel);
  }
  return Status::Ok();
}

}  // namespace wirerig
