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

namespace wirerig::gltf {

// `rotation` / `translation`: #K x #J skinning transforms, key-major (x -> R x + t maps the
// rest mesh to key k). `parent`: #J, the skeleton's parents. Returns new influences (#V).
SkinInfluences FitWeights(const SkinInfluences& start, const std::vector<int>& parent,
                          const BaseVertices& base, const BakedAnimation& bake,
                          std::span<const Mat3> rotation, std::span<const Vec3> translation);

}  // namespace wirerig::gltf
