#include "wirerig/runtime/rig_evaluation.h"

#include <algorithm>
#include <cmath>

#include "wirerig/runtime/spine_interpolation.h"

namespace wirerig {
namespace {

Frame RotateFrame(const Mat3& r, const Frame& f) {
  return {r * f.tangent, r * f.normal, r * f.binormal};
}

Status ValidateLoads(const SpineLoads& loads) {
  for (const PointLoad& p : loads.bending_point_loads)
    if (!(std::isfinite(p.at) && std::isfinite(p.force.x()) && std::isfinite(p.force.y())))
      return Status::Invalid("poses", "spine bending loads must be finite");
  return Status::Ok();
}

}  // namespace

RigWorkspace MakeRigWorkspace(const RigModel& model) {
  RigWorkspace w;
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
  w.normal_accumulator.resize(model.vertices.size());
  std::size_t widest = 1;
  for (const PartModel& part : model.parts)
    for (const ProfileModel& profile : part.profiles)
      widest = std::max(widest, profile.local_points.size());
  w.profile_samples.resize(widest + 1);
  w.profile_displacement.resize(widest + 1);
  return w;
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
  if (positions.size() != model->vertices.size())
    return Status::Invalid("positions", "needs one element per vertex");
  if (!warnings.empty() && warnings.size() != model->parts.size())
    return Status::Invalid("warnings", "must be empty or have one element per part");
  if (!normals.empty() && normals.size() != model->vertices.size())
    return Status::Invalid("normals", "must be empty or have one element per vertex");
  if (workspace->spine_points.size() != model->parts.size() ||
      workspace->normal_accumulator.size() != model->vertices.size())
    return Status::Invalid("workspace", "was made for another model");
  for (const PartPose& pose : poses) {
    const Eigen::Vector4d q = pose.rotation.coeffs();
    if (!(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]) &&
          std::isfinite(q[3]) && std::abs(q.squaredNorm() - 1.0) < 1e-6))
      return Status::Invalid("poses", "rotations must be finite unit quaternions");
    if (!(std::isfinite(pose.translation.x()) && std::isfinite(pose.translation.y()) &&
          std::isfinite(pose.translation.z())))
      return Status::Invalid("poses", "translations must be finite");
    if (Status s = ValidateLoads(pose.loads); !s) return s;
  }
  for (const ProfileLoads& loads : profile_loads) {
    if (loads.part >= model->parts.size() ||
        loads.profile >= model->parts[loads.part].profiles.size())
      return Status::Invalid("profile_loads", "names a profile the model does not have");
    if (!(loads.from >= 0.0 && loads.to <= 1.0 && loads.from < loads.to))
      return Status::Invalid("profile_loads", "needs 0 <= from < to <= 1");
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
      bending.start_displacement = pose.loads.start_displacement;
      bending.end_displacement = pose.loads.end_displacement;
      bending.point_loads = pose.loads.bending_point_loads;
      bending.line_loads = pose.loads.bending_line_loads;
      bending.samples = samples;
      bending.displacement = std::span<Vec3>(w.bending.data(), n);
      bending.slope = std::span<Vec3>(w.slope.data(), n);
      if (Status s = bending.Run(); !s) return Status::Invalid("poses", s.reason);
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
      if (!warnings.empty()) {
        PartWarnings& warn = warnings[i];
        warn = PartWarnings{};
        for (std::size_t k = 0; k < n; ++k) {
          warn.max_slope = std::max(warn.max_slope, std::atan(w.slope[k].head<2>().norm()));
          warn.max_deflection_ratio = std::max(warn.max_deflection_ratio,
                                               w.bending[k].head<2>().norm() / part.spine_length);
        }
        warn.beyond_small_deflection = warn.max_slope > 0.3 || warn.max_deflection_ratio > 0.1;
      }
      // Each frame turns minimally onto the exact deformed tangent (closed-form slope).
      for (std::size_t k = 0; k < n; ++k) {
        const Frame& f = part.spine_frames[k];
        points[k] +=
            w.bending[k].x() * f.normal + w.bending[k].y() * f.binormal + w.axial[k] * f.tangent;
        const Vec3 tangent =
            (f.tangent + w.slope[k].x() * f.normal + w.slope[k].y() * f.binormal).normalized();
        frames[k] = RotateFrame(Quat::FromTwoVectors(f.tangent, tangent).toRotationMatrix(), f);
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
        const double x = profile.spine_v * double(n - 1);
        const std::size_t k = std::min(static_cast<std::size_t>(x), n - 2);
        const double f = x - double(k);
        const double strain = (1.0 - f) * w.strain[i][k] + f * w.strain[i][k + 1];
        const double scale = 1.0 / std::sqrt(std::max(1.0 + strain, 1e-6));
        w.profile_scale[i][p] = scale;
        axes.col(0) *= scale;
        axes.col(1) *= scale;
      }
      w.profile_origins[i][p] = origin;
      w.profile_normals[i][p] = frame.tangent;
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

  // 6. Vertices follow the profiles.
  for (std::size_t v = 0; v < model->vertices.size(); ++v) {
    const VertexAttachment& a = model->vertices[v];
    const PartModel& part = model->parts[a.part];
    if (a.cap) {
      Vec3 origin;
      const Frame frame = InterpolateSpine(w.spine_points[a.part], w.spine_frames[a.part],
                                           part.profiles[a.profile].spine_v, &origin);
      Mat3 axes = FrameAxes(frame);
      // In-plane like its end profile, and 1/scale^2 along the tangent: the cap keeps its
      // volume and meets the profile's plane continuously.
      const double scale = w.profile_scale[a.part][a.profile];
      axes.col(0) *= scale;
      axes.col(1) *= scale;
      axes.col(2) /= scale * scale;
      positions[v] = origin + axes * a.cap_local;
      continue;
    }
    const WirePolyline wire_i{w.profile_points[a.part][a.profile], part.profiles[a.profile].closed};
    const WirePolyline wire_j{w.profile_points[a.part][a.profile + 1],
                              part.profiles[a.profile + 1].closed};
    positions[v] = ApplyPairBinding(a.pair, wire_i, wire_j, w.profile_origins[a.part][a.profile],
                                    w.profile_origins[a.part][a.profile + 1]);
  }

  // 7. Area-weighted vertex normals.
  if (normals.empty()) return Status::Ok();
  std::fill(w.normal_accumulator.begin(), w.normal_accumulator.end(), Vec3::Zero());
  for (const Triangle& t : model->triangles) {
    const Vec3 n = (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
    for (std::uint32_t index : t) w.normal_accumulator[index] += n;
  }
  for (std::size_t v = 0; v < normals.size(); ++v) {
    const double length = w.normal_accumulator[v].norm();
    normals[v] = length > 0.0 ? Vec3(w.normal_accumulator[v] / length) : Vec3::UnitY();
  }
  return Status::Ok();
}

}  // namespace wirerig
