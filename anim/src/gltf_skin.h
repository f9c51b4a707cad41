// The skin mode's skeleton and vertex influences exactly as they are written to the file (float
// values), and adding them to a tinygltf model. Which joints there are and how they move is
// decided by gltf_skin_fit.h.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

#include "wirerig/anim/baked_animation.h"

namespace wirerig::gltf {

using Quatf = Eigen::Quaternionf;
using Mat4f = Eigen::Matrix4f;

// A rigid transform in double: x -> rotation x + translation.
struct RigidTransform {
  Quat rotation = Quat::Identity();
  Vec3 translation = Vec3::Zero();
  RigidTransform Compose(const RigidTransform& local) const {
    return {rotation * local.rotation, translation + rotation * local.translation};
  }
  // The transform `local` with Compose(local) == world.
  RigidTransform LocalOf(const RigidTransform& world) const {
    const Quat inverse = rotation.conjugate();
    return {inverse * world.rotation, inverse * (world.translation - translation)};
  }
};

struct Skeleton {
  std::vector<int> parent;  // #J: parent joint, or -1 for a root; parents come first
  std::vector<std::string> names;
  std::vector<Vec3f> rest_translations;  // #J local (relative to the parent joint), m
  std::vector<Quatf> rest_rotations;     // #J local
  // #K x #J local transforms, key-major, as a reader has them at every key: at the keys a
  // joint's track stores (`keys`) the stored values (translation float, rotation a normalized
  // signed short per component), between them the reader's interpolation (lerp, slerp).
  // Consecutive rotations of a joint are in one hemisphere (slerp takes the short way).
  std::vector<Vec3f> translations;
  std::vector<Quatf> rotations;
  std::vector<std::vector<std::uint32_t>> keys;  // #J: stored keys, increasing, first and last
  std::vector<Mat4f> inverse_bind;               // #J: inverse of the rest joint-to-world
  std::size_t JointCount() const { return parent.size(); }
  std::size_t StoredKeyCount() const;  // over all joints
};

// How MakeSkeleton thins each joint's track: a key is left out when interpolating its
// neighbours reproduces it within `tolerance`, measured as the joint's translation error plus
// its rotation error (radians) times `reach[j]`, the farthest distance of a vertex it moves
// from its origin. A child's locals are taken against the parent as a reader reconstructs it,
// so the errors do not add up along a chain. Tolerance 0 keeps every key.
struct KeyThinning {
  std::span<const float> times;   // #K key times as stored, s
  double tolerance = 0.0;         // m
  std::span<const double> reach;  // #J, m
  int translation_bits = 0;       // > 0: through the EXPONENTIAL filter, at most these bits
  int rotation_bits = 0;          // > 0: rotations stored through the QUATERNION filter
};

// The skeleton of joints with parents `parent` (parents first) and names `names`, at rest at the
// world transforms `rest` (#J) and at key k at keyed[k * #J + j]. Local transforms are taken
// relative to the parent's world transform as reconstructed from the stored locals, so
// rounding and thinning do not accumulate along a chain.
Skeleton MakeSkeleton(std::vector<int> parent, std::vector<std::string> names,
                      std::span<const RigidTransform> rest, std::span<const RigidTransform> keyed,
                      const KeyThinning& thinning);

// Per vertex `slots` (4 or 8) joints and weights as written: sorted by decreasing weight, stored
// as normalized unsigned shorts that sum to exactly 65535 over all slots (weights q / 65535) or,
// with byte_weights, unsigned bytes summing to 255 (q / 255: within 0.5 / 255 of the fitted
// weight, as gltfpack stores them); unused slots are joint 0 with weight 0. Slots 0-3 are
// JOINTS_0 / WEIGHTS_0, 4-7 JOINTS_1 / WEIGHTS_1.
inline constexpr std::size_t kMaxInfluences = 8;  // slots per vertex: 4 (default) or 8
struct SkinInfluences {
  std::size_t slots = 4;
  bool byte_weights = false;
  std::vector<std::uint16_t> joints;  // #V x slots
  std::vector<float> weights;         // #V x slots, the stored q / 65535 (or q / 255)
  // What the stored integers of a vertex sum to: 65535, or 255 with byte_weights.
  std::uint32_t WeightTotal() const { return byte_weights ? 255u : 65535u; }
};
// Appends one vertex's influences from (joint, weight) pairs (distinct joints, weights >= 0,
// some positive): the `influences->slots` largest kept and normalized.
void AppendInfluences(std::vector<std::pair<std::uint32_t, double>> pairs,
                      SkinInfluences* influences);

// Appends the joint nodes (their roots to `roots`, for the scene), the skin with its inverse
// bind matrices, and per joint a translation and a rotation channel (LINEAR) on its stored keys
// to `animation`: `time_accessor` (all #K `times`) when it keeps every key, else an input of
// its own, shared by joints keeping the same keys. The inverse bind matrices are written times
// `stored_to_rest` (the positions' dequantization, PositionQuantization). Returns the skin index.
int AddSkeleton(tinygltf::Model& model, tinygltf::Animation& animation, const Skeleton& skeleton,
                std::span<const float> times, int time_accessor, std::vector<int>* roots,
                const Eigen::Matrix4d& stored_to_rest = Eigen::Matrix4d::Identity());

// Adds JOINTS_0 and WEIGHTS_0 (and JOINTS_1, WEIGHTS_1 with 8 slots) to every primitive of mesh
// `mesh_index`.
void AddSkinAttributes(tinygltf::Model& model, int mesh_index, const SkinInfluences& influences,
                       std::size_t joint_count);

}  // namespace wirerig::gltf
