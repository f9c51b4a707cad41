// The poses a joint is judged in: bent alone in each direction its type allows, by 30, 60, 90
// and 120 degrees (within its limits), and twisted by 90 degrees where it can twist. Used by the
// joint-skin tests, the skinning benchmark and `wirerig rig --joint-report`.
#pragma once

#include <string>
#include <vector>

#include "wirerig/runtime/joint.h"

namespace wirerig {

struct JointSweepPose {
  std::string label;  // e.g. "x+90", "y-30", "twist+90"
  Vec3 degrees = Vec3::Zero();
};

// Angles beyond a limit are left out (not clamped), so every pose is reached exactly; a joint
// whose limits allow none of them (a fixed joint) gets none.
std::vector<JointSweepPose> JointSweep(const JointModel& joint);

}  // namespace wirerig
