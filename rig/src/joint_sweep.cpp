#include "wirerig/rig/joint_sweep.h"

#include <cmath>
#include <cstdio>
#include <span>

namespace wirerig {
namespace {

constexpr double kSteps[] = {30.0, 60.0, 90.0, 120.0};
constexpr double kTwist = 90.0;

std::string Label(const char* axis, double degrees) {
  char text[32];
  std::snprintf(text, sizeof text, "%s%+g", axis, std::round(degrees * 10.0) / 10.0);
  return text;
}

// The angles of one direction (sign) of an axis: the steps within the limit, then the limit
// itself where it falls short of the next step (a spine's 15 degrees, a neck's 45 of twist).
void AddDirection(const JointModel& joint, int axis, double sign, std::span<const double> steps,
                  const char* name, std::vector<JointSweepPose>* out) {
  const double limit = sign > 0.0 ? joint.max_degrees[axis] : -joint.min_degrees[axis];
  if (!(limit > 0.0)) return;
  double reached = 0.0;
  for (double angle : steps) {
    if (angle > limit) break;
    Vec3 degrees = Vec3::Zero();
    degrees[axis] = sign * angle;
    out->push_back({Label(name, degrees[axis]), degrees});
    reached = angle;
  }
  if (reached < steps.back() && limit > reached) {
    Vec3 degrees = Vec3::Zero();
    degrees[axis] = sign * limit;
    out->push_back({Label(name, degrees[axis]), degrees});
  }
}

}  // namespace

std::vector<JointSweepPose> JointSweep(const JointModel& joint) {
  std::vector<JointSweepPose> out;
  if (joint.type == JointType::kFixed) return out;
  const int bend_axes = joint.type == JointType::kHinge ? 1 : 2;
  const char* names[2] = {"x", "y"};
  for (int axis = 0; axis < bend_axes; ++axis)
    for (double sign : {1.0, -1.0}) AddDirection(joint, axis, sign, kSteps, names[axis], &out);
  if (joint.type == JointType::kBall) {
    const double twist[] = {kTwist};
    for (double sign : {1.0, -1.0}) AddDirection(joint, 2, sign, twist, "twist", &out);
  }
  return out;
}

}  // namespace wirerig
