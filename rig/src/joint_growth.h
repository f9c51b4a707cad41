// Fits each bridged joint's growth_scale (JointModel) to the mesh: the limb (limb_volume.h)
// keeps its rest volume as the joint bends.
//
// The bridge's cross-sections grow as its curve shortens; with growth_scale 1 they keep the
// volume of a tube of constant section about the curve. A real limb is no such tube (the flesh
// of an elbow lies off the bone line; a bridge bent at rest shortens less), so per joint the
// scale is the least-squares fit, over its bends (each bend axis its type allows, both ways, at
// 90 degrees or its limit if that is at least 30), of the limb's volume to rest; the volume is
// taken linear in the scale (measured at 0 and 1), clamped to [0, kMaxGrowthScale = 1]: the
// fit only takes growth away. Where a limb loses more volume than the tube (a shoulder, whose
// limb takes in the torso skin the joint spreads over), more growth would not restore it but
// stretch the skin (measured on human.zae: shoulders' worst stretch 1.90 -> 2.34 at 1.47). A
// joint whose bends do not change its volume keeps 1. Used by BuildRigModel after the skin is
// bound.
#pragma once

#include <span>

#include "wirerig/runtime/rig_model.h"

namespace wirerig {

// `rest`: the welded rest positions of model->vertices.
void FitJointGrowth(std::span<const Vec3> rest, RigModel* model);

}  // namespace wirerig
