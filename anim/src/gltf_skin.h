// The skin mode's skeleton and vertex influences exactly as they are written to the file (float
// values), and adding them to a tinygltf model. A joint per spine sample, numbered over the
// spines in order and samples in order (BakedAnimation's numbering); joint s > 0 of a spine is a
// child of joint s - 1, joint 0 of a child spine a child of its parent spine's `parent_joint`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "wirerig/anim/baked_animation.h"

namespace wirerig::gltf {

using Quatf = Eigen::Quaternionf;
using Mat4f = Eigen::Matrix4f;

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

// Local transforms are taken relative to the parent's world transform as reconstructed from the
// stored (float) locals, so float rounding does not accumulate along a chain.
Skeleton BuildSkeleton(const BakedAnimation& bake);

// Per vertex 4 joints and weights as written: the bake's influences with duplicate joints
// merged, sorted by decreasing weight, normalized so that the float weights sum to 1; unused
// slots are joint 0 with weight 0.
struct SkinInfluences {
  std::vector<std::uint16_t> joints;  // #V x 4
  std::vector<float> weights;         // #V x 4
};
SkinInfluences MakeSkinInfluences(const BakedAnimation& bake);

// Appends the joint nodes (their roots to `roots`, for the scene), the skin with its inverse
// bind matrices, and per joint a translation and a rotation channel (LINEAR, on
// `time_accessor`) to `animation`. Returns the skin index.
int AddSkeleton(tinygltf::Model& model, tinygltf::Animation& animation, const Skeleton& skeleton,
                int time_accessor, std::vector<int>* roots);

// Adds JOINTS_0 and WEIGHTS_0 to every primitive of mesh `mesh_index`.
void AddSkinAttributes(tinygltf::Model& model, int mesh_index, const SkinInfluences& influences,
                       std::size_t joint_count);

}  // namespace wirerig::gltf
