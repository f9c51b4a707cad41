#include "wirerig/anim/clip_asset_export.h"

#include <cmath>
#include <cstdio>

#include "wirerig/anim/bake.h"

namespace wirerig {
namespace {

template <class Load>
LoadRange Append(std::span<const Load> loads, std::vector<Load>* all) {
  const LoadRange range{std::uint32_t(all->size()), std::uint32_t(loads.size())};
  all->insert(all->end(), loads.begin(), loads.end());
  return range;
}

ClipLoop LoopOf(LoopMode mode) {
  switch (mode) {
    case LoopMode::kLoop:
      return ClipLoop::kLoop;
    case LoopMode::kPingPong:
      return ClipLoop::kPingPong;
    case LoopMode::kOnce:
      break;
  }
  return ClipLoop::kOnce;
}

}  // namespace

Result<SampledClip> SampleClipForRuntime(const RigModel& model, const Clip& clip,
                                         const PlaybackOptions& playback, double fps,
                                         std::vector<std::string>* warnings) {
  if (!(std::isfinite(fps) && fps > 0.0 && fps <= 1000.0))
    return Error{"fps: must lie in (0, 1000]"};
  if (!(clip.duration > 0.0)) return Error{"clip \"" + clip.name + "\": has no duration to sample"};
  // The work and the asset's size first: every frame is a full evaluation (a 1e5 s clip ran
  // for minutes toward a 0.7 GB file).
  if (const double frames = std::ceil(clip.duration * fps - 1e-9) + 1.0;
      !(frames <= kMaxClipAssetFrames)) {
    char message[300];
    std::snprintf(message, sizeof message,
                  "clip \"%s\": %s frames (%g s at %g frames/s), more than a clip asset may hold "
                  "(%.0f); sample fewer frames per second or a shorter clip",
                  clip.name.c_str(), KeyCountText(frames).c_str(), clip.duration, fps,
                  kMaxClipAssetFrames);
    return Error{message};
  }
  Result<Playback> made = Playback::Make(model, clip, playback);
  if (!made) return Error{made.error()};
  Playback& player = made.value();
  SampledClip out;
  out.name = clip.name;
  out.duration = clip.duration;
  out.frame_rate = fps;
  out.loop = LoopOf(clip.loop);
  out.part_count = std::uint32_t(model.parts.size());
  const WireDynamics& wires = player.wires();
  for (std::size_t w = 0; w < wires.size(); ++w) {
    const ModalWireModel& m = wires.model(w);
    out.wires.push_back({std::uint32_t(wires.part(w)), m.basis.boundary,
                         std::uint32_t(m.basis.modes),
                         std::uint32_t(model.parts[wires.part(w)].spine_points.size()), m.length,
                         m.bending_stiffness});
  }
  const ProfileDynamics& profile_wires = player.profile_wires();
  for (std::size_t w = 0; w < profile_wires.size(); ++w)
    out.profile_wires.push_back(profile_wires.Recorded(w));
  const auto frames = std::size_t(std::ceil(clip.duration * fps - 1e-9)) + 1;
  std::vector<Vec3> positions(model.vertices.size());
  std::vector<PartWarnings> frame(model.parts.size());
  std::vector<std::pair<PartWarnings, double>> worst(model.parts.size());  // (worst, its time)
  for (std::size_t k = 0; k < frames; ++k) {
    // Clip-local time: a loop's last frame is its end, not its wrap back to the start.
    const double t = std::min(double(k) / fps, clip.duration);
    if (Status s = player.Evaluate(t, positions, {}, frame); !s)
      return Error{"clip \"" + clip.name + "\" at " + std::to_string(t) + " s: " + ToString(s)};
    for (std::size_t p = 0; p < frame.size(); ++p)
      if (frame[p].max_deflection_ratio > worst[p].first.max_deflection_ratio)
        worst[p] = {frame[p], t};
    for (const PartPose& pose : player.sample().poses) {
      PartKey key;
      key.rotation = pose.rotation;
      key.translation = pose.translation;
      const SpineLoads& loads = pose.loads;
      key.boundary = loads.boundary;
      key.tip_force = loads.tip_force;
      key.tip_couple = loads.tip_couple;
      key.large_deflection = loads.large_deflection;
      key.curl_segments = std::uint32_t(loads.curl_segments);
      key.start_displacement = loads.start_displacement;
      key.end_displacement = loads.end_displacement;
      key.axial_fixed_at = loads.axial_fixed_at;
      key.point_loads = Append(loads.bending_point_loads, &out.point_loads);
      key.line_loads = Append(loads.bending_line_loads, &out.line_loads);
      key.axial_point_loads = Append(loads.axial_point_loads, &out.axial_point_loads);
      key.axial_line_loads = Append(loads.axial_line_loads, &out.axial_line_loads);
      out.parts.push_back(key);
    }
    const std::span<const ProfileLoads> profiles = player.sample().profile_loads;
    out.profile_keys_of_frame.push_back(
        {std::uint32_t(out.profile_keys.size()), std::uint32_t(profiles.size())});
    for (const ProfileLoads& p : profiles) {
      ProfileKey key{p.part, p.profile, p.from, p.to, p.boundary, {}, {}};
      key.point_loads = Append(p.point_loads, &out.point_loads);
      key.line_loads = Append(p.line_loads, &out.line_loads);
      out.profile_keys.push_back(key);
    }
    for (const ModalResidual& r : wires.residuals()) {
      out.wire_motion.insert(out.wire_motion.end(), r.coordinates.begin(),
                             r.coordinates.begin() + r.modes);
      out.wire_motion.push_back(r.uniform_load);
      out.wire_motion.push_back(r.turning_load);
    }
    for (const ModalResidual& r : profile_wires.residuals()) {
      out.profile_wire_motion.insert(out.profile_wire_motion.end(), r.coordinates.begin(),
                                     r.coordinates.begin() + r.modes);
      out.profile_wire_motion.push_back(r.uniform_load);
    }
  }
  if (Status s = ValidateSampledClip(out, &model); !s)
    return Error{"clip \"" + clip.name + "\": " + ToString(s)};
  for (std::size_t p = 0; warnings != nullptr && p < worst.size(); ++p)
    if (std::string w = DeflectionWarning(model.parts[p], worst[p].first, worst[p].second);
        !w.empty())
      warnings->push_back("clip \"" + clip.name + "\": " + w);
  return out;
}

}  // namespace wirerig
