// The skin a skinless bone moves (a clavicle: a joint and a rigid bone, no skin of its own;
// rig_description.h). Used by SpreadJointBindings after every skinned joint is spread.
//
// The bone's children carry its motion: their skin, and the skin their joint bridges move
// (the chest's skin on a shoulder's bridge: each such bridge's parent end rides on the bone's
// end), follow the bone fully (u = 1 on its joint). Around them, the skin of every other part
// within kSkinlessSpreadLengths x the bone's length along the surface gets u harmonic over the
// surface (edge weights 1 / length): 1 beside that carried skin, 0 at the reach's edge. Its
// influence on the bone's joint has bridge 0: the vertex follows its own side (the skinned
// ancestor's) and the bone's rigid motion blended by smoothstep(u), so a shrug lifts the top
// of the shoulder and fades out over the chest.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "mesh_adjacency.h"
#include "wirerig/runtime/rig_model.h"

namespace wirerig {

inline constexpr double kSkinlessSpreadLengths = 2.0;

// `own_samples`: per vertex, its own part's spine sample nearest it. Returns the vertices left
// out for want of a free influence slot.
std::size_t SpreadSkinlessJoints(const Adjacency& adjacency,
                                 std::span<const std::uint32_t> own_samples, RigModel* model);

}  // namespace wirerig
