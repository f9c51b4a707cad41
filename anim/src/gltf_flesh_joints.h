// Flesh joints: joints for what the skeleton's bones cannot do, found from the bake (as Dem Bones
// finds its bones, by clustering vertex paths). Jiggling skin (profile wires swinging on each
// step) moves each loop of a limb along its own damped oscillation: no bone follows it, and a
// few corrective shapes cannot carry dozens of loops ringing at their own frequencies. A joint
// that hangs from the bone and moves with a loop's oscillation can, with weights that fall off
// around the loop as the swing does.
//
// The vertices the skin still misses by more than `min_error` at some key are clustered by the
// shape of their residual paths (cosine similarity over the keys: a joint moves its vertices
// alike up to their weights); each cluster of at least kMinFleshMembers vertices becomes a joint
// under the joint that moves its vertices most, at rest at their centroid with that joint's
// rest rotation, starting at each key from the rigid fit (Kabsch) of its vertices' rest
// positions to the bake. The caller then fits weights and transforms with the new joints in.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "gltf_mesh.h"
#include "gltf_skin.h"
#include "wirerig/anim/baked_animation.h"

namespace wirerig::gltf {

inline constexpr std::size_t kMinFleshMembers = 6;

struct FleshJoints {
  std::vector<int> parent;           // #N: an existing joint
  std::vector<RigidTransform> rest;  // #N world rest frames
  std::vector<Mat3> rotation;        // #K x #N skinning transforms x -> R x + t, key-major
  std::vector<Vec3> translation;     // #K x #N
  std::size_t Count() const { return parent.size(); }
};

// At most `budget` flesh joints for the skin `influences` whose #K x #J skinning transforms are
// `rotation`, `translation` (key-major) and whose joints' rest frames are `rest` (#J).
FleshJoints FindFleshJoints(const SkinInfluences& influences, const BaseVertices& base,
                            const BakedAnimation& bake, std::span<const RigidTransform> rest,
                            std::span<const Mat3> rotation, std::span<const Vec3> translation,
                            std::size_t budget, double min_error);

}  // namespace wirerig::gltf
