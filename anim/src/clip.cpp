#include "wirerig/anim/clip.h"

#include "wirerig/io/name_hint.h"
#include "wirerig/runtime/clip_asset.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace wirerig {
namespace {

// Where a track sits, for messages: "parts[2].point_loads[0].magnitude".
std::string At(std::string prefix, std::string_view member) {
  return prefix.append(".").append(member);
}
std::string Indexed(std::string prefix, std::string_view member, std::size_t i) {
  return prefix.append(".").append(member).append("[").append(std::to_string(i)).append("]");
}

template <typename T>
std::string CheckTrack(const RawTrack<T>& raw, double duration, const std::string& where) {
  if (raw.keys.empty()) return {};  // absent: the default value
  if (std::string error = ValidateRawTrack(raw); !error.empty()) {
    return At(where, error);
  }
  for (std::size_t i = 0; i < raw.keys.size(); ++i) {
    if (raw.keys[i].time < 0.0 || raw.keys[i].time > duration) {
      std::string message = where;
      message.append(".keys[")
          .append(std::to_string(i))
          .append("].time: must lie within the clip, [0, duration]");
      return message;
    }
  }
  return {};
}

// Visits every track of raw channels with its place, in declaration order.
template <typename Visit>
void VisitLoads(const PointLoadChannels<RawTrack>& c, const std::string& where, Visit&& visit) {
  visit(c.at, At(where, "at"));
  visit(c.magnitude, At(where, "magnitude"));
  visit(c.direction, At(where, "direction"));
}
template <typename Visit>
void VisitLoads(const LineLoadChannels<RawTrack>& c, const std::string& where, Visit&& visit) {
  visit(c.from, At(where, "from"));
  visit(c.to, At(where, "to"));
  visit(c.force_per_length, At(where, "force_per_length"));
}
template <typename Visit>
void VisitLoads(const AxialPointLoadChannels<RawTrack>& c, const std::string& where,
                Visit&& visit) {
  visit(c.at, At(where, "at"));
  visit(c.force, At(where, "force"));
}
template <typename Visit>
void VisitLoads(const AxialLineLoadChannels<RawTrack>& c, const std::string& where, Visit&& visit) {
  visit(c.from, At(where, "from"));
  visit(c.to, At(where, "to"));
  visit(c.force_per_length, At(where, "force_per_length"));
}
template <typename Visit>
void VisitLoads(const RigidForceChannels<RawTrack>& c, const std::string& where, Visit&& visit) {
  visit(c.force, At(where, "force"));
}
template <typename List, typename Visit>
void VisitList(const List& list, const std::string& where, std::string_view member, Visit&& visit) {
  for (std::size_t i = 0; i < list.size(); ++i)
    VisitLoads(list[i], Indexed(where, member, i), visit);
}
template <typename Visit>
void VisitTracks(const PartChannels<RawTrack>& c, const std::string& where, Visit&& visit) {
  VisitList(c.point_loads, where, "point_loads", visit);
  VisitList(c.line_loads, where, "line_loads", visit);
  visit(c.tip_force, At(where, "tip_force"));
  visit(c.tip_couple, At(where, "tip_couple"));
  visit(c.reach.target, At(where, "reach/target"));
  visit(c.reach.weight, At(where, "reach/weight"));
  visit(c.start_displacement, At(where, "start_displacement"));
  visit(c.end_displacement, At(where, "end_displacement"));
  VisitList(c.axial_point_loads, where, "axial_point_loads", visit);
  VisitList(c.axial_line_loads, where, "axial_line_loads", visit);
  visit(c.rotation, At(where, "rotation"));
  visit(c.translation, At(where, "translation"));
  visit(c.joint_angles, At(where, "joint_angles"));
  VisitList(c.rigid_forces, where, "rigid_forces", visit);
  visit(c.rigid_torque, At(where, "rigid_torque"));
}
template <typename Visit>
void VisitTracks(const ProfileChannels<RawTrack>& c, const std::string& where, Visit&& visit) {
  VisitList(c.point_loads, where, "point_loads", visit);
  VisitList(c.line_loads, where, "line_loads", visit);
}

// Raw -> built, for tracks already validated: an absent track stays the empty default.
template <typename T>
Track<T> Built(const RawTrack<T>& raw) {
  return raw.keys.empty() ? Track<T>{} : BuildTrack(raw).value();
}
PointLoadChannels<Track> Built(const PointLoadChannels<RawTrack>& c) {
  return {Built(c.at), Built(c.magnitude), Built(c.direction), c.axes};
}
LineLoadChannels<Track> Built(const LineLoadChannels<RawTrack>& c) {
  return {Built(c.from), Built(c.to), Built(c.force_per_length), c.axes};
}
AxialPointLoadChannels<Track> Built(const AxialPointLoadChannels<RawTrack>& c) {
  return {Built(c.at), Built(c.force)};
}
AxialLineLoadChannels<Track> Built(const AxialLineLoadChannels<RawTrack>& c) {
  return {Built(c.from), Built(c.to), Built(c.force_per_length)};
}
RigidForceChannels<Track> Built(const RigidForceChannels<RawTrack>& c) {
  return {c.at, Built(c.force)};
}
template <typename In>
auto BuiltList(const std::vector<In>& list) {
  std::vector<decltype(Built(list.front()))> out;
  out.reserve(list.size());
  for (const In& item : list) out.push_back(Built(item));
  return out;
}
PartChannels<Track> Built(const PartChannels<RawTrack>& c) {
  PartChannels<Track> out;
  out.boundary = c.boundary;
  out.point_loads = BuiltList(c.point_loads);
  out.line_loads = BuiltList(c.line_loads);
  out.tip_force = Built(c.tip_force);
  out.tip_couple = Built(c.tip_couple);
  out.tip_couple_axes = c.tip_couple_axes;
  out.large_deflection = c.large_deflection;
  out.reach = {Built(c.reach.target), c.reach.parent_frame, Built(c.reach.weight),
               c.reach.max_force};
  out.start_displacement = Built(c.start_displacement);
  out.end_displacement = Built(c.end_displacement);
  out.axial_fixed_at = c.axial_fixed_at;
  out.axial_point_loads = BuiltList(c.axial_point_loads);
  out.axial_line_loads = BuiltList(c.axial_line_loads);
  out.rotation = Built(c.rotation);
  out.translation = Built(c.translation);
  out.joint_angles = Built(c.joint_angles);
  out.rigid_forces = BuiltList(c.rigid_forces);
  out.rigid_torque = Built(c.rigid_torque);
  out.rigid_drag = c.rigid_drag;
  return out;
}
ProfileChannels<Track> Built(const ProfileChannels<RawTrack>& c) {
  ProfileChannels<Track> out;
  out.profiles = c.profiles;
  out.from = c.from;
  out.to = c.to;
  out.boundary = c.boundary;
  out.point_loads = BuiltList(c.point_loads);
  out.line_loads = BuiltList(c.line_loads);
  return out;
}

std::string CheckBoundaryKeys(const std::vector<BoundaryKey>& keys, double duration,
                              const std::string& where) {
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string key = Indexed(where, "boundary", i);
    const int family = static_cast<int>(keys[i].boundary);
    if (family < 0 || family > 3) return At(key, "boundary: unknown family");
    if (!(keys[i].time >= 0.0 && keys[i].time <= duration))
      return At(key, "time: must lie within the clip, [0, duration]");
    if (i > 0 && !(keys[i].time > keys[i - 1].time))
      return At(key, "time: key times must be strictly increasing");
  }
  return {};
}

bool HasRigidInput(const PartChannels<RawTrack>& c) {
  return !c.rigid_forces.empty() || !c.rigid_torque.keys.empty() || !c.rigid_drag.IsZero();
}

// A load's keyed values that would make it vanish: a point load's direction of zero length, a
// line load whose stretch (from, to, each clamped to [0, 1]; absent: 0 and 1) is empty at every
// key of its ends, so that it never acts. (Both are skipped when sampled: the load would
// silently do nothing. A stretch that closes at some keys only is a load sliding off: kept.)
std::string CheckLoadKeys(const PointLoadChannels<RawTrack>& c, const std::string& where) {
  for (std::size_t i = 0; i < c.direction.keys.size(); ++i)
    if (!(c.direction.keys[i].value.norm() > 1e-12))
      return At(where, "direction.keys[" + std::to_string(i) +
                           "].value: must have a non-zero length (the force's direction)");
  return {};
}
template <typename LineLoad>
std::string CheckStretchKeys(const LineLoad& c, const std::string& where) {
  const Track<double> from = Built(c.from), to = Built(c.to);
  auto at = [](const Track<double>& track, double t, double absent) {
    return track.IsEmpty() ? absent : std::clamp(track.Sample(t), 0.0, 1.0);
  };
  std::vector<double> times(from.KeyTimes().begin(), from.KeyTimes().end());
  times.insert(times.end(), to.KeyTimes().begin(), to.KeyTimes().end());
  if (times.empty()) return {};  // 0 to 1
  for (const double t : times)
    if (at(to, t, 1.0) > at(from, t, 0.0)) return {};
  char values[96];
  std::snprintf(values, sizeof values, " (at t = %g s: from %g, to %g)", times.front(),
                at(from, times.front(), 0.0), at(to, times.front(), 1.0));
  return At(where, std::string("to: must be greater than from at some key, or the load never "
                               "acts") +
                       values);
}
std::string CheckLoadKeys(const LineLoadChannels<RawTrack>& c, const std::string& where) {
  return CheckStretchKeys(c, where);
}
std::string CheckLoadKeys(const AxialLineLoadChannels<RawTrack>& c, const std::string& where) {
  return CheckStretchKeys(c, where);
}
template <typename List>
std::string CheckListKeys(const List& list, const std::string& where, std::string_view member) {
  for (std::size_t i = 0; i < list.size(); ++i)
    if (std::string error = CheckLoadKeys(list[i], Indexed(where, member, i)); !error.empty())
      return error;
  return {};
}

}  // namespace

std::string_view ToString(LoopMode mode) {
  switch (mode) {
    case LoopMode::kOnce:
      return "once";
    case LoopMode::kLoop:
      return "loop";
    case LoopMode::kPingPong:
      return "ping_pong";
  }
  return "unknown";
}

bool ParseLoopMode(std::string_view name, LoopMode* out) {
  for (LoopMode m : {LoopMode::kOnce, LoopMode::kLoop, LoopMode::kPingPong}) {
    if (name == ToString(m)) {
      *out = m;
      return true;
    }
  }
  return false;
}

std::string ValidateRawClip(const RawClip& raw) {
  if (raw.name.empty()) return "name: a clip needs a name";
  // At most about 11.6 days: a longer clip is a typo (its keys would not fit any file).
  if (!(std::isfinite(raw.duration) && raw.duration > 0.0 && raw.duration <= kMaxClipDuration))
    return "duration: must be positive and at most 1e6 (s)";
  const int loop = static_cast<int>(raw.loop);
  if (loop < 0 || loop > 2) return "loop: unknown loop mode";
  std::string error;
  auto check = [&](const auto& track, const std::string& where) {
    if (error.empty()) error = CheckTrack(track, raw.duration, where);
  };
  for (std::size_t i = 0; i < raw.parts.size(); ++i) {
    const std::string where = Indexed("", "parts", i).substr(1);
    if (raw.parts[i].part.empty()) return At(where, "part: names no part");
    for (std::size_t j = 0; j < i; ++j)
      if (raw.parts[j].part == raw.parts[i].part)
        return At(where, "part: this part already has tracks in the clip");
    const PartChannels<RawTrack>& channels = raw.parts[i].channels;
    if (!std::isfinite(channels.axial_fixed_at) || channels.axial_fixed_at < 0.0 ||
        channels.axial_fixed_at > 1.0)
      return At(where, "axial_fixed_at: must lie in [0, 1]");
    const RigidDrag& drag = channels.rigid_drag;
    for (const auto& [name, value] :
         {std::pair{"linear", drag.linear}, std::pair{"quadratic", drag.quadratic},
          std::pair{"angular", drag.angular}})
      if (!(std::isfinite(value) && value >= 0.0 && value <= 1e9))
        return At(where, std::string("rigid_drag/") + name + ": must be finite, in [0, 1e9]");
    if (!(std::isfinite(channels.reach.max_force) && channels.reach.max_force >= 0.0 &&
          channels.reach.max_force <= 1e12))
      return At(where, "reach/max_force: must be finite, in [0, 1e12] (N)");
    if (channels.large_deflection || !channels.reach.target.keys.empty())
      for (const BoundaryKey& key : channels.boundary)
        if (!IsCantilever(key.boundary))
          return At(where, "boundary: large_deflection and reach need cantilever keys only");
    if (std::string boundary = CheckBoundaryKeys(channels.boundary, raw.duration, where);
        !boundary.empty())
      return boundary;
    VisitTracks(channels, where, check);
    if (!error.empty()) return error;
    for (const std::string& loads :
         {CheckListKeys(channels.point_loads, where, "point_loads"),
          CheckListKeys(channels.line_loads, where, "line_loads"),
          CheckListKeys(channels.axial_line_loads, where, "axial_line_loads")})
      if (!loads.empty()) return loads;
    // A part moved beyond the evaluation's reach (1e7 m) is a typo: named here, not where the
    // bake's vertices overflow.
    const std::vector<RawKey<Vec3>>& moves = channels.translation.keys;
    for (std::size_t k = 0; k < moves.size(); ++k)
      if (!(moves[k].value.norm() <= kMaxClipTranslation))
        return At(where, "translation.keys[" + std::to_string(k) + "].value: beyond 1e6 m");
  }
  for (std::size_t i = 0; i < raw.profiles.size(); ++i) {
    const std::string where = Indexed("", "profiles", i).substr(1);
    const ProfileChannels<RawTrack>& channels = raw.profiles[i].channels;
    if (raw.profiles[i].part.empty()) return At(where, "part: names no part");
    if (!(channels.from >= 0.0 && channels.to <= 1.0 && channels.from < channels.to))
      return At(where, "from: the stretch must satisfy 0 <= from < to <= 1");
    const int family = static_cast<int>(channels.boundary);
    if (family < 0 || family > 3) return At(where, "boundary: unknown family");
    VisitTracks(channels, where, check);
    if (!error.empty()) return error;
    for (const std::string& loads : {CheckListKeys(channels.point_loads, where, "point_loads"),
                                     CheckListKeys(channels.line_loads, where, "line_loads")})
      if (!loads.empty()) return loads;
  }
  return {};
}

double Clip::LocalTime(double t) const {
  // The runtime's clip assets loop by the same rule (clip_asset.h); one definition of it.
  return ClipLocalTime(ClipLoop(int(loop)), duration, t);
}

bool Clip::HasDynamics() const {
  for (const PartChannels<Track>& part : parts)
    if (!part.rigid_forces.empty() || !part.rigid_torque.IsEmpty() || !part.rigid_drag.IsZero())
      return true;
  return false;
}

Result<Clip> BuildClip(const RawClip& raw, const RigModel& model) {
  if (std::string error = ValidateRawClip(raw); !error.empty()) return Error{error};
  auto find_part = [&](const std::string& name) -> int {
    for (std::size_t p = 0; p < model.parts.size(); ++p)
      if (model.parts[p].name == name) return static_cast<int>(p);
    return -1;
  };
  auto unknown_part = [&](const std::string& where, const std::string& name) {
    std::vector<std::string> names;
    for (const PartModel& part : model.parts) names.push_back(part.name);
    std::string message = At(where, "part: no part of the rig is named \"");
    return Error{message.append(name).append("\"").append(NameHint(name, names, "parts"))};
  };
  Clip clip;
  clip.name = raw.name;
  clip.duration = raw.duration;
  clip.loop = raw.loop;
  clip.parts.resize(model.parts.size());
  std::vector<double> times = {0.0, raw.duration};
  auto collect = [&](const auto& track, const std::string&) {
    for (const auto& key : track.keys) times.push_back(key.time);
  };
  for (std::size_t i = 0; i < raw.parts.size(); ++i) {
    const RawPartTracks& tracks = raw.parts[i];
    const std::string where = Indexed("", "parts", i).substr(1);
    const int p = find_part(tracks.part);
    if (p < 0) return unknown_part(where, tracks.part);
    if (HasRigidInput(tracks.channels) && model.parts[p].kind != SpineKind::kRigid)
      return Error{At(where, "rigid_forces: rigid-body forces and torques need a rigid part")};
    if ((tracks.channels.large_deflection || !tracks.channels.reach.target.keys.empty()) &&
        model.parts[p].kind != SpineKind::kDeformable)
      return Error{At(where, "large_deflection: large curls and reach need a deformable part")};
    if (!tracks.channels.joint_angles.keys.empty() && model.parts[p].parent < 0)
      return Error{At(where, "joint_angles: part \"" + tracks.part +
                                 "\" is the root: it has no joint to turn")};
    VisitTracks(tracks.channels, where, collect);
    for (const BoundaryKey& key : tracks.channels.boundary) times.push_back(key.time);
    clip.parts[p] = Built(tracks.channels);
  }
  for (std::size_t i = 0; i < raw.profiles.size(); ++i) {
    const RawProfileTracks& tracks = raw.profiles[i];
    const std::string where = Indexed("", "profiles", i).substr(1);
    const int p = find_part(tracks.part);
    if (p < 0) return unknown_part(where, tracks.part);
    const std::size_t count = model.parts[p].profiles.size();
    for (std::size_t k = 0; k < tracks.channels.profiles.size(); ++k) {
      if (tracks.channels.profiles[k] >= count) {
        std::string message = Indexed(where, "profiles", k);
        message.append(": part \"").append(tracks.part).append("\" has ");
        message.append(std::to_string(count)).append(" profile wires");
        return Error{message};
      }
    }
    VisitTracks(tracks.channels, where, collect);
    Clip::ProfileGroup group{static_cast<std::uint32_t>(p), Built(tracks.channels)};
    if (group.channels.profiles.empty())
      for (std::uint32_t k = 0; k < count; ++k) group.channels.profiles.push_back(k);
    clip.profiles.push_back(std::move(group));
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  clip.key_times = std::move(times);
  return clip;
}

}  // namespace wirerig
