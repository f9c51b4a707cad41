// Morph targets, one per key, and the `weights` animation that shows target k at key k.
#pragma once

#include <cstddef>
#include <span>

#include <tiny_gltf.h>

namespace wirerig::gltf {

// Adds #K morph targets to every primitive of mesh `mesh_index`, all primitives sharing the same
// accessors: `position_deltas` #K x #V x 3 (key-major, with min/max as glTF requires) and
// `normal_deltas` of the same size or empty. Sets the mesh's default weights (all 0) and its
// extras.targetNames ("key_<k>").
void AddMorphTargets(tinygltf::Model& model, int mesh_index, std::span<const float> position_deltas,
                     std::span<const float> normal_deltas, std::size_t key_count);

// Adds to `animation` a LINEAR sampler on `time_accessor` (#K key times) and a channel animating
// the `weights` of `node`: at key k weight k is 1 and the others 0, so between keys k and k + 1
// the mesh blends linearly from target k to target k + 1.
void AddKeyWeightsChannel(tinygltf::Model& model, tinygltf::Animation& animation, int node,
                          int time_accessor, std::size_t key_count);

}  // namespace wirerig::gltf
