#include "limb_volume.h"

#include "wirerig/rig/skin_quality.h"

namespace wirerig {

Limb LimbOf(const RigModel& model, std::size_t c, std::span<const std::uint32_t> surface_border) {
  std::vector<std::uint8_t> in_subtree(model.parts.size(), 0);
  in_subtree[c] = 1;
  for (std::size_t i = c + 1; i < model.parts.size(); ++i)
    if (model.parts[i].parent >= 0 && in_subtree[std::size_t(model.parts[i].parent)])
      in_subtree[i] = 1;
  Limb limb;
  limb.flags.assign(model.vertices.size(), 0);
  for (std::size_t v = 0; v < model.vertices.size(); ++v) {
    const VertexAttachment& a = model.vertices[v];
    limb.flags[v] = in_subtree[a.part] || a.OnJoint(int(c));
  }
  std::vector<std::uint8_t> border(model.vertices.size(), 0);
  for (const Triangle& t : model.triangles) {
    const int inside = limb.flags[t[0]] + limb.flags[t[1]] + limb.flags[t[2]];
    if (inside == 0 || inside == 3) continue;
    for (std::uint32_t v : t) border[v] |= limb.flags[v];
  }
  for (std::size_t v = 0; v < border.size(); ++v)
    if (border[v]) limb.border.push_back(std::uint32_t(v));
  limb.surface_border.assign(surface_border.begin(), surface_border.end());
  return limb;
}

double LimbVolume(const Limb& limb, std::span<const Vec3> positions,
                  std::span<const Triangle> triangles) {
  Vec3 apex = Vec3::Zero();
  for (std::uint32_t v : limb.border) apex += positions[v];
  if (!limb.border.empty()) apex /= double(limb.border.size());
  return RegionVolume(positions, triangles, limb.flags, apex);
}

double LimbVolumeRatio(const Limb& limb, std::span<const Vec3> rest, std::span<const Vec3> posed,
                       std::span<const Triangle> triangles) {
  const double rest_volume = LimbVolume(limb, rest, triangles);
  if (rest_volume == 0.0) return 1.0;
  if (const std::optional<double> change =
          SurfaceVolumeChange(rest, posed, triangles, limb.surface_border))
    return 1.0 + *change / rest_volume;
  return LimbVolume(limb, posed, triangles) / rest_volume;
}

}  // namespace wirerig
