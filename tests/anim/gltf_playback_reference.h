// What a glTF viewer must draw of an ExportGltf file at any time, computed in double from the
// BakedAnimation it was exported from (not from the file, and sharing no code with the
// exporter): the reference the three.js reader test compares three's positions with.
//
// Keys are at the bake's times rounded to float (as the file stores them); at time t between
// keys k and k + 1, u = (t - t_k) / (t_{k+1} - t_k), and before the first or after the last key
// the end key holds.
//  * Morph: the rest plus weights (1 - u, u) of the two keys' deltas = the linear blend of the
//    two baked positions.
//  * Skin: each joint's local transform (parent^-1 * world, from the baked spine frames) at both
//    keys, rotation slerped the short way and translation lerped, then composed down the chain
//    to G_j(t); a vertex p goes to sum_i w_i G_{j_i}(t) B_{j_i}^-1 p, where B_j is joint j's rest
//    world transform and (j_i, w_i) the bake's influences (normalized).
//  * Skin with residual targets: the same applied to p + (1 - u) r_k + u r_{k+1}, where the
//    residual r_k = A_k^-1 (bake_k - M_k p) makes the skinned vertex equal the bake at key k
//    (M_k = [A_k b_k] the vertex's blended matrix at key k; bake_k - M_k p where |det A_k| <
//    1e-9, as glTF export documents).
#pragma once

#include <vector>

#include "wirerig/anim/baked_animation.h"
#include "wirerig/rig/mesh.h"

namespace wirerig::testing {

enum class GltfPlayback { kMorph, kSkin, kSkinResidual };

// The bake's key times as the file stores them: rounded to float, as doubles (#K).
std::vector<double> FloatKeyTimes(const BakedAnimation& bake);

// The world position of every render vertex of `mesh` (#V, the bake's vertex order) at time `t`
// (s) of an export of `bake` played as `playback`. Skin modes need the bake's spines and skin.
std::vector<Vec3> GltfPositionsAt(const Mesh& mesh, const BakedAnimation& bake,
                                  GltfPlayback playback, double t);

}  // namespace wirerig::testing
