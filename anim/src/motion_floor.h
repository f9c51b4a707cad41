// Keeping a retargeted motion's skin above the floor (motion_mapping.h, RetargetFloor::kAbove).
#pragma once

#include "wirerig/anim/clip.h"
#include "wirerig/io/result.h"
#include "wirerig/runtime/rig_model.h"

namespace wirerig {

// Raises `root_part`'s translation keys in *clip (a clip retargeted onto `model`, the root's
// translation keyed wherever the pose is) by how far the evaluated skin's lowest point lies
// below the rest skin's lowest point (+Y up, the converted mesh frame) at each key's time; keys
// above the floor are kept. Returns the largest lift (m). Errors: the clip does not build.
Result<double> LiftAboveFloor(const RigModel& model, const std::string& root_part, RawClip* clip);

}  // namespace wirerig
