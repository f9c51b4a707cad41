// Loose pieces of a mesh (eyes, teeth, buttons: separate connected pieces much smaller than the
// body) ride rigidly on the part they sit on, instead of being skinned like flesh (used by
// BuildRigModel after the per-vertex binding).
#pragma once

#include <cstdint>
#include <vector>

#include "wirerig/rig/mesh.h"
#include "wirerig/runtime/rig_model.h"

namespace wirerig {

// A piece with at most this fraction of the welded vertices is loose (the largest never is).
inline constexpr double kLoosePieceFraction = 0.05;

struct LoosePieces {
  std::vector<std::uint8_t> loose;  // per welded vertex: 1 on a loose piece
  std::size_t pieces = 0, vertices = 0;
};

// Rebinds every loose piece's vertices rigidly (a cap binding, no joint bridges) to the profile
// frame of the part most of its vertices were bound to, nearest its centroid along the spine.
LoosePieces BindLoosePieces(const Mesh& mesh, RigModel* model);

}  // namespace wirerig
