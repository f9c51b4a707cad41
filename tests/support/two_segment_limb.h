// A procedural limb for joint tests: a rig description of a 1 m limb along +Y as two segments
// jointed at its middle, for MakeCapsule(radius, 1.0, ...).
#pragma once

#include "wirerig/rig/rig_description.h"

namespace wirerig::testing {

// "upper" (the root, from y = 0.95 down to 0.5) and "lower" (its child, from 0.5 down to 0.05),
// ten profiles each; the joint's first axis is +X.
inline RigDescription TwoSegmentLimb() {
  RigDescription description;
  PartDescription upper, lower;
  upper.name = "upper";
  upper.central_curve = {Vec3(0, 0.95, 0), Vec3(0, 0.5, 0)};
  upper.profile_count = 10;
  lower = upper;
  lower.name = "lower";
  lower.parent = "upper";
  lower.central_curve = {Vec3(0, 0.5, 0), Vec3(0, 0.05, 0)};
  lower.joint.axis = Vec3::UnitX();
  description.parts = {upper, lower};
  return description;
}

// The same limb with a skinless bone ("bone", "skin": false, from y = 0.55 down to 0.45) between
// "upper" (from 0.95 down to 0.55) and "lower" (from 0.45 down to 0.05); both joints' first
// axis is +X.
inline RigDescription SkinlessBoneLimb() {
  RigDescription description = TwoSegmentLimb();
  description.parts[0].central_curve = {Vec3(0, 0.95, 0), Vec3(0, 0.55, 0)};
  PartDescription bone;
  bone.name = "bone";
  bone.parent = "upper";
  bone.skin = false;
  bone.profile_count = bone.points_per_profile = 0;
  bone.central_curve = {Vec3(0, 0.55, 0), Vec3(0, 0.45, 0)};
  bone.joint.axis = Vec3::UnitX();
  description.parts[1].parent = "bone";
  description.parts[1].central_curve = {Vec3(0, 0.45, 0), Vec3(0, 0.05, 0)};
  description.parts.insert(description.parts.begin() + 1, bone);
  return description;
}

}  // namespace wirerig::testing
