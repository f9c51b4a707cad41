// The poses a joint is judged in: bent alone in each direction its type allows, by 30, 60, 90
// and 120 degrees within its limits and to the limit itself where it falls short of the next of
// them, and twisted by 90 degrees (or to its twist limit, if less) where it can twist; so a
// joint whose limits are all below 30 degrees (a chest's) is still judged at them. Used by the
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

// Every pose lies within the limits, so it is reached exactly; a fixed joint, or a direction
// whose limit is 0, gets none.
std::vector<JointSweepPose> JointSweep(const JointModel& joint);

}  // namespace wirerig
