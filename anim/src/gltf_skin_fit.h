// The skin mode's skeleton: a few joints per part, chosen among its spine samples, and their
// transforms at every key fitted to the baked vertices (a skinning decomposition in the manner
// of Dem Bones: the weights held fixed, each joint's rigid transform by weighted least squares
// with the others held, in turn; rotations from the SVD, so they stay orthonormal).
//
// Joints: a part whose spine moves rigidly over the whole bake (every sample keeps its place in
// the first sample's frame) gets one joint, at its first sample, named after the part; a
// deformable part gets up to `max_joints_per_part` joints spread evenly over its samples from
// the first to the last ("arm_0" ... "arm_6"), fewer when the skin's budget `max_joints` would
// be exceeded (every part keeps at least one). A part's first joint hangs from the joint of its
// parent part nearest before the attachment; the others from the joint before them. With
// bridge_joints, and while max_joints allows once every part has its joints, each attached
// part adds a bridge joint ("forearm_l_bridge"): a leaf under the parent's joint, at the
// child's root, starting half-way (slerp) between the two sides' transforms, so the fitted
// skin can bend across the joint as the rig's bridge does.
//
// Weights: a vertex's bake weights on spine samples (BakedAnimation::skin_joints / weights),
// each sample's weight split between the two chosen joints around it in proportion to its
// place between them (all of it when it is a chosen joint); the `influences` largest kept.
//
// Fit: every key starts from the baked spine frames at the chosen samples; `iterations` passes
// update each joint's transform in turn to minimise the squared distance of its vertices'
// skinned positions to the bake, a step kept only when it lowers that distance. Before that,
// for `weight_rounds` rounds, the weights are solved with the transforms held
// (gltf_skin_weights.h; the first round on the baked frames), each round followed by the
// transform passes with the new weights held.
//
// Then, while max_joints allows and with flesh_joints, joints for what the bones miss
// (gltf_flesh_joints.h: jiggling skin), followed by the weight rounds again.
//
// Last, each joint's track is stored (rotations as normalized shorts) and thinned within
// key_tolerance (gltf_skin.h): the skeleton holds what a reader has at every key.
#pragma once

#include <cstddef>

#include "gltf_mesh.h"
#include "gltf_skin.h"
#include "wirerig/anim/baked_animation.h"
#include "wirerig/io/result.h"

namespace wirerig::gltf {

struct SkinFitOptions {
  std::size_t max_joints = 64;          // per skin
  std::size_t max_joints_per_part = 8;  // deformable parts; 0: a joint at every spine sample
  std::size_t influences = 4;           // joints per vertex: 4 or 8 (kMaxInfluences)
  int iterations = 2;                   // fitting passes per key; 0: the baked spine frames
  int weight_rounds = 2;       // weight solves (gltf_skin_weights.h), each followed by the passes
  double key_tolerance = 0.0;  // m: joint keys thinned within it (KeyThinning); 0 keeps all
  bool bridge_joints = true;   // a joint at each part's attachment, within max_joints
  // Flesh joints (gltf_flesh_joints.h) for the vertices still missed by more than flesh_error
  // (m) after the weight rounds, within max_joints; then the weight rounds again with them in.
  bool flesh_joints = true;
  double flesh_error = 1e-3;
  bool byte_weights = false;  // weights stored as bytes (SkinInfluences)
  int translation_bits = 0;   // > 0: translation keys rounded for the EXPONENTIAL filter
  int rotation_bits = 0;      // > 0: rotation keys rounded for the QUATERNION filter
};

struct FittedSkin {
  Skeleton skeleton;
  SkinInfluences influences;
};

// `bake` must carry spines and skin weights on their samples (ExportGltf's input check). Fails
// when the parts alone need more joints than `max_joints` (or, with a joint at every sample,
// the samples do), giving the counts.
Result<FittedSkin> FitSkeleton(const BakedAnimation& bake, const BaseVertices& base,
                               const SkinFitOptions& options);

}  // namespace wirerig::gltf
