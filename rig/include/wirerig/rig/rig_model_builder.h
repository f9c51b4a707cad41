// BuildRigModel: turns a rig file's rig and its mesh into the runtime's RigModel (computed
// once): spines sampled at equal arc length with rotation-minimizing frames, profiles in their
// spine frames, mass properties from the closed surface the profiles span, and a binding for
// every welded vertex (between the two profiles around its projection on the spine, or
// rigidly to the end profile for the end caps). Each joint gets its rest frame, type and limits
// from the rig's joint description and a skin bridge (joint_bridge.h) of half-length
// min(kBlendRadii (kBranchBlendRadii for a limb off its parent's side) x the limb's radius at
// the joint, kBlendMaxFraction x the child's bone (from the joint to its farthest child's
// joint, or along its spine where that is longer), kBlendMaxFraction x the distance from the
// joint to the parent's own joint, if the parent has one) unless the description sets one, so
// the bridges of a chain never overlap;
// vertices near it are bound to it. A vertex lying around another part's spine (at most
// kNearer times as far from it as from its own, within kAroundRadii of its radius) follows it.
#pragma once

#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/rig/rig.h"
#include "wirerig/runtime/rig_model.h"

namespace wirerig {

inline constexpr double kBlendRadii = 2.5;
// A limb branching off its parent's side (a shoulder, a hip): a shorter bridge, so it sweeps
// less of the torso.
inline constexpr double kBranchBlendRadii = 1.5;
inline constexpr double kBlendMaxFraction = 0.45;
// A skinless bone's bridge (a blend of its sides' rigid motions): this fraction of its bone.
inline constexpr double kSkinlessBlendFraction = 0.5;
// A skinless bone's mass is a solid rod this fraction of its length in radius.
inline constexpr double kSkinlessRodRadius = 0.1;

struct RigModelOptions {
  int min_spine_samples = 16;  // samples per spine: max(this, 4 x profiles)
  SpineKind spine_kind = SpineKind::kDeformable;
};

struct RigModelReport {
  std::size_t cap_vertices = 0;           // beyond the first or last profile
  std::size_t fallback_vertices = 0;      // the pair binding refused: bound rigidly instead
  std::size_t flagged_vertices = 0;       // the pair binding used a documented fallback
  std::size_t bridged_vertices = 0;       // follow a joint's skin bridge
  std::size_t reowned_vertices = 0;       // beyond their part's end, around a neighbour's bone
  double strongest_lost_influence = 0.0;  // the largest share of a joint's motion one carried
  std::size_t lost_joint_influences = 0;  // a joint's spread left out or displaced: no free slot
  std::size_t loose_pieces = 0;           // small separate pieces riding rigidly on a part
  std::size_t loose_vertices = 0;
};

struct BuiltRigModel {
  RigModel model;
  RigModelReport report;
};

// How far outside the mesh's box a rig's geometry may lie, in box diagonals.
inline constexpr double kRigReach = 1.0;

// The mesh must be the one the rig was built on (same welded counts), and the rig's geometry
// (every curve point) must lie within the mesh's box grown by kRigReach x its diagonal: a rig
// file point of 2e9 m is refused, naming the part and the point.
Result<BuiltRigModel> BuildRigModel(const Mesh& mesh, const Rig& rig,
                                    const RigModelOptions& options = {});

// What of a built model follows from its rig's wire properties (materials and sections): each
// part's spine stiffness and mass properties and its profiles' stiffness. For a rig whose wire
// properties changed after `model` was built from it (same parts and profiles): the model is
// then as BuildRigModel would make it, without binding the mesh again.
void SetWireProperties(const Rig& rig, RigModel* model);

}  // namespace wirerig
