// BuildSpineSkin: linear-blend skin weights of a mesh's render vertices on the spine joints of a
// BakedAnimation (a joint per spine sample, numbered over the parts in order and each part's
// samples in order; sample s of a part with n spine points sits at v = s / (n - 1)).
//
// Where a vertex sits on its part's spine, from the rig's binding (RigModel::vertices):
//  * between profiles i and i + 1: the rest welded position (Mesh::welded_positions) projected
//    onto the rest spine polyline (RigModel spine_points), restricted to the stretch between the
//    two profiles' spine_v. The projection follows the vertex's actual place along the stretch
//    (a vertex next to profile i moves with profile i), which the pair binding's alpha, beta,
//    gamma do not give directly.
//  * a cap (beyond an end profile): the end profile's spine_v, bound rigidly to the nearest
//    sample, as the cap moves rigidly with that profile's frame.
// A vertex at spine parameter v, u = v (n - 1) in sample units, weighs sample s by the tent
// max(0, 1 - |u - s| / spread), normalized; the 4 largest are kept. spread = 1 is linear
// interpolation between the two samples around u; a wider tent spreads the weight over up to 4
// samples (docs/gltf-export.md gives the measured skinning error of each).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "wirerig/anim/baked_animation.h"
#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/runtime/rig_model.h"

namespace wirerig {

struct SpineSkinOptions {
  double spread = 1.0;  // tent half-width in sample spacings, in [1, 2]
};

struct SpineSkin {
  std::vector<std::array<std::uint32_t, 4>> joints;  // #V render vertices; unused slots 0
  std::vector<Vec4f> weights;                        // #V, sum to 1, decreasing; unused 0
};

// `model` must be built on `mesh` (one attachment per welded vertex). Refuses, naming the field:
// a spread outside [1, 2]; mesh.weld_map not of #V entries or pointing beyond the welded
// vertices; model.vertices not one per welded vertex; an attachment whose part or profile is out
// of range; a part with fewer than 2 spine points, or with 1 profile (skinless bones have
// none); non-finite rest positions.
Result<SpineSkin> BuildSpineSkin(const RigModel& model, const Mesh& mesh,
                                 const SpineSkinOptions& options = {});

}  // namespace wirerig
