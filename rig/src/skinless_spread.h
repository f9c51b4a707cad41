// The skin a skinless bone moves (a clavicle: a joint and a rigid bone, no skin of its own;
// rig_description.h). Used by SpreadJointBindings after every skinned joint is spread.
//
// The bone's children carry its motion on their own skin (their joint bridges' parent ends
// ride on the bone's end, so a bridge adds only the child's turn relative to the bone). Around
// that skin, the skin of every other part within kSkinlessSpreadLengths x the bone's length
// along the surface gets u harmonic over the surface (edge weights 1 / length): 1 beside the
// children's skin, 0 at the reach's edge. Its influence on the bone's joint has bridge 0: the
// vertex follows its own side (the skinned ancestor's) and the bone's rigid motion blended by
// smoothstep(u), so a shrug lifts the top of the shoulder and fades out over the chest. Where
// smoothstep(u) < kSkinlessLeastBlend the vertex takes no influence (it keeps its slots, which
// the torso's many bridges need).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "joint_skin_spread.h"
#include "mesh_adjacency.h"
#include "wirerig/runtime/rig_model.h"

namespace wirerig {

inline constexpr double kSkinlessSpreadLengths = 1.5;
inline constexpr double kSkinlessLeastBlend = 1e-3;

// `own_samples`: per vertex, its own part's spine sample nearest it. Returns the joint
// influences lost for want of a free slot (AddJointInfluence).
LostInfluences SpreadSkinlessJoints(const Adjacency& adjacency,
                                    std::span<const std::uint32_t> own_samples, RigModel* model);

}  // namespace wirerig
