// The weight step of the skin's decomposition (as in Dem Bones): with every joint's skinning
// transform at every key held, each vertex's weights are solved to reproduce its baked path.
// Candidates are the joints the vertex has and their parents, children and siblings (so the
// skin across a joint can blend both sides and the joint's bridge joint, as the wire rig's
// bridges do); the weights are the non-negative
// least squares solution over all keys with their sum held to 1, a faint pull towards the
// starting weights where the path cannot tell joints apart, and the 4 largest kept.
#pragma once

#include <span>
#include <vector>

#include "gltf_mesh.h"
#include "gltf_skin.h"
#include "wirerig/anim/baked_animation.h"
#include "wirerig/runtime/parallel.h"

namespace wirerig::gltf {

// `rotation` / `translation`: #K x #J skinning transforms, key-major (x -> R x + t maps the
// rest mesh to key k). `parent`: #J, the skeleton's parents. Returns new influences (#V).
// Vertices are solved in tasks through `parallel` (none: on this thread), each alone, so the
// result does not depend on the threads.
SkinInfluences FitWeights(const SkinInfluences& start, const std::vector<int>& parent,
                          const BaseVertices& base, const BakedAnimation& bake,
                          std::span<const Mat3> rotation, std::span<const Vec3> translation,
                          const ParallelFor* parallel = nullptr);

// Vertex v at rest `r` moved by one key's skinning transforms (#J each): sum_j w_j (R_j r + t_j).
Vec3 SkinnedByTransforms(const SkinInfluences& influences, std::size_t v, const Vec3& r,
                         std::span<const Mat3> rotation, std::span<const Vec3> translation);

// Sum over the keys and vertices of the squared distance of the skinned rest mesh to the bake
// (`rotation` / `translation` as for FitWeights).
double SquaredSkinError(const SkinInfluences& influences, const BaseVertices& base,
                        const BakedAnimation& bake, std::span<const Mat3> rotation,
                        std::span<const Vec3> translation);

}  // namespace wirerig::gltf
