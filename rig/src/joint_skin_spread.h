// Smooths each joint's skin binding over the mesh surface, so no edge carries a jump of motion
// (used by BuildRigModel after the per-vertex binding).
//
// Per joint: skin riding on the bridge as rigid cross-sections (JointInfluence::bridge at 1)
// keeps its bridge coordinate u; skin the bridge only blends (bridge < 1: far from the limb,
// like an armpit or the torso around a shoulder) and the skin of the joint's parent and its
// ancestors within kSpreadRadii x the joint's radius of it along the surface get u harmonic
// over the surface (edge weights 1 / length), with u = 0 on the parent's side and 1 on the
// child's beyond (ancestors' and siblings' skin too: it moves with the parent's side). The skin
// of parts below the child within that reach (an arm's skin beside a chest's joint) gets u too:
// it rides on the child, so it must blend as the child's skin next to it does (within
// kSiblingSpreadRadii, as siblings' skin).
// A vertex whose kJointInfluences slots hold stronger influences is left out, and a weaker one
// is displaced; the count of influences so lost is returned. Skin on a sibling joint's bridge or
// spread (between two legs) is no cross-section of either: every joint is spread twice, the second
// time knowing what every sibling's first spread reached. Siblings are joints of the same skinned
// parent (SkinParent: a shoulder hung from a clavicle is the neck's sibling). Last, skinless bones'
// joints (skinless_spread.h).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "wirerig/runtime/rig_model.h"

namespace wirerig {

inline constexpr double kSpreadRadii = 3.0;
// The share of the skinless bones' length above a joint (a clavicle's, above a shoulder) its
// spread adds to its reach. human.zae's shoulders at 90 and 120 degrees of flexion: 1 and 3
// folded edges -> 0 and 1 at 0.3 (0.5: the same folds, limb volume 0.897 against 0.901; 1:
// 0.883); any share folded the chest (2 edges, 2.9x) while a vertex held only 6 joints
// (kJointInfluences, now 8).
inline constexpr double kSkinlessSpreadShare = 0.3;
// Sibling skin within 1.25 joint radii (was 1): human.zae's hips at 120 degrees of flexion
// 4 folded edges / 2.19x stretch -> 2 / 1.79x, their adduction limit's section 0.897 -> 0.863 of
// its rest perimeter (1.1: 3 / 2.02x; 1.5: 2 / 1.80x, 0.854; 2: 4 folds).
inline constexpr double kSiblingSpreadRadii = 1.25;

// Joint influences a spread could not keep (left out, or displaced by a stronger one): their
// count and the largest share of a joint's motion one carried (AddJointInfluence's strength).
struct LostInfluences {
  std::size_t count = 0;
  double strongest = 0.0;
  LostInfluences& operator+=(const LostInfluences& other) {
    count += other.count;
    strongest = std::max(strongest, other.strongest);
    return *this;
  }
};

// Gives the vertex the influence, in a free slot or instead of its weakest influence if that
// is weaker (strength: how far the influence moves the vertex from where its own part puts it,
// weight x u on the parent's side, weight x (1 - u) on the child's: the child's skin and the
// skin of parts below it). Returns what was lost: nothing when a slot was free, else the
// influence left out or the weaker one it displaced (either way the skin may jump by that
// share of the joint's motion where a neighbour kept it).
LostInfluences AddJointInfluence(const RigModel& model, const JointInfluence& influence,
                                 VertexAttachment* a);

// `rest`: the welded rest positions of model.vertices; `own_samples`: per vertex, its own part's
// spine sample nearest it. Returns the joint influences lost for want of a free slot.
LostInfluences SpreadJointBindings(std::span<const Vec3> rest,
                                   std::span<const std::uint32_t> own_samples, RigModel* model);

}  // namespace wirerig
