#include "wirerig/anim/clip_json.h"

#include <type_traits>

#include <nlohmann/json.hpp>

namespace wirerig {
namespace {

using nlohmann::json;

double ReadNumber(const json& value, const std::string& path) {
  if (!value.is_number()) throw FieldError(path, "must be a number");
  return value.get<double>();
}

template <typename T>
T ReadValue(const json& value, const std::string& path) {
  if constexpr (std::is_same_v<T, Vec3>) {
    return ReadVector3(value, path);
  } else {
    return ReadNumber(value, path);
  }
}

Interpolation ReadInterpolation(const json& value, const std::string& path) {
  Interpolation out = Interpolation::kLinear;
  if (!value.is_string() || !ParseInterpolation(value.get<std::string>(), &out))
    throw FieldError(path, "must be \"step\", \"linear\" or \"cubic\"");
  return out;
}

bool IsConstant(const json& value) { return value.is_number() || value.is_array(); }

template <typename T>
RawTrack<T> ReadTrack(const json& value, const std::string& path) {
  RawTrack<T> track;
  if (IsConstant(value)) {
    track.keys.push_back({0.0, ReadValue<T>(value, path), Interpolation::kStep});
  } else {
    if (!value.is_object()) {  // "must be an object" pointed away from the usual constant
      throw FieldError(path, std::is_same_v<T, double>
                                 ? "must be a number or a track {\"keys\": [[time, value], ...]}"
                                 : "must be [x, y, z] or a track {\"keys\": [[time, [x, y, z]], "
                                   "...]}");
    }
    const JsonObject object(value, path);
    object.RejectUnknownKeys({"interpolation", "keys"});
    Interpolation fallback = Interpolation::kLinear;
    if (object.Has("interpolation"))
      fallback =
          ReadInterpolation(object.Required("interpolation"), object.PathOf("interpolation"));
    const std::string keys_path = object.PathOf("keys");
    const json& keys = RequireArray(object.Required("keys"), keys_path);
    for (std::size_t i = 0; i < ArraySize(keys); ++i) {
      const json& key = ArrayElement(keys, i);
      const std::string key_path = keys_path + "/" + std::to_string(i);
      RawKey<T> out;
      out.interpolation = fallback;
      if (key.is_array()) {
        if (key.size() < 2 || key.size() > 3)
          throw FieldError(key_path, "must be [time, value] or [time, value, interpolation]");
        out.time = ReadNumber(key[0], key_path + "/0");
        out.value = ReadValue<T>(key[1], key_path + "/1");
        if (key.size() == 3) out.interpolation = ReadInterpolation(key[2], key_path + "/2");
      } else {
        const JsonObject k(key, key_path);
        k.RejectUnknownKeys({"time", "value", "interpolation"});
        out.time = k.Number("time");
        out.value = ReadValue<T>(k.Required("value"), k.PathOf("value"));
        if (k.Has("interpolation"))
          out.interpolation =
              ReadInterpolation(k.Required("interpolation"), k.PathOf("interpolation"));
      }
      track.keys.push_back(out);
    }
  }
  if (std::string error = ValidateRawTrack(track); !error.empty()) {
    // "keys[2].time: ..." -> "/path/keys/2/time: ..."
    throw FieldError(path, error);
  }
  return track;
}

template <typename T>
void ReadOptionalTrack(const JsonObject& object, std::string_view key, RawTrack<T>* out) {
  if (object.Has(key)) *out = ReadTrack<T>(object.Required(key), object.PathOf(key));
}

json ValueToJson(double v) { return v; }
json ValueToJson(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

template <typename T>
json TrackToJson(const RawTrack<T>& track) {
  if (track.keys.size() == 1 && track.keys[0].time == 0.0 &&
      track.keys[0].interpolation == Interpolation::kStep)
    return ValueToJson(track.keys[0].value);
  json keys = json::array();
  for (const RawKey<T>& key : track.keys)
    keys.push_back({{"time", key.time},
                    {"value", ValueToJson(key.value)},
                    {"interpolation", std::string(ToString(key.interpolation))}});
  return {{"keys", keys}};
}

template <typename T>
void WriteOptionalTrack(json& object, const char* key, const RawTrack<T>& track) {
  if (!track.keys.empty()) object[key] = TrackToJson(track);
}

BoundaryCondition ReadBoundary(const json& value, const std::string& path) {
  BoundaryCondition out = BoundaryCondition::kClamped;
  if (!value.is_string() || !ParseBoundaryCondition(value.get<std::string>(), &out))
    throw FieldError(path,
                     "must be \"simply_supported\", \"clamped\", \"cantilever_free\" or "
                     "\"cantilever_guided\"");
  return out;
}

LoadAxes ReadAxes(const JsonObject& o, std::string_view key = "axes") {
  if (!o.Has(key)) return LoadAxes::kLocal;
  const std::string axes = o.String(key);
  if (axes == "local") return LoadAxes::kLocal;
  if (axes == "world") return LoadAxes::kWorld;
  throw FieldError(o.PathOf(key), "must be \"local\" or \"world\"");
}
void WriteAxes(json& out, LoadAxes axes, const char* key = "axes") {
  if (axes == LoadAxes::kWorld) out[key] = "world";
}

PointLoadChannels<RawTrack> ReadPointLoad(const JsonObject& o) {
  o.RejectUnknownKeys({"at", "magnitude", "direction", "axes"});
  PointLoadChannels<RawTrack> c;
  c.axes = ReadAxes(o);
  c.at = ReadTrack<double>(o.Required("at"), o.PathOf("at"));
  c.magnitude = ReadTrack<double>(o.Required("magnitude"), o.PathOf("magnitude"));
  c.direction = ReadTrack<Vec3>(o.Required("direction"), o.PathOf("direction"));
  return c;
}
json ToJson(const PointLoadChannels<RawTrack>& c) {
  json out = {{"at", TrackToJson(c.at)},
              {"magnitude", TrackToJson(c.magnitude)},
              {"direction", TrackToJson(c.direction)}};
  WriteAxes(out, c.axes);
  return out;
}

LineLoadChannels<RawTrack> ReadLineLoad(const JsonObject& o) {
  o.RejectUnknownKeys({"from", "to", "force_per_length", "axes"});
  LineLoadChannels<RawTrack> c;
  c.axes = ReadAxes(o);
  ReadOptionalTrack(o, "from", &c.from);
  ReadOptionalTrack(o, "to", &c.to);
  c.force_per_length =
      ReadTrack<Vec3>(o.Required("force_per_length"), o.PathOf("force_per_length"));
  return c;
}
json ToJson(const LineLoadChannels<RawTrack>& c) {
  json out = {{"force_per_length", TrackToJson(c.force_per_length)}};
  WriteAxes(out, c.axes);
  WriteOptionalTrack(out, "from", c.from);
  WriteOptionalTrack(out, "to", c.to);
  return out;
}

AxialPointLoadChannels<RawTrack> ReadAxialPointLoad(const JsonObject& o) {
  o.RejectUnknownKeys({"at", "force"});
  return {ReadTrack<double>(o.Required("at"), o.PathOf("at")),
          ReadTrack<double>(o.Required("force"), o.PathOf("force"))};
}
json ToJson(const AxialPointLoadChannels<RawTrack>& c) {
  return {{"at", TrackToJson(c.at)}, {"force", TrackToJson(c.force)}};
}

AxialLineLoadChannels<RawTrack> ReadAxialLineLoad(const JsonObject& o) {
  o.RejectUnknownKeys({"from", "to", "force_per_length"});
  AxialLineLoadChannels<RawTrack> c;
  ReadOptionalTrack(o, "from", &c.from);
  ReadOptionalTrack(o, "to", &c.to);
  c.force_per_length =
      ReadTrack<double>(o.Required("force_per_length"), o.PathOf("force_per_length"));
  return c;
}
json ToJson(const AxialLineLoadChannels<RawTrack>& c) {
  json out = {{"force_per_length", TrackToJson(c.force_per_length)}};
  WriteOptionalTrack(out, "from", c.from);
  WriteOptionalTrack(out, "to", c.to);
  return out;
}

RigidForceChannels<RawTrack> ReadRigidForce(const JsonObject& o) {
  o.RejectUnknownKeys({"at", "force"});
  return {ReadVector3(o.Required("at"), o.PathOf("at")),
          ReadTrack<Vec3>(o.Required("force"), o.PathOf("force"))};
}
json ToJson(const RigidForceChannels<RawTrack>& c) {
  return {{"at", ValueToJson(c.at)}, {"force", TrackToJson(c.force)}};
}

template <typename Read>
auto ReadList(const JsonObject& o, std::string_view key, Read read) {
  std::vector<decltype(read(o))> out;
  ForEachElement(o, key, [&](const JsonObject& element) { out.push_back(read(element)); });
  return out;
}
json ToJson(const RawPartTracks& tracks);
json ToJson(const RawProfileTracks& tracks);

template <typename List>
void WriteList(json& object, const char* key, const List& list) {
  if (list.empty()) return;
  json array = json::array();
  for (const auto& item : list) array.push_back(ToJson(item));
  object[key] = array;
}

std::vector<BoundaryKey> ReadBoundaryKeys(const JsonObject& o) {
  const json& value = o.Required("boundary");
  const std::string path = o.PathOf("boundary");
  if (value.is_string()) return {{0.0, ReadBoundary(value, path)}};
  std::vector<BoundaryKey> keys;
  const json& array = RequireArray(value, path);
  for (std::size_t i = 0; i < ArraySize(array); ++i) {
    const JsonObject key(ArrayElement(array, i), path + "/" + std::to_string(i));
    key.RejectUnknownKeys({"time", "boundary"});
    keys.push_back(
        {key.Number("time"), ReadBoundary(key.Required("boundary"), key.PathOf("boundary"))});
  }
  return keys;
}

RawPartTracks ReadPartTracks(const JsonObject& o) {
  o.RejectUnknownKeys({"part",
                       "boundary",
                       "point_loads",
                       "line_loads",
                       "tip_force",
                       "tip_couple",
                       "tip_couple_axes",
                       "large_deflection",
                       "reach",
                       "start_displacement",
                       "end_displacement",
                       "axial_fixed_at",
                       "axial_point_loads",
                       "axial_line_loads",
                       "rotation",
                       "translation",
                       "joint_angles",
                       "rigid_forces",
                       "rigid_torque",
                       "rigid_drag"});
  RawPartTracks tracks;
  tracks.part = o.String("part");
  PartChannels<RawTrack>& c = tracks.channels;
  if (o.Has("boundary")) c.boundary = ReadBoundaryKeys(o);
  c.point_loads = ReadList(o, "point_loads", ReadPointLoad);
  c.line_loads = ReadList(o, "line_loads", ReadLineLoad);
  ReadOptionalTrack(o, "tip_force", &c.tip_force);
  ReadOptionalTrack(o, "tip_couple", &c.tip_couple);
  c.tip_couple_axes = ReadAxes(o, "tip_couple_axes");
  c.large_deflection = o.Bool("large_deflection", false);
  if (o.Has("reach")) {
    const JsonObject reach = o.Object("reach");
    reach.RejectUnknownKeys({"target", "parent_frame", "weight", "max_force"});
    c.reach.parent_frame = reach.Bool("parent_frame", false);
    ReadOptionalTrack(reach, "target", &c.reach.target);
    ReadOptionalTrack(reach, "weight", &c.reach.weight);
    c.reach.max_force = reach.Number("max_force", c.reach.max_force);
  }
  ReadOptionalTrack(o, "start_displacement", &c.start_displacement);
  ReadOptionalTrack(o, "end_displacement", &c.end_displacement);
  c.axial_fixed_at = o.Number("axial_fixed_at", 0.0);
  c.axial_point_loads = ReadList(o, "axial_point_loads", ReadAxialPointLoad);
  c.axial_line_loads = ReadList(o, "axial_line_loads", ReadAxialLineLoad);
  ReadOptionalTrack(o, "rotation", &c.rotation);
  ReadOptionalTrack(o, "translation", &c.translation);
  ReadOptionalTrack(o, "joint_angles", &c.joint_angles);
  c.rigid_forces = ReadList(o, "rigid_forces", ReadRigidForce);
  ReadOptionalTrack(o, "rigid_torque", &c.rigid_torque);
  if (o.Has("rigid_drag")) {
    const JsonObject drag = o.Object("rigid_drag");
    drag.RejectUnknownKeys({"linear", "quadratic", "angular"});
    c.rigid_drag = {drag.Number("linear", 0.0), drag.Number("quadratic", 0.0),
                    drag.Number("angular", 0.0)};
  }
  return tracks;
}

json ToJson(const RawPartTracks& tracks) {
  const PartChannels<RawTrack>& c = tracks.channels;
  json out = {{"part", tracks.part}};
  if (!c.boundary.empty()) {
    json keys = json::array();
    for (const BoundaryKey& key : c.boundary)
      keys.push_back({{"time", key.time}, {"boundary", std::string(ToString(key.boundary))}});
    out["boundary"] = keys;
  }
  WriteList(out, "point_loads", c.point_loads);
  WriteList(out, "line_loads", c.line_loads);
  WriteOptionalTrack(out, "tip_force", c.tip_force);
  WriteOptionalTrack(out, "tip_couple", c.tip_couple);
  WriteAxes(out, c.tip_couple_axes, "tip_couple_axes");
  if (c.large_deflection) out["large_deflection"] = true;
  if (!c.reach.target.keys.empty()) {
    json reach = json::object();
    WriteOptionalTrack(reach, "target", c.reach.target);
    WriteOptionalTrack(reach, "weight", c.reach.weight);
    reach["max_force"] = c.reach.max_force;
    if (c.reach.parent_frame) reach["parent_frame"] = true;
    out["reach"] = reach;
  }
  WriteOptionalTrack(out, "start_displacement", c.start_displacement);
  WriteOptionalTrack(out, "end_displacement", c.end_displacement);
  if (c.axial_fixed_at != 0.0) out["axial_fixed_at"] = c.axial_fixed_at;
  WriteList(out, "axial_point_loads", c.axial_point_loads);
  WriteList(out, "axial_line_loads", c.axial_line_loads);
  WriteOptionalTrack(out, "rotation", c.rotation);
  WriteOptionalTrack(out, "translation", c.translation);
  WriteOptionalTrack(out, "joint_angles", c.joint_angles);
  WriteList(out, "rigid_forces", c.rigid_forces);
  WriteOptionalTrack(out, "rigid_torque", c.rigid_torque);
  if (!c.rigid_drag.IsZero())
    out["rigid_drag"] = {{"linear", c.rigid_drag.linear},
                         {"quadratic", c.rigid_drag.quadratic},
                         {"angular", c.rigid_drag.angular}};
  return out;
}

RawProfileTracks ReadProfileTracks(const JsonObject& o) {
  o.RejectUnknownKeys({"part", "profiles", "from", "to", "boundary", "point_loads", "line_loads"});
  RawProfileTracks tracks;
  tracks.part = o.String("part");
  ProfileChannels<RawTrack>& c = tracks.channels;
  if (o.Has("profiles")) {
    const std::string path = o.PathOf("profiles");
    const json& array = RequireArray(o.Required("profiles"), path);
    for (std::size_t i = 0; i < ArraySize(array); ++i) {
      const json& index = ArrayElement(array, i);
      if (!index.is_number_integer() || index.get<long long>() < 0 ||
          index.get<long long>() > 0xFFFFFFFFLL)
        throw FieldError(path + "/" + std::to_string(i), "must be a profile index (0, 1, ...)");
      c.profiles.push_back(index.get<std::uint32_t>());
    }
  }
  c.from = o.Number("from", 0.0);
  c.to = o.Number("to", 1.0);
  if (o.Has("boundary")) c.boundary = ReadBoundary(o.Required("boundary"), o.PathOf("boundary"));
  c.point_loads = ReadList(o, "point_loads", ReadPointLoad);
  c.line_loads = ReadList(o, "line_loads", ReadLineLoad);
  return tracks;
}

json ToJson(const RawProfileTracks& tracks) {
  const ProfileChannels<RawTrack>& c = tracks.channels;
  json out = {{"part", tracks.part},
              {"from", c.from},
              {"to", c.to},
              {"boundary", std::string(ToString(c.boundary))}};
  if (!c.profiles.empty()) out["profiles"] = c.profiles;
  WriteList(out, "point_loads", c.point_loads);
  WriteList(out, "line_loads", c.line_loads);
  return out;
}

}  // namespace

RawClip ReadClip(const JsonObject& o) {
  o.RejectUnknownKeys({"name", "duration", "loop", "parts", "profiles"});
  RawClip clip;
  clip.name = o.String("name");
  clip.duration = o.Number("duration");
  if (o.Has("loop") && !ParseLoopMode(o.String("loop"), &clip.loop))
    throw FieldError(o.PathOf("loop"), "must be \"once\", \"loop\" or \"ping_pong\"");
  clip.parts = ReadList(o, "parts", ReadPartTracks);
  clip.profiles = ReadList(o, "profiles", ReadProfileTracks);
  return clip;
}

nlohmann::json ClipToJson(const RawClip& clip) {
  json out = {
      {"name", clip.name}, {"duration", clip.duration}, {"loop", std::string(ToString(clip.loop))}};
  WriteList(out, "parts", clip.parts);
  WriteList(out, "profiles", clip.profiles);
  return out;
}

}  // namespace wirerig
