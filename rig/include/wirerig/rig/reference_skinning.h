// The skinning methods engines ship, run on a wire rig's bones for comparison (skin-at-joints
// benchmark and tests): linear blend skinning, dual-quaternion skinning (Kavan et al. 2008) and
// skinning with optimized centres of rotation (Le and Hodgins 2016). Written as engines write
// them: float, one flat array per attribute, at most 4 influences per vertex; linear blend
// vectorised the way ozz-animation's SkinningJob is (a bone's transform as four SIMD columns).
//
// Bones are the rig's parts; a bone's transform is its part's rigid motion (the turn of its
// spine's root frame, about its root point). Weights come from the rig's own blend region, so
// every method blends over the same skin: a vertex on a joint's skin bridge at coordinate u with
// bridge weight b gives b smoothstep(u) to the child, b (1 - smoothstep(u)) to the parent and
// 1 - b to its own part; any other vertex follows its own part alone.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {

enum class ReferenceSkinning : int { kLinearBlend = 0, kDualQuaternion = 1, kCentreOfRotation = 2 };
const char* ToString(ReferenceSkinning method);

struct ReferenceSkin {
  static constexpr int kInfluences = 4;
  std::vector<float> x, y, z;     // #W rest positions
  std::vector<float> nx, ny, nz;  // #W rest normals (area-weighted, unit)
  std::vector<std::array<std::uint16_t, kInfluences>> bones;
  std::vector<std::array<float, kInfluences>> weights;  // sum to 1; unused slots 0
  std::vector<float> cx, cy, cz;  // #W optimized centres of rotation (Le and Hodgins 2016)
};
// Weights from `model`'s joint bridges; centres of rotation by the paper's similarity
// (sigma = 0.1) over the triangles sharing a bone with the vertex.
ReferenceSkin MakeReferenceSkin(const RigModel& model, std::span<const Vec3> rest);

// One rigid transform per bone (part), float, row-major 3x4.
using BoneMatrix = std::array<float, 12>;
// The parts' rigid motions after an evaluation of `model` into `workspace`.
void BoneMatricesFromWorkspace(const RigModel& model, const RigWorkspace& workspace,
                               std::span<BoneMatrix> out);

// Deforms every vertex: positions and normals (unit) as float arrays of #W each.
struct ReferenceSkinningJob {
  ReferenceSkinning method = ReferenceSkinning::kLinearBlend;
  const ReferenceSkin* skin = nullptr;
  std::span<const BoneMatrix> bones;
  std::span<float> x, y, z, nx, ny, nz;
  void Run() const;
};

}  // namespace wirerig
