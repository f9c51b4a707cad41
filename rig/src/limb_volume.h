// The limb of a joint and its volume, for the joint-skin report and the bridge's growth fit.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "wirerig/runtime/rig_model.h"

namespace wirerig {

// The child's side of the joint of part `c`: the vertices of c and its descendants and those on
// c's bridge (`flags`), and the region's border (its vertices on a triangle that leaves it).
// `surface_border`: SurfaceBorder(model.triangles) (skin_quality.h), made once per model.
struct Limb {
  std::vector<std::uint8_t> flags;
  std::vector<std::uint32_t> border;
  // The model's surface border: vertices of its edges not on exactly two triangles (holes,
  // seams). While they stay put, the limb's change of volume is exact (LimbVolumeRatio).
  std::vector<std::uint32_t> surface_border;
};
Limb LimbOf(const RigModel& model, std::size_t c, std::span<const std::uint32_t> surface_border);

// The limb's volume in `positions`, m^3: its triangles closed by the cone to the middle of its
// border (a nearly flat cap across the limb where it meets the body).
double LimbVolume(const Limb& limb, std::span<const Vec3> positions,
                  std::span<const Triangle> triangles);

// The limb's volume in `posed` over its volume in `rest`. While the surface's border stays put
// (a closed surface, or holes away from the joint's skin) the change of volume is the whole
// surface's (exact by the divergence theorem: a bend changes the volume only around its
// joint), over the limb's rest volume; otherwise the ratio of the two LimbVolumes (whose cone
// cap across the limb moves with the limb's border, which need not be one loop).
double LimbVolumeRatio(const Limb& limb, std::span<const Vec3> rest, std::span<const Vec3> posed,
                       std::span<const Triangle> triangles);

}  // namespace wirerig
