#include "wirerig/runtime/clip_asset.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "asset_envelope.h"
#include "byte_codec.h"
#include "validation.h"

namespace wirerig {
namespace {

constexpr AssetMagic kMagic = {'W', 'C', 'L', 'P'};
constexpr std::size_t kPartKeyBytes = 32 + 24 + 1 + 72 + 8 + 32, kProfileKeyBytes = 41;

void Write(bytes::Writer& w, const LoadRange& r) { w.U32(r.first), w.U32(r.count); }
LoadRange ReadRange(bytes::Reader& r) {
  const std::uint32_t first = r.U32(), count = r.U32();
  return {first, count};
}

void Write(bytes::Writer& w, const PartKey& k) {
  w.F64(k.rotation.x()), w.F64(k.rotation.y()), w.F64(k.rotation.z()), w.F64(k.rotation.w());
  w.V3(k.translation);
  w.U8(std::uint8_t(k.boundary));
  w.V3(k.tip_force), w.V3(k.start_displacement), w.V3(k.end_displacement);
  w.V3(k.tip_couple), w.U8(k.large_deflection ? 1 : 0), w.U32(k.curl_segments);
  w.F64(k.axial_fixed_at);
  Write(w, k.point_loads), Write(w, k.line_loads);
  Write(w, k.axial_point_loads), Write(w, k.axial_line_loads);
}

PartKey ReadPartKey(bytes::Reader& r) {
  PartKey k;
  const double x = r.F64(), y = r.F64(), z = r.F64(), w = r.F64();
  k.rotation = Quat(w, x, y, z);
  k.translation = r.V3();
  k.boundary = BoundaryCondition(r.U8());
  k.tip_force = r.V3(), k.start_displacement = r.V3(), k.end_displacement = r.V3();
  k.tip_couple = r.V3(), k.large_deflection = r.U8() != 0, k.curl_segments = r.U32();
  k.axial_fixed_at = r.F64();
  k.point_loads = ReadRange(r), k.line_loads = ReadRange(r);
  k.axial_point_loads = ReadRange(r), k.axial_line_loads = ReadRange(r);
  return k;
}

bool Finite(double x) { return std::isfinite(x) && std::abs(x) <= 1e12; }
bool Finite(const Vec3& v) { return Finite(v.x()) && Finite(v.y()) && Finite(v.z()); }
bool OnWire(double v) { return v >= 0.0 && v <= 1.0; }
bool Inside(const LoadRange& r, std::size_t size) {
  return r.first <= size && r.count <= size - r.first;
}

Status ValidateLoads(const SampledClip& c) {
  for (const PointLoad& l : c.point_loads)
    if (!OnWire(l.at) || !Finite(l.force))
      return Status::Invalid("point_loads", "need at in [0, 1] and a finite force");
  for (const LineLoad& l : c.line_loads)
    if (!OnWire(l.from) || !OnWire(l.to) || !(l.from < l.to) || !Finite(l.force_per_length))
      return Status::Invalid("line_loads", "need 0 <= from < to <= 1 and a finite force");
  for (const AxialPointLoad& l : c.axial_point_loads)
    if (!OnWire(l.at) || !Finite(l.force))
      return Status::Invalid("axial_point_loads", "need at in [0, 1] and a finite force");
  for (const AxialLineLoad& l : c.axial_line_loads)
    if (!OnWire(l.from) || !OnWire(l.to) || !(l.from < l.to) || !Finite(l.force_per_length))
      return Status::Invalid("axial_line_loads", "need 0 <= from < to <= 1 and a finite force");
  return Status::Ok();
}

Status ValidateWires(const SampledClip& c, const RigModel* model) {
  std::vector<bool> seen(c.part_count, false);
  for (std::size_t i = 0; i < c.wires.size(); ++i) {
    const ClipWire& w = c.wires[i];
    const int index = int(i);
    if (w.part >= c.part_count || seen[w.part])
      return Status::InvalidElement("wires", index, "part", "must name a part no other wire does");
    seen[w.part] = true;
    if (!detail::IsKnownBoundary(w.boundary))
      return Status::InvalidElement("wires", index, "boundary", "unknown boundary condition");
    if (w.modes < 1 || w.modes > std::uint32_t(ModalBasis::kMaxModes))
      return Status::InvalidElement("wires", index, "modes", "must lie in [1, 32]");
    if (w.samples < 2 || w.samples > 65536)
      return Status::InvalidElement("wires", index, "samples", "must lie in [2, 65536]");
    if (!(Finite(w.length) && w.length > 0.0) ||
        !(Finite(w.bending_stiffness) && w.bending_stiffness > 0.0))
      return Status::InvalidElement("wires", index, "",
                                    "length and bending_stiffness must be "
                                    "finite and positive");
    // Keeps every residual's closed form finite (ModalResidualJob): loads are at most 1e12.
    const double compliance = std::pow(w.length, 4) / w.bending_stiffness;
    if (!(std::isfinite(compliance) && compliance <= 1e138))
      return Status::InvalidElement("wires", index, "bending_stiffness",
                                    "too small for the length (L^4 / EI above 1e138)");
    if (model != nullptr) {
      const PartModel& part = model->parts[w.part];
      if (part.kind != SpineKind::kDeformable || part.spine_points.size() != w.samples)
        return Status::InvalidElement("wires", index, "part",
                                      "is not a deformable part with as many spine samples");
    }
  }
  // The stride is at most 34 x 65536 x part_count: no overflow in the product below.
  if (c.wire_motion.size() != c.frame_count() * c.wire_motion_stride())
    return Status::Invalid("wire_motion", "needs every wire's residual at every frame");
  for (std::size_t i = 0; i < c.wire_motion.size(); ++i)
    if (!Finite(c.wire_motion[i]))
      return Status::InvalidElement("wire_motion", int(i), "", "must be finite, at most 1e12");
  return Status::Ok();
}

Status ValidateProfileWires(const SampledClip& c, const RigModel* model) {
  // (part, profile, index) sorted: a profile named twice shows as neighbours (n log n, as a
  // file may hold a million profile wires).
  std::vector<std::array<std::uint32_t, 3>> named(c.profile_wires.size());
  for (std::size_t i = 0; i < c.profile_wires.size(); ++i)
    named[i] = {c.profile_wires[i].part, c.profile_wires[i].profile, std::uint32_t(i)};
  std::sort(named.begin(), named.end());
  for (std::size_t i = 1; i < named.size(); ++i)
    if (named[i][0] == named[i - 1][0] && named[i][1] == named[i - 1][1])
      return Status::InvalidElement("profile_wires", int(named[i][2]), "profile",
                                    "must name a profile no other profile wire does");
  for (std::size_t i = 0; i < c.profile_wires.size(); ++i) {
    const ClipProfileWire& w = c.profile_wires[i];
    const int index = int(i);
    if (w.part >= c.part_count)
      return Status::InvalidElement("profile_wires", index, "part", "must name a part");
    if (w.modes < 1 || w.modes > std::uint32_t(ModalBasis::kMaxModes))
      return Status::InvalidElement("profile_wires", index, "modes", "must lie in [1, 32]");
    if (w.weights.size() < 2 || w.weights.size() > 65536)
      return Status::InvalidElement("profile_wires", index, "weights",
                                    "need one per profile point, 2 to 65536");
    for (const double weight : w.weights)
      if (!(weight >= 0.0 && weight <= 1.0))
        return Status::InvalidElement("profile_wires", index, "weights", "must lie in [0, 1]");
    if (!(Finite(w.length) && w.length > 0.0) ||
        !(Finite(w.bending_stiffness) && w.bending_stiffness > 0.0) ||
        !(Finite(w.reach) && w.reach > 0.0))
      return Status::InvalidElement("profile_wires", index, "",
                                    "length, bending_stiffness and reach must be finite and "
                                    "positive");
    const double compliance = std::pow(w.length, 4) / w.bending_stiffness;
    if (!(std::isfinite(compliance) && compliance <= 1e138))
      return Status::InvalidElement("profile_wires", index, "bending_stiffness",
                                    "too small for the length (L^4 / EI above 1e138)");
    if (model != nullptr) {
      const PartModel& part = model->parts[w.part];
      if (w.profile >= part.profiles.size() ||
          part.profiles[w.profile].local_points.size() != w.weights.size() ||
          part.profiles[w.profile].closed != w.closed)
        return Status::InvalidElement("profile_wires", index, "profile",
                                      "is not a profile of the part with as many points");
    }
  }
  if (c.profile_wire_motion.size() != c.frame_count() * c.profile_wire_motion_stride())
    return Status::Invalid("profile_wire_motion",
                           "needs every profile wire's residual at every "
                           "frame");
  for (std::size_t i = 0; i < c.profile_wire_motion.size(); ++i)
    if (!Finite(c.profile_wire_motion[i]))
      return Status::InvalidElement("profile_wire_motion", int(i), "",
                                    "must be finite, at most 1e12");
  return Status::Ok();
}

// The largest count of a range over the part keys (per part) and profile keys, for buffers.
template <class Key, class Member>
std::uint32_t MostOf(const std::vector<Key>& keys, Member member) {
  std::uint32_t most = 0;
  for (const Key& k : keys) most = std::max(most, (k.*member).count);
  return most;
}

// The sizes of MakeClipPlaybackBuffers' buffers: each part's and profile key's loads get their
// own stretch, as long as the most that part (or profile key) ever carries; each wire its mode
// tables. In size_t: a file's counts may multiply past 32 bits.
struct PlaybackSizes {
  std::size_t profiles = 0;  // most profile keys in a frame
  std::size_t points = 0, lines = 0, axial_points = 0, axial_lines = 0;
  std::size_t table_entries = 0;  // samples x modes, summed over the wires and profile wires
};

PlaybackSizes PlaybackSizesOf(const SampledClip& c) {
  PlaybackSizes z;
  for (const LoadRange& r : c.profile_keys_of_frame)
    z.profiles = std::max<std::size_t>(z.profiles, r.count);
  const std::size_t slots = std::size_t(c.part_count) + z.profiles;
  z.points = slots * std::max(MostOf(c.parts, &PartKey::point_loads),
                              MostOf(c.profile_keys, &ProfileKey::point_loads));
  z.lines = slots * std::max(MostOf(c.parts, &PartKey::line_loads),
                             MostOf(c.profile_keys, &ProfileKey::line_loads));
  z.axial_points = std::size_t(c.part_count) * MostOf(c.parts, &PartKey::axial_point_loads);
  z.axial_lines = std::size_t(c.part_count) * MostOf(c.parts, &PartKey::axial_line_loads);
  for (const ClipWire& w : c.wires) z.table_entries += std::size_t(w.samples) * w.modes;
  for (const ClipProfileWire& w : c.profile_wires)
    z.table_entries += w.weights.size() * std::size_t(w.modes);
  return z;
}

// What playback may hold: 4 Mi loads of each kind (about 100 MB at most) and 16 Mi mode table
// entries (256 MB). A real clip holds a few loads per part; a file asking for more (counts
// that multiply: many parts x one part with many loads) is refused at load, not allocated.
constexpr std::size_t kMostPlaybackLoads = std::size_t(1) << 22;     // 4194304, in the messages
constexpr std::size_t kMostModeTableEntries = std::size_t(1) << 24;  // 16777216

Status ValidatePlaybackSizes(const SampledClip& c) {
  const PlaybackSizes z = PlaybackSizesOf(c);
  const std::pair<const char*, std::size_t> loads[] = {{"point_loads", z.points},
                                                       {"line_loads", z.lines},
                                                       {"axial_point_loads", z.axial_points},
                                                       {"axial_line_loads", z.axial_lines}};
  for (const auto& [field, count] : loads)
    if (count > kMostPlaybackLoads)
      return Status::Invalid(field,
                             "playback would need over 4194304 slots (the most loads one part "
                             "or profile key carries, times the parts and profile keys of a "
                             "frame)");
  if (z.table_entries > kMostModeTableEntries)
    return Status::Invalid("wires",
                           "their mode tables would hold over 16777216 entries (samples x modes)");
  return Status::Ok();
}

// Loads of frames a and b at fraction f: interpolated element-wise when the two frames carry
// the same number of loads, else the nearer frame's. Writes `out` from `first`.
template <class Load, class Lerp>
std::span<const Load> Blend(const std::vector<Load>& all, const LoadRange& a, const LoadRange& b,
                            double f, bool same_shape, Lerp lerp, Load* out) {
  if (same_shape && a.count == b.count) {
    for (std::uint32_t i = 0; i < a.count; ++i)
      out[i] = lerp(all[a.first + i], all[b.first + i], f);
    return {out, a.count};
  }
  const LoadRange& near = f < 0.5 ? a : b;
  std::copy_n(all.begin() + near.first, near.count, out);
  return {out, near.count};
}

PointLoad Lerp(const PointLoad& a, const PointLoad& b, double f) {
  return {a.at + f * (b.at - a.at), a.force + f * (b.force - a.force)};
}
LineLoad Lerp(const LineLoad& a, const LineLoad& b, double f) {
  return {a.from + f * (b.from - a.from), a.to + f * (b.to - a.to),
          a.force_per_length + f * (b.force_per_length - a.force_per_length)};
}
AxialPointLoad Lerp(const AxialPointLoad& a, const AxialPointLoad& b, double f) {
  return {a.at + f * (b.at - a.at), a.force + f * (b.force - a.force)};
}
AxialLineLoad Lerp(const AxialLineLoad& a, const AxialLineLoad& b, double f) {
  return {a.from + f * (b.from - a.from), a.to + f * (b.to - a.to),
          a.force_per_length + f * (b.force_per_length - a.force_per_length)};
}
template <class Load>
Load LerpOf(const Load& a, const Load& b, double f) {
  return Lerp(a, b, f);
}

// A wire's residual between two frames' records a and e (modes coordinates, the uniform load,
// and with `turning` the ramp's end value) at fraction f.
ModalResidual LerpResidual(const Vec3* a, const Vec3* e, double f, std::uint32_t modes,
                           bool turning) {
  ModalResidual r;
  r.modes = int(modes);
  for (std::uint32_t n = 0; n <= modes; ++n) {
    Vec3& out = n < modes ? r.coordinates[n] : r.uniform_load;
    out = a[n] + f * (e[n] - a[n]);
  }
  if (turning) r.turning_load = a[modes + 1] + f * (e[modes + 1] - a[modes + 1]);
  return r;
}

}  // namespace

double ClipLocalTime(ClipLoop loop, double duration, double t) {
  if (!std::isfinite(t) || !(duration > 0.0)) return 0.0;
  // t modulo `period` in [0, period): a negative time wraps too (it held the first frame).
  const auto wrap = [t](double period) {
    const double u = std::fmod(t, period);
    return u < 0.0 ? std::min(u + period, std::nextafter(period, 0.0)) : u;
  };
  switch (loop) {
    case ClipLoop::kOnce:
      return std::clamp(t, 0.0, duration);
    case ClipLoop::kLoop:
      return wrap(duration);
    case ClipLoop::kPingPong: {
      const double u = wrap(2.0 * duration);
      return u <= duration ? u : 2.0 * duration - u;
    }
  }
  return 0.0;
}

Status ValidateSampledClip(const SampledClip& c, const RigModel* model) {
  if (!(std::isfinite(c.duration) && c.duration > 0.0 && c.duration <= 1e6))
    return Status::Invalid("duration", "must be positive and at most 1e6 s");
  if (!(std::isfinite(c.frame_rate) && c.frame_rate > 0.0 && c.frame_rate <= 1e4))
    return Status::Invalid("frame_rate", "must be positive and at most 1e4 per second");
  if (int(c.loop) < 0 || int(c.loop) > 2)
    return Status::Invalid("loop", "must be once, loop or ping_pong");
  if (c.part_count == 0 || c.frame_count() == 0 || c.parts.size() != c.frame_count() * c.part_count)
    return Status::Invalid("parts", "need one key per part per frame");
  if (model != nullptr && model->parts.size() != c.part_count)
    return Status::Invalid("part_count", "differs from the rig's");
  for (std::size_t i = 0; i < c.parts.size(); ++i) {
    const PartKey& k = c.parts[i];
    const int index = int(i);
    if (!(k.rotation.coeffs().array().abs() <= 1.5).all() ||
        std::abs(k.rotation.squaredNorm() - 1.0) > 1e-6)
      return Status::InvalidElement("parts", index, "rotation", "must be a unit quaternion");
    if (!Finite(k.translation) || !Finite(k.tip_force) || !Finite(k.start_displacement) ||
        !Finite(k.end_displacement) || !OnWire(k.axial_fixed_at) ||
        !detail::IsKnownBoundary(k.boundary))
      return Status::InvalidElement("parts", index, "", "must be finite, v in [0, 1]");
    if (!Finite(k.tip_couple))
      return Status::InvalidElement("parts", index, "tip_couple", "must be finite");
    if (k.curl_segments > 256)
      return Status::InvalidElement("parts", index, "curl_segments", "must be at most 256");
    if (!Inside(k.point_loads, c.point_loads.size()) ||
        !Inside(k.line_loads, c.line_loads.size()) ||
        !Inside(k.axial_point_loads, c.axial_point_loads.size()) ||
        !Inside(k.axial_line_loads, c.axial_line_loads.size()))
      return Status::InvalidElement("parts", index, "loads", "range past the end of the loads");
  }
  for (const LoadRange& r : c.profile_keys_of_frame)
    if (!Inside(r, c.profile_keys.size()))
      return Status::Invalid("profile_keys_of_frame", "range past the end of profile_keys");
  for (std::size_t i = 0; i < c.profile_keys.size(); ++i) {
    const ProfileKey& k = c.profile_keys[i];
    const int index = int(i);
    if (k.part >= c.part_count || !OnWire(k.from) || !OnWire(k.to) || !(k.from < k.to) ||
        !detail::IsKnownBoundary(k.boundary))
      return Status::InvalidElement("profile_keys", index, "",
                                    "need a part and 0 <= from < to <= 1");
    if (model != nullptr && k.profile >= model->parts[k.part].profiles.size())
      return Status::InvalidElement("profile_keys", index, "profile",
                                    "names a profile the part lacks");
    if (!Inside(k.point_loads, c.point_loads.size()) || !Inside(k.line_loads, c.line_loads.size()))
      return Status::InvalidElement("profile_keys", index, "loads",
                                    "range past the end of the loads");
  }
  if (Status s = ValidateWires(c, model); !s) return s;
  if (Status s = ValidateProfileWires(c, model); !s) return s;
  if (Status s = ValidateLoads(c); !s) return s;
  return ValidatePlaybackSizes(c);
}

std::size_t SampledClip::wire_motion_stride() const {
  std::size_t stride = 0;
  for (const ClipWire& w : wires) stride += std::size_t(w.modes) + 2;
  return stride;
}

std::size_t SampledClip::profile_wire_motion_stride() const {
  std::size_t stride = 0;
  for (const ClipProfileWire& w : profile_wires) stride += std::size_t(w.modes) + 1;
  return stride;
}

std::vector<std::uint8_t> SerializeClipAsset(const SampledClip& c) {
  bytes::Writer w;
  w.String(c.name);
  w.F64(c.duration), w.F64(c.frame_rate), w.U8(std::uint8_t(c.loop)), w.U32(c.part_count);
  w.Count(c.parts.size());
  for (const PartKey& k : c.parts) Write(w, k);
  w.Count(c.profile_keys_of_frame.size());
  for (const LoadRange& r : c.profile_keys_of_frame) Write(w, r);
  w.Count(c.profile_keys.size());
  for (const ProfileKey& k : c.profile_keys) {
    w.U32(k.part), w.U32(k.profile), w.F64(k.from), w.F64(k.to), w.U8(std::uint8_t(k.boundary));
    Write(w, k.point_loads), Write(w, k.line_loads);
  }
  w.Count(c.point_loads.size());
  for (const PointLoad& l : c.point_loads) w.F64(l.at), w.V3(l.force);
  w.Count(c.line_loads.size());
  for (const LineLoad& l : c.line_loads) w.F64(l.from), w.F64(l.to), w.V3(l.force_per_length);
  w.Count(c.axial_point_loads.size());
  for (const AxialPointLoad& l : c.axial_point_loads) w.F64(l.at), w.F64(l.force);
  w.Count(c.axial_line_loads.size());
  for (const AxialLineLoad& l : c.axial_line_loads)
    w.F64(l.from), w.F64(l.to), w.F64(l.force_per_length);
  w.Count(c.wires.size());
  for (const ClipWire& wire : c.wires) {
    w.U32(wire.part), w.U8(std::uint8_t(wire.boundary)), w.U32(wire.modes), w.U32(wire.samples);
    w.F64(wire.length), w.F64(wire.bending_stiffness);
  }
  w.Count(c.wire_motion.size());
  for (const Vec3& x : c.wire_motion) w.V3(x);
  w.Count(c.profile_wires.size());
  for (const ClipProfileWire& wire : c.profile_wires) {
    w.U32(wire.part), w.U32(wire.profile), w.U32(wire.modes), w.U8(wire.closed ? 1 : 0);
    w.F64(wire.length), w.F64(wire.bending_stiffness), w.F64(wire.reach);
    w.Count(wire.weights.size());
    for (const double weight : wire.weights) w.F64(weight);
  }
  w.Count(c.profile_wire_motion.size());
  for (const Vec3& x : c.profile_wire_motion) w.V3(x);
  return Envelope(kMagic, kClipAssetVersion, w.bytes());
}

Status ParseClipAsset(std::span<const std::uint8_t> bytes, SampledClip* out) {
  if (out == nullptr) return Status::Invalid("out", "is required");
  std::span<const std::uint8_t> payload;
  if (Status s = OpenEnvelope(bytes, kMagic, kClipAssetVersion,
                              "is not a wirerig clip asset (.wclip): wrong magic", &payload);
      !s)
    return s;
  bytes::Reader r(payload);
  SampledClip c;
  c.name = r.String();
  c.duration = r.F64(), c.frame_rate = r.F64(), c.loop = ClipLoop(r.U8()), c.part_count = r.U32();
  c.parts.resize(r.Count(kPartKeyBytes));
  for (PartKey& k : c.parts) k = ReadPartKey(r);
  c.profile_keys_of_frame.resize(r.Count(8));
  for (LoadRange& range : c.profile_keys_of_frame) range = ReadRange(r);
  c.profile_keys.resize(r.Count(kProfileKeyBytes));
  for (ProfileKey& k : c.profile_keys) {
    k.part = r.U32(), k.profile = r.U32(), k.from = r.F64(), k.to = r.F64();
    k.boundary = BoundaryCondition(r.U8());
    k.point_loads = ReadRange(r), k.line_loads = ReadRange(r);
  }
  c.point_loads.resize(r.Count(32));
  for (PointLoad& l : c.point_loads) l.at = r.F64(), l.force = r.V3();
  c.line_loads.resize(r.Count(40));
  for (LineLoad& l : c.line_loads) l.from = r.F64(), l.to = r.F64(), l.force_per_length = r.V3();
  c.axial_point_loads.resize(r.Count(16));
  for (AxialPointLoad& l : c.axial_point_loads) l.at = r.F64(), l.force = r.F64();
  c.axial_line_loads.resize(r.Count(24));
  for (AxialLineLoad& l : c.axial_line_loads)
    l.from = r.F64(), l.to = r.F64(), l.force_per_length = r.F64();
  c.wires.resize(r.Count(29));
  for (ClipWire& wire : c.wires) {
    wire.part = r.U32(), wire.boundary = BoundaryCondition(r.U8());
    wire.modes = r.U32(), wire.samples = r.U32();
    wire.length = r.F64(), wire.bending_stiffness = r.F64();
  }
  c.wire_motion.resize(r.Count(24));
  for (Vec3& x : c.wire_motion) x = r.V3();
  c.profile_wires.resize(r.Count(41));
  for (ClipProfileWire& wire : c.profile_wires) {
    wire.part = r.U32(), wire.profile = r.U32(), wire.modes = r.U32(), wire.closed = r.U8() != 0;
    wire.length = r.F64(), wire.bending_stiffness = r.F64(), wire.reach = r.F64();
    wire.weights.resize(r.Count(8));
    for (double& weight : wire.weights) weight = r.F64();
  }
  c.profile_wire_motion.resize(r.Count(24));
  for (Vec3& x : c.profile_wire_motion) x = r.V3();
  if (!r.ok()) return Status::Invalid("payload", "ends before its contents do");
  if (r.left() != 0) return Status::Invalid("payload", "has bytes after its contents");
  if (Status s = ValidateSampledClip(c); !s) return s;
  *out = std::move(c);
  return Status::Ok();
}

ClipPlaybackBuffers MakeClipPlaybackBuffers(const SampledClip& c) {
  ClipPlaybackBuffers b;
  b.poses.resize(c.part_count);
  const PlaybackSizes z = PlaybackSizesOf(c);
  b.profile_loads.resize(z.profiles + c.profile_wires.size());
  b.point_loads.resize(z.points);
  b.line_loads.resize(z.lines);
  b.axial_point_loads.resize(z.axial_points);
  b.axial_line_loads.resize(z.axial_lines);
  b.wires.resize(c.wires.size());
  for (std::size_t i = 0; i < c.wires.size(); ++i) {
    const ClipWire& wire = c.wires[i];
    ClipPlaybackBuffers::Wire& out = b.wires[i];
    ModalBasis basis;
    if (!BuildModalBasis(wire.boundary, int(wire.modes), &basis)) continue;  // refused later
    out.samples.resize(wire.samples);
    for (std::size_t k = 0; k < wire.samples; ++k)
      out.samples[k] = double(k) / double(wire.samples - 1);
    out.mode_values.resize(std::size_t(wire.samples) * wire.modes);
    out.mode_slopes.resize(out.mode_values.size());
    if (!TabulateModes(basis, out.samples, out.mode_values, out.mode_slopes)) {
      out = {};
      continue;
    }
    out.displacement.resize(wire.samples);
    out.slope.resize(wire.samples);
  }
  b.profile_wires.resize(c.profile_wires.size());
  for (std::size_t i = 0; i < c.profile_wires.size(); ++i) {
    const ClipProfileWire& wire = c.profile_wires[i];
    ClipPlaybackBuffers::ProfileWire& out = b.profile_wires[i];
    ModalBasis basis;
    if (!BuildModalBasis(BoundaryCondition::kClamped, int(wire.modes), &basis)) continue;
    const std::size_t m = wire.weights.size();
    const double segments = double(wire.closed ? m : m - 1);
    out.samples.resize(m);
    for (std::size_t q = 0; q < m; ++q) out.samples[q] = double(q) / segments;
    out.mode_values.resize(m * wire.modes);
    std::vector<double> slopes(out.mode_values.size());
    if (!TabulateModes(basis, out.samples, out.mode_values, slopes)) {
      out = {};
      continue;
    }
    out.displacement.resize(m);
  }
  return b;
}

namespace {

// The profile wires' motion between frames f0 and f1 (fraction f), each appended as a
// whole-loop ProfileLoads after the clip's own.
Status SampleProfileWires(const SampledClip& c, std::size_t f0, std::size_t f1, double f,
                          ClipPlaybackBuffers* buffers) {
  ClipPlaybackBuffers& b = *buffers;
  const std::size_t stride = c.profile_wire_motion_stride();
  std::size_t offset = 0;
  for (std::size_t i = 0; i < c.profile_wires.size(); ++i) {
    const ClipProfileWire& wire = c.profile_wires[i];
    const Vec3* a = c.profile_wire_motion.data() + f0 * stride + offset;
    const Vec3* e = c.profile_wire_motion.data() + f1 * stride + offset;
    offset += std::size_t(wire.modes) + 1;
    const ModalResidual r = LerpResidual(a, e, f, wire.modes, false);
    ClipPlaybackBuffers::ProfileWire& out = b.profile_wires[i];
    if (Status s = EvaluateLoopMotion(r, wire.length, wire.bending_stiffness, out.samples,
                                      out.mode_values, wire.weights, wire.reach, out.displacement);
        !s)
      return s;
    ProfileLoads& loads = b.profile_loads[b.profile_load_count++];
    loads = ProfileLoads{};
    loads.part = wire.part, loads.profile = wire.profile;
    loads.boundary = BoundaryCondition::kClamped;
    loads.extra_displacement = out.displacement;
  }
  return Status::Ok();
}

}  // namespace

Status SampleClipJob::Validate() const {
  if (clip == nullptr) return Status::Invalid("clip", "is required");
  if (buffers == nullptr) return Status::Invalid("buffers", "are required");
  if (buffers->poses.size() != clip->part_count)
    return Status::Invalid("buffers", "were made for another clip");
  if (!std::isfinite(time)) return Status::Invalid("time", "must be finite");
  if (buffers->wires.size() != clip->wires.size())
    return Status::Invalid("buffers", "were made for another clip");
  for (std::size_t i = 0; i < clip->wires.size(); ++i)
    if (buffers->wires[i].displacement.size() != clip->wires[i].samples)
      return Status::Invalid("buffers", "were made for another clip (or a wire's modes failed)");
  if (buffers->profile_wires.size() != clip->profile_wires.size())
    return Status::Invalid("buffers", "were made for another clip");
  for (std::size_t i = 0; i < clip->profile_wires.size(); ++i)
    if (buffers->profile_wires[i].displacement.size() != clip->profile_wires[i].weights.size())
      return Status::Invalid("buffers", "were made for another clip (or a wire's modes failed)");
  return Status::Ok();
}

Status SampleClipJob::Run() const {
  if (Status s = Validate(); !s) return s;
  const SampledClip& c = *clip;
  ClipPlaybackBuffers& b = *buffers;
  const std::size_t last = c.frame_count() - 1;
  const double x =
      std::clamp(ClipLocalTime(c.loop, c.duration, time) * c.frame_rate, 0.0, double(last));
  const std::size_t f0 = std::min(std::size_t(x), last), f1 = std::min(f0 + 1, last);
  const double f = x - double(f0);
  const std::size_t parts = c.part_count;
  // Load slots: one per part and per profile key (the profile wires' entries carry no loads).
  const std::size_t slots = parts + b.profile_loads.size() - c.profile_wires.size();
  const std::size_t point_stride = b.point_loads.size() / slots;
  const std::size_t line_stride = b.line_loads.size() / slots;
  const std::size_t axial_point_stride = b.axial_point_loads.size() / parts;
  const std::size_t axial_line_stride = b.axial_line_loads.size() / parts;
  for (std::size_t p = 0; p < parts; ++p) {
    const PartKey& a = c.parts[f0 * parts + p];
    const PartKey& e = c.parts[f1 * parts + p];
    PartPose& pose = b.poses[p];
    pose.rotation = a.rotation.slerp(f, e.rotation).normalized();
    pose.translation = a.translation + f * (e.translation - a.translation);
    SpineLoads& loads = pose.loads;
    const bool same = a.boundary == e.boundary;
    loads.boundary = (same || f < 0.5) ? a.boundary : e.boundary;
    loads.tip_force = a.tip_force + f * (e.tip_force - a.tip_force);
    loads.tip_couple = a.tip_couple + f * (e.tip_couple - a.tip_couple);
    const PartKey& nearer = f < 0.5 ? a : e;
    loads.large_deflection = nearer.large_deflection;
    loads.curl_segments = int(nearer.curl_segments);
    loads.start_displacement =
        a.start_displacement + f * (e.start_displacement - a.start_displacement);
    loads.end_displacement = a.end_displacement + f * (e.end_displacement - a.end_displacement);
    loads.axial_fixed_at = a.axial_fixed_at + f * (e.axial_fixed_at - a.axial_fixed_at);
    loads.bending_point_loads = Blend(c.point_loads, a.point_loads, e.point_loads, f, same,
                                      LerpOf<PointLoad>, b.point_loads.data() + p * point_stride);
    loads.bending_line_loads = Blend(c.line_loads, a.line_loads, e.line_loads, f, same,
                                     LerpOf<LineLoad>, b.line_loads.data() + p * line_stride);
    loads.axial_point_loads =
        Blend(c.axial_point_loads, a.axial_point_loads, e.axial_point_loads, f, same,
              LerpOf<AxialPointLoad>, b.axial_point_loads.data() + p * axial_point_stride);
    loads.axial_line_loads =
        Blend(c.axial_line_loads, a.axial_line_loads, e.axial_line_loads, f, same,
              LerpOf<AxialLineLoad>, b.axial_line_loads.data() + p * axial_line_stride);
  }
  // The wires' motion beyond their static shapes: residuals interpolated, then evaluated.
  const std::size_t stride = c.wire_motion_stride();
  std::size_t offset = 0;
  for (std::size_t i = 0; i < c.wires.size(); ++i) {
    const ClipWire& wire = c.wires[i];
    const Vec3* a = c.wire_motion.data() + f0 * stride + offset;
    const Vec3* e = c.wire_motion.data() + f1 * stride + offset;
    offset += std::size_t(wire.modes) + 2;
    const ModalResidual r = LerpResidual(a, e, f, wire.modes, true);
    ClipPlaybackBuffers::Wire& out = b.wires[i];
    SpineLoads& loads = b.poses[wire.part].loads;
    ModalResidualJob job;
    job.boundary = loads.boundary;
    job.length = wire.length;
    job.bending_stiffness = wire.bending_stiffness;
    job.residual = &r;
    job.samples = out.samples;
    job.mode_values = out.mode_values;
    job.mode_slopes = out.mode_slopes;
    job.displacement = out.displacement;
    job.slope = out.slope;
    if (Status s = job.Run(); !s) return s;
    loads.extra_displacement = out.displacement;
    loads.extra_slope = out.slope;
  }
  // Profile loads: the two frames' keys pair up when they list the same profiles in the same
  // order; otherwise the nearer frame's are taken.
  const LoadRange ka = c.profile_keys_of_frame[f0], ke = c.profile_keys_of_frame[f1];
  bool paired = ka.count == ke.count;
  for (std::uint32_t i = 0; paired && i < ka.count; ++i) {
    const ProfileKey &a = c.profile_keys[ka.first + i], &e = c.profile_keys[ke.first + i];
    paired = a.part == e.part && a.profile == e.profile && a.boundary == e.boundary;
  }
  const LoadRange& own = (paired || f < 0.5) ? ka : ke;
  const double g = paired ? f : 0.0;
  b.profile_load_count = own.count;
  for (std::uint32_t i = 0; i < own.count; ++i) {
    const ProfileKey& a = c.profile_keys[own.first + i];
    const ProfileKey& e = paired ? c.profile_keys[ke.first + i] : a;
    ProfileLoads& out = b.profile_loads[i];
    out.part = a.part, out.profile = a.profile, out.boundary = a.boundary;
    out.extra_displacement = {};
    out.from = a.from + g * (e.from - a.from), out.to = a.to + g * (e.to - a.to);
    const std::size_t slot = parts + i;
    out.point_loads = Blend(c.point_loads, a.point_loads, e.point_loads, g, true, LerpOf<PointLoad>,
                            b.point_loads.data() + slot * point_stride);
    out.line_loads = Blend(c.line_loads, a.line_loads, e.line_loads, g, true, LerpOf<LineLoad>,
                           b.line_loads.data() + slot * line_stride);
  }
  return SampleProfileWires(c, f0, f1, f, &b);
}

}  // namespace wirerig
