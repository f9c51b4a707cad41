#include "wirerig/runtime/rig_asset.h"

#include <algorithm>
#include <array>
#include <cstring>

#include "asset_envelope.h"
#include "byte_codec.h"

namespace wirerig {
namespace {

constexpr AssetMagic kMagic = {'W', 'R', 'I', 'G'};

// The smallest encoding of one element of each array, for bounding counts before allocating.
constexpr std::size_t kVec3Bytes = 24, kFrameBytes = 72, kTriangleBytes = 12, kIndexBytes = 4;
constexpr std::size_t kProfileBytes = 29, kPartBytes = 438, kVertexBytes = 131;

void WriteProfile(bytes::Writer& w, const ProfileModel& p) {
  w.F64(p.spine_v);
  w.U8(p.closed ? 1 : 0);
  w.Count(p.local_points.size());
  for (const Vec3& q : p.local_points) w.V3(q);
  w.F64(p.stiffness.axial), w.F64(p.stiffness.bending);
}

void WriteJoint(bytes::Writer& w, const JointModel& j) {
  w.U8(std::uint8_t(j.type));
  w.M3(j.axes);
  w.V3(j.min_degrees), w.V3(j.max_degrees), w.V3(j.parent_axis);
  w.F64(j.blend_length), w.F64(j.radius), w.F64(j.parent_radius);
  for (double growth : j.growth_scales) w.F64(growth);
}

void WritePart(bytes::Writer& w, const PartModel& p) {
  w.String(p.name);
  w.I32(p.parent);
  w.F64(p.attachment);
  w.U8(std::uint8_t(p.kind));
  w.Count(p.spine_points.size());
  for (const Vec3& q : p.spine_points) w.V3(q);
  w.Count(p.spine_frames.size());
  for (const Frame& f : p.spine_frames) w.V3(f.tangent), w.V3(f.normal), w.V3(f.binormal);
  w.F64(p.spine_length);
  w.F64(p.spine_stiffness.axial), w.F64(p.spine_stiffness.bending);
  w.F64(p.mass.volume), w.F64(p.mass.mass), w.V3(p.mass.center), w.M3(p.mass.inertia);
  w.M3(p.mass.principal_axes), w.V3(p.mass.principal_moments);
  w.Count(p.profiles.size());
  for (const ProfileModel& profile : p.profiles) WriteProfile(w, profile);
  w.F64(p.max_radius);
  WriteJoint(w, p.joint);
}

void WriteVertex(bytes::Writer& w, const VertexAttachment& a) {
  w.U32(a.part), w.U32(a.profile), w.U8(a.cap ? 1 : 0);
  const PairBinding& b = a.pair;
  w.U32(b.k1), w.F64(b.lambda1), w.U32(b.k2), w.F64(b.lambda2);
  w.F64(b.alpha), w.F64(b.beta), w.F64(b.gamma), w.V3(b.rest_normal), w.V3(b.rest_edge);
  w.U8(b.flags);
  w.V3(a.cap_local);
  // The joint influences in use (joint >= 0), preceded by their count.
  w.U8(std::uint8_t(std::count_if(a.joints.begin(), a.joints.end(),
                                  [](const JointInfluence& j) { return j.joint >= 0; })));
  for (const JointInfluence& j : a.joints) {
    if (j.joint < 0) continue;
    w.I32(j.joint), w.U32(j.sample);
    w.F64(j.u), w.F64(j.weight), w.F64(j.bridge), w.F64(j.section);
  }
}

ProfileModel ReadProfile(bytes::Reader& r) {
  ProfileModel p;
  p.spine_v = r.F64();
  p.closed = r.U8() != 0;
  p.local_points.resize(r.Count(kVec3Bytes));
  for (Vec3& q : p.local_points) q = r.V3();
  p.stiffness.axial = r.F64(), p.stiffness.bending = r.F64();
  return p;
}

JointModel ReadJoint(bytes::Reader& r) {
  JointModel j;
  j.type = JointType(r.U8());
  j.axes = r.M3();
  j.min_degrees = r.V3(), j.max_degrees = r.V3(), j.parent_axis = r.V3();
  j.blend_length = r.F64(), j.radius = r.F64(), j.parent_radius = r.F64();
  for (double& growth : j.growth_scales) growth = r.F64();
  return j;
}

PartModel ReadPart(bytes::Reader& r) {
  PartModel p;
  p.name = r.String();
  p.parent = r.I32();
  p.attachment = r.F64();
  p.kind = SpineKind(r.U8());
  p.spine_points.resize(r.Count(kVec3Bytes));
  for (Vec3& q : p.spine_points) q = r.V3();
  p.spine_frames.resize(r.Count(kFrameBytes));
  for (Frame& f : p.spine_frames) f.tangent = r.V3(), f.normal = r.V3(), f.binormal = r.V3();
  p.spine_length = r.F64();
  p.spine_stiffness.axial = r.F64(), p.spine_stiffness.bending = r.F64();
  p.mass.volume = r.F64(), p.mass.mass = r.F64(), p.mass.center = r.V3();
  p.mass.inertia = r.M3(), p.mass.principal_axes = r.M3(), p.mass.principal_moments = r.V3();
  p.profiles.resize(r.Count(kProfileBytes));
  for (ProfileModel& profile : p.profiles) profile = ReadProfile(r);
  p.max_radius = r.F64();
  p.joint = ReadJoint(r);
  return p;
}

// False when the vertex claims more joint influences than a vertex holds.
bool ReadVertex(bytes::Reader& r, VertexAttachment* out) {
  VertexAttachment& a = *out;
  a.part = r.U32(), a.profile = r.U32(), a.cap = r.U8() != 0;
  PairBinding& b = a.pair;
  b.k1 = r.U32(), b.lambda1 = r.F64(), b.k2 = r.U32(), b.lambda2 = r.F64();
  b.alpha = r.F64(), b.beta = r.F64(), b.gamma = r.F64();
  b.rest_normal = r.V3(), b.rest_edge = r.V3();
  b.flags = r.U8();
  a.cap_local = r.V3();
  const std::size_t influences = r.U8();
  if (influences > a.joints.size()) return false;
  for (std::size_t i = 0; i < influences; ++i) {
    JointInfluence& j = a.joints[i];
    j.joint = r.I32(), j.sample = r.U32();
    j.u = r.F64(), j.weight = r.F64(), j.bridge = r.F64(), j.section = r.F64();
  }
  return true;
}

}  // namespace

// Slicing-by-8 (Kounavis and Berry): eight bytes per step through eight tables, about 8x the
// bytewise loop, so checking a 4 MB asset costs little of its load time.
std::uint32_t Crc32(std::span<const std::uint8_t> data) {
  using Tables = std::array<std::array<std::uint32_t, 256>, 8>;
  static const Tables tables = [] {
    Tables t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[0][i] = c;
    }
    for (std::uint32_t i = 0; i < 256; ++i)
      for (std::size_t k = 1; k < 8; ++k) t[k][i] = (t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xFFu];
    return t;
  }();
  std::uint32_t crc = 0xFFFFFFFFu;
  const std::uint8_t* p = data.data();
  std::size_t n = data.size();
  for (; n >= 8; n -= 8, p += 8) {
    const std::uint32_t lo = crc ^ (std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 |
                                    std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24);
    crc = tables[7][lo & 0xFFu] ^ tables[6][(lo >> 8) & 0xFFu] ^ tables[5][(lo >> 16) & 0xFFu] ^
          tables[4][lo >> 24] ^ tables[3][p[4]] ^ tables[2][p[5]] ^ tables[1][p[6]] ^
          tables[0][p[7]];
  }
  for (; n > 0; --n, ++p) crc = tables[0][(crc ^ *p) & 0xFFu] ^ (crc >> 8);
  return crc ^ 0xFFFFFFFFu;
}

std::vector<std::uint8_t> SerializeRigAsset(const RigAsset& asset) {
  bytes::Writer payload;
  const RigModel& model = asset.model;
  payload.Count(model.parts.size());
  for (const PartModel& part : model.parts) WritePart(payload, part);
  payload.Count(model.vertices.size());
  for (const VertexAttachment& a : model.vertices) WriteVertex(payload, a);
  payload.Count(model.triangles.size());
  for (const Triangle& t : model.triangles) payload.U32(t[0]), payload.U32(t[1]), payload.U32(t[2]);
  payload.Count(asset.vertex_order.size());
  for (std::uint32_t v : asset.vertex_order) payload.U32(v);

  return Envelope(kMagic, kRigAssetVersion, payload.bytes());
}

Status ParseRigAsset(std::span<const std::uint8_t> bytes, RigAsset* out) {
  if (out == nullptr) return Status::Invalid("out", "is required");
  std::span<const std::uint8_t> payload;
  if (Status s = OpenEnvelope(bytes, kMagic, kRigAssetVersion,
                              "is not a wirerig rig asset (.wrig): wrong magic", &payload);
      !s)
    return s;
  bytes::Reader r(payload);
  RigAsset asset;
  RigModel& model = asset.model;
  model.parts.resize(r.Count(kPartBytes));
  for (PartModel& part : model.parts) part = ReadPart(r);
  model.vertices.resize(r.Count(kVertexBytes));
  for (std::size_t v = 0; v < model.vertices.size(); ++v)
    if (!ReadVertex(r, &model.vertices[v]))
      return Status::InvalidElement("vertices", int(v), "joints",
                                    "holds more joint influences than a vertex can");
  model.triangles.resize(r.Count(kTriangleBytes));
  for (Triangle& t : model.triangles) t = {r.U32(), r.U32(), r.U32()};
  asset.vertex_order.resize(r.Count(kIndexBytes));
  for (std::uint32_t& v : asset.vertex_order) v = r.U32();
  if (!r.ok()) return Status::Invalid("payload", "ends before its contents do");
  if (r.left() != 0) return Status::Invalid("payload", "has bytes after its contents");
  if (Status s = ValidateRigModel(model); !s) return s;
  for (std::uint32_t v : asset.vertex_order)
    if (v >= model.vertices.size())
      return Status::Invalid("vertex_order", "names a vertex the model does not have");
  *out = std::move(asset);
  return Status::Ok();
}

}  // namespace wirerig
