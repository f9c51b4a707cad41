#include "wirerig/anim/clip_sampling.h"

#include "wirerig/runtime/spine_interpolation.h"

#include <algorithm>
#include <cmath>

namespace wirerig {
namespace {

double Clamp01(double v) { return std::clamp(v, 0.0, 1.0); }

// The rest frame a world-axes load at v turns into: the spine's frame at v (interpolated as the
// evaluation interpolates it), or for a profile wire (spine == nullptr) its own spine frame.
struct LoadFrames {
  const PartModel* spine = nullptr;
  Frame profile;
  Vec3 ToLocal(const Vec3& world, double v) const {
    Vec3 origin;
    const Frame f =
        spine ? InterpolateSpine(spine->spine_points, spine->spine_frames, v, &origin) : profile;
    return {world.dot(f.normal), world.dot(f.binormal), world.dot(f.tangent)};
  }
};

std::size_t SamplePointLoads(const std::vector<PointLoadChannels<Track>>& channels, double t,
                             const LoadFrames& frames, std::vector<PointLoad>& out) {
  std::size_t n = 0;
  for (const auto& c : channels) {
    const Vec3 direction = c.direction.Sample(t);
    const double length = direction.norm();
    const double magnitude = c.magnitude.Sample(t);
    if (!(length > 1e-12) || magnitude == 0.0) continue;
    const double at = Clamp01(c.at.Sample(t));
    const Vec3 force = direction * (magnitude / length);
    out[n++] = {at, c.axes == LoadAxes::kWorld ? frames.ToLocal(force, at) : force};
  }
  return n;
}

std::size_t SampleLineLoads(const std::vector<LineLoadChannels<Track>>& channels, double t,
                            const LoadFrames& frames, std::vector<LineLoad>& out) {
  std::size_t n = 0;
  for (const auto& c : channels) {
    const double from = c.from.IsEmpty() ? 0.0 : Clamp01(c.from.Sample(t));
    const double to = c.to.IsEmpty() ? 1.0 : Clamp01(c.to.Sample(t));
    if (!(to > from)) continue;
    const Vec3 force = c.force_per_length.Sample(t);
    out[n++] = {from, to,
                c.axes == LoadAxes::kWorld ? frames.ToLocal(force, 0.5 * (from + to)) : force};
  }
  return n;
}

BoundaryCondition BoundaryAt(const std::vector<BoundaryKey>& keys, double t) {
  BoundaryCondition boundary = BoundaryCondition::kCantileverFree;
  for (const BoundaryKey& key : keys) {
    if (key.time > t) break;
    boundary = key.boundary;
  }
  return boundary;
}

// Every finite vector gives a unit quaternion: stableNorm scales before squaring, where norm()
// overflows to infinity past components of 1.3e154 (and the quaternion became NaN).
Quat FromAxisAngle(const Vec3& v) {
  const double angle = v.stableNorm();
  if (!(angle > 1e-15)) return Quat::Identity();
  return Quat(Eigen::AngleAxisd(angle, v / angle));
}

}  // namespace

ClipSample MakeClipSample(const Clip& clip, const RigModel& model) {
  ClipSample s;
  s.model = &model;
  const std::size_t parts = model.parts.size();
  s.poses.resize(parts);
  std::size_t profile_loads = 0;
  for (const Clip::ProfileGroup& group : clip.profiles)
    profile_loads += group.channels.profiles.size();
  s.point_loads.resize(parts + profile_loads);
  s.line_loads.resize(parts + profile_loads);
  s.axial_point_loads.resize(parts);
  s.axial_line_loads.resize(parts);
  for (std::size_t p = 0; p < parts && p < clip.parts.size(); ++p) {
    s.point_loads[p].resize(clip.parts[p].point_loads.size());
    s.line_loads[p].resize(clip.parts[p].line_loads.size());
    s.axial_point_loads[p].resize(clip.parts[p].axial_point_loads.size());
    s.axial_line_loads[p].resize(clip.parts[p].axial_line_loads.size());
  }
  std::size_t entry = parts;
  for (const Clip::ProfileGroup& group : clip.profiles) {
    for (std::size_t k = 0; k < group.channels.profiles.size(); ++k, ++entry) {
      s.point_loads[entry].resize(group.channels.point_loads.size());
      s.line_loads[entry].resize(group.channels.line_loads.size());
    }
  }
  s.profile_loads.resize(profile_loads);
  return s;
}

void SampleClip(const Clip& clip, double t, ClipSample* sample) {
  ClipSample& s = *sample;
  const std::size_t parts = s.poses.size();
  for (std::size_t p = 0; p < parts; ++p) {
    const PartChannels<Track>& c = clip.parts[p];
    PartPose& pose = s.poses[p];
    pose.rotation = FromAxisAngle(c.rotation.Sample(t));
    if (!c.joint_angles.IsEmpty())
      pose.rotation =
          (pose.rotation * JointRotation(s.model->parts[p].joint, c.joint_angles.Sample(t)))
              .normalized();
    pose.translation = c.translation.Sample(t);
    SpineLoads& loads = pose.loads;
    loads.boundary = BoundaryAt(c.boundary, t);
    const LoadFrames frames{&s.model->parts[p], {}};
    loads.bending_point_loads = std::span<const PointLoad>(
        s.point_loads[p].data(), SamplePointLoads(c.point_loads, t, frames, s.point_loads[p]));
    loads.bending_line_loads = std::span<const LineLoad>(
        s.line_loads[p].data(), SampleLineLoads(c.line_loads, t, frames, s.line_loads[p]));
    loads.tip_force = IsCantilever(loads.boundary) ? c.tip_force.Sample(t) : Vec3::Zero();
    loads.tip_couple = loads.boundary == BoundaryCondition::kCantileverFree ? c.tip_couple.Sample(t)
                                                                            : Vec3::Zero();
    loads.large_deflection = c.large_deflection;
    loads.curl_segments = 0;
    loads.start_displacement = c.start_displacement.Sample(t);
    loads.end_displacement = c.end_displacement.Sample(t);
    loads.axial_fixed_at = c.axial_fixed_at;
    std::vector<AxialPointLoad>& axial_points = s.axial_point_loads[p];
    for (std::size_t k = 0; k < axial_points.size(); ++k)
      axial_points[k] = {Clamp01(c.axial_point_loads[k].at.Sample(t)),
                         c.axial_point_loads[k].force.Sample(t)};
    loads.axial_point_loads = axial_points;
    std::vector<AxialLineLoad>& axial_lines = s.axial_line_loads[p];
    std::size_t n = 0;
    for (const AxialLineLoadChannels<Track>& a : c.axial_line_loads) {
      const double from = a.from.IsEmpty() ? 0.0 : Clamp01(a.from.Sample(t));
      const double to = a.to.IsEmpty() ? 1.0 : Clamp01(a.to.Sample(t));
      if (to > from) axial_lines[n++] = {from, to, a.force_per_length.Sample(t)};
    }
    loads.axial_line_loads = std::span<const AxialLineLoad>(axial_lines.data(), n);
  }
  std::size_t next = 0;
  for (std::size_t g = 0; g < clip.profiles.size(); ++g) {
    const Clip::ProfileGroup& group = clip.profiles[g];
    const PartModel& part = s.model->parts[group.part];
    for (std::uint32_t profile : group.channels.profiles) {
      // A profile's world-axes loads turn into its own spine frame (at its spine_v, as the
      // evaluation places it).
      Vec3 origin;
      const LoadFrames frames{nullptr, InterpolateSpine(part.spine_points, part.spine_frames,
                                                        part.profiles[profile].spine_v, &origin)};
      std::vector<PointLoad>& points = s.point_loads[parts + next];
      std::vector<LineLoad>& lines = s.line_loads[parts + next];
      const std::size_t point_count =
          SamplePointLoads(group.channels.point_loads, t, frames, points);
      const std::size_t line_count = SampleLineLoads(group.channels.line_loads, t, frames, lines);
      ProfileLoads& loads = s.profile_loads[next++];
      loads.part = group.part;
      loads.profile = profile;
      loads.from = group.channels.from;
      loads.to = group.channels.to;
      loads.boundary = group.channels.boundary;
      loads.point_loads = std::span<const PointLoad>(points.data(), point_count);
      loads.line_loads = std::span<const LineLoad>(lines.data(), line_count);
    }
  }
}

void ComposePlacements(const RigModel& model, std::span<const PartPose> poses,
                       std::span<Mat3> rotations, std::span<Vec3> translations) {
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Mat3 r = poses[p].rotation.toRotationMatrix();
    const Vec3& root = model.parts[p].spine_points.front();
    rotations[p] = r;
    translations[p] = root - r * root + poses[p].translation;
    if (const int parent = model.parts[p].parent; parent >= 0) {
      translations[p] =
          rotations[std::size_t(parent)] * translations[p] + translations[std::size_t(parent)];
      rotations[p] = rotations[std::size_t(parent)] * r;
    }
  }
}

}  // namespace wirerig
