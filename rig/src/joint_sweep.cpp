#include "wirerig/rig/joint_sweep.h"

namespace wirerig {

std::vector<JointSweepPose> JointSweep(const JointModel& joint) {
  std::vector<JointSweepPose> out;
  if (joint.type == JointType::kFixed) return out;
  const int bend_axes = joint.type == JointType::kHinge ? 1 : 2;
  const char* names[2] = {"x", "y"};
  for (int axis = 0; axis < bend_axes; ++axis)
    for (double sign : {1.0, -1.0})
      for (double angle : {30.0, 60.0, 90.0, 120.0}) {
        Vec3 degrees = Vec3::Zero();
        degrees[axis] = sign * angle;
        if (degrees[axis] < joint.min_degrees[axis] || degrees[axis] > joint.max_degrees[axis])
          continue;
        out.push_back(
            {std::string(names[axis]) + (sign > 0 ? "+" : "-") + std::to_string(int(angle)),
             degrees});
      }
  if (joint.type == JointType::kBall)
    for (double sign : {1.0, -1.0}) {
      const Vec3 degrees(0.0, 0.0, 90.0 * sign);
      if (degrees.z() < joint.min_degrees.z() || degrees.z() > joint.max_degrees.z()) continue;
      out.push_back({sign > 0 ? "twist+90" : "twist-90", degrees});
    }
  return out;
}

}  // namespace wirerig
