#include "wirerig/rig/mesh_subdivision.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace wirerig {
namespace {

Mesh SubdivideOnce(const Mesh& in) {
  Mesh out;
  out.positions = in.positions;
  out.normals = in.normals;
  out.uvs = in.uvs;
  out.materials = in.materials;
  out.joints = in.joints;
  out.skin_joints = in.skin_joints;
  out.skin_weights = in.skin_weights;
  std::unordered_map<std::uint64_t, std::uint32_t> midpoints;
  midpoints.reserve(in.triangles.size() * 2);
  auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
    const auto [it, inserted] = midpoints.try_emplace(key, std::uint32_t(out.positions.size()));
    if (!inserted) return it->second;
    out.positions.push_back(0.5 * (in.positions[a] + in.positions[b]));
    if (!in.normals.empty()) {
      const Vec3 n = in.normals[a] + in.normals[b];
      out.normals.push_back(n.norm() > 0.0 ? Vec3(n.normalized()) : in.normals[a]);
    }
    if (!in.uvs.empty()) out.uvs.push_back(0.5 * (in.uvs[a] + in.uvs[b]));
    if (!in.skin_joints.empty()) {
      out.skin_joints.push_back(in.skin_joints[a]);
      out.skin_weights.push_back(in.skin_weights[a]);
    }
    return it->second;
  };
  out.triangles.reserve(in.triangles.size() * 4);
  for (const Triangle& t : in.triangles) {
    const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]),
                        ca = midpoint(t[2], t[0]);
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }
  for (MeshPart part : in.parts) {
    part.first_triangle *= 4;
    part.triangle_count *= 4;
    out.parts.push_back(part);
  }
  WeldByPosition(out);
  return out;
}

}  // namespace

Mesh SubdivideMidpoint(const Mesh& mesh, int levels) {
  Mesh out = mesh;
  for (int i = 0; i < levels; ++i) out = SubdivideOnce(out);
  if (levels <= 0 && out.weld_map.empty()) WeldByPosition(out);
  return out;
}

}  // namespace wirerig
