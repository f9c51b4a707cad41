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
  std::vector<Vec3f> translations;       // #K x #J local, key-major
  std::vector<Quatf> rotations;          // #K x #J local, key-major, same hemisphere per joint
  std::vector<Mat4f> inverse_bind;       // #J: inverse of the rest joint-to-world transform
  std::size_t JointCount() const { return parent.size(); }
};

// The skeleton of joints with parents `parent` (parents first) and names `names`, at rest at the
// world transforms `rest` (#J) and at key k at keyed[k * #J + j]. Local transforms are taken
// relative to the parent's world transform as reconstructed from the stored (float) locals, so
// float rounding does not accumulate along a chain; consecutive rotation keys of a joint are
// kept in one hemisphere (slerp takes the short way).
Skeleton MakeSkeleton(std::vector<int> parent, std::vector<std::string> names,
                      std::span<const RigidTransform> rest, std::span<const RigidTransform> keyed);

// Per vertex 4 joints and weights as written: sorted by decreasing weight, normalized so that
// the float weights sum to 1; unused slots are joint 0 with weight 0.
struct SkinInfluences {
  std::vector<std::uint16_t> joints;  // #V x 4
  std::vector<float> weights;         // #V x 4
};
// Appends one vertex's influences from (joint, weight) pairs (distinct joints, weights >= 0,
// some positive): the 4 largest kept and normalized.
void AppendInfluences(std::vector<std::pair<std::uint32_t, double>> pairs,
                      SkinInfluences* influences);

// Appends the joint nodes (their roots to `roots`, for the scene), the skin with its inverse
// bind matrices, and per joint a translation and a rotation channel (LINEAR, on
// `time_accessor`) to `animation`. Returns the skin index.
int AddSkeleton(tinygltf::Model& model, tinygltf::Animation& animation, const Skeleton& skeleton,
                int time_accessor, std::vector<int>* roots);

// Adds JOINTS_0 and WEIGHTS_0 to every primitive of mesh `mesh_index`.
void AddSkinAttributes(tinygltf::Model& model, int mesh_index, const SkinInfluences& influences,
                       std::size_t joint_count);

}  // namespace wirerig::gltf
