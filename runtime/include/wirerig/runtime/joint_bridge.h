// The skin bridge across a joint (joint.h): binding skin points to it at rest, and its shape
// each frame, sampled so the per-vertex work is two interpolations and a matrix product.
#pragma once

#include <array>

#include "wirerig/runtime/joint.h"

namespace wirerig {

// Where a rest skin point lies on a joint's bridge. u in [0, 1] runs from the parent's end
// (blend_length before the child's root point, along the child's rest bone axis) to the
// child's end; weight in [0, 1] is how fully the point follows the bridge rather than its own
// part: 1 within joint.radius * kBridgeInner of the bone line, fading smoothly to 0 at
// joint.radius * kBridgeOuter. At its ends the bridge moves exactly as the side it meets, so
// points there join their own part's skin continuously.
// A point of one side up to one more blend_length beyond the bridge's far end (a vertex its part
// claimed across the joint) binds to that end (u = 0 or 1): it follows the other side.
struct JointBinding {
  double u = 0.0;
  double weight = 0.0;  // 0: not on the bridge
};
inline constexpr double kBridgeInner = 1.25;
inline constexpr double kBridgeOuter = 2.0;

// `root` is the child's rest root point; `child_side` says which part owns the point.
JointBinding BindToJoint(const JointModel& joint, const Vec3& root, const Vec3& p, bool child_side);

// The bridge's two clamped ends for one configuration (rest or posed), world axes.
struct BridgeEnds {
  Vec3 start = Vec3::Zero();           // on the parent's side: root - blend_length * start tangent
  Vec3 start_tangent = Vec3::UnitZ();  // unit
  Vec3 end = Vec3::Zero();             // the child's spine point blend_length along it
  Vec3 end_tangent = Vec3::UnitZ();    // unit
};

// The bridge sampled at u_k = k / kBridgeSegments: each sample maps a rest point q at
// bridge coordinate u_k to q' = centre + map * (q - rest_centre).
inline constexpr int kBridgeSegments = 16;
struct BridgeSamples {
  std::array<Vec3, kBridgeSegments + 1> rest_centre;
  std::array<Vec3, kBridgeSegments + 1> centre;
  std::array<Mat3, kBridgeSegments + 1> map;
};

// Samples the bridge for a pose: `rest` and `posed` ends, and the rotations the parent's and
// the child's sides have turned by (rest world axes -> world). The rotation field spreads the
// relative turn's swing and twist (about the rest bone axis joint.axes.col(2)) evenly in u;
// the cross-sections grow in area by 1 + c 4u(1 - u), c such that the bridge keeps its rest
// volume (area x length), evenly or, where that would reach within joint.radius of the bend's
// centre of curvature, across the bend. At
// rest (posed == rest, rotations identity) every map is the identity. Allocation-free.
void SampleJointBridge(const JointModel& joint, const BridgeEnds& rest, const BridgeEnds& posed,
                       const Mat3& parent_rotation, const Mat3& child_rotation, BridgeSamples* out);

// The bridge's image of the rest-space point q at coordinate u (clamped to [0, 1]).
Vec3 ApplyJointBridge(const BridgeSamples& bridge, double u, const Vec3& q);

}  // namespace wirerig
