// Fits each bridged joint's growth scales (JointModel::growth_scales) to the mesh: the limb
// (limb_volume.h) keeps its rest volume as the joint bends.
//
// The bridge's cross-sections grow as its curve shortens; with scale 1 they keep the volume of a
// tube of constant section about the curve. A real limb is no such tube: the flesh of an elbow
// lies off the bone line (a bridge bent at rest shortens less), a wrist bent back squeezes the
// palm's skin into the forearm's, and the two ways of a bend differ. So per joint and bend
// direction (+X, -X, +Y, -Y) the scale is the least-squares fit, over the direction's poses of
// the joint sweep (joint_sweep.h: 30, 60, 90, 120 degrees and the limit), of the limb's volume
// to rest; the volume is taken linear in the scale (measured at 0 and 1), clamped to
// [kMinGrowthScale, kMaxGrowthScale]. Growth stretches the skin around the bend, so a fit that
// folds more edges than the tube's scale or stretches an edge beyond both 1.9x and the tube's
// worst is taken back towards 1 by bisection (measured on human.zae before the back-off: a
// shoulder's worst stretch 1.90 -> 2.34 at scale 1.47). A direction with no poses keeps 1.
// Used by BuildRigModel after the skin is bound.
#pragma once

#include <span>

#include "wirerig/runtime/rig_model.h"

namespace wirerig {

// `rest`: the welded rest positions of model->vertices.
void FitJointGrowth(std::span<const Vec3> rest, RigModel* model);

}  // namespace wirerig
