// The skin bridge across a joint (joint.h): binding skin points to it at rest, and its shape
// each frame, sampled so the per-vertex work is two interpolations and a matrix product.
#pragma once

#include <array>

#include "wirerig/runtime/joint.h"

namespace wirerig {

// Where a rest skin point of the joint's parent or child lies on the joint's bridge. u in
// [0, 1] runs from the parent's end (blend_length before the child's root point, along the
// joint's parent axis) to the child's end. weight (1, or 0: not on the bridge) is how fully the
// joint, rather than the point's own part, moves it. bridge in [0, 1] is how much of that
// follows the swept cross-sections rather than the two sides' rigid motions blended by
// smoothstep(u): 1 within radius * kBridgeInner of the bridge curve, fading smoothly to 0 at
// radius * kBridgeOuter, where radius runs from joint.parent_radius over the parent's half
// (u <= 1/4) to joint.radius (u >= 1/2) (skin far from the limb, like a thumb by the wrist, is
// no cross-section of it). At its ends the bridge moves exactly as the side it meets, so points
// there join their own part's skin continuously. A point of one side up to `reach` beyond the
// bridge's far end (a vertex its part claimed across the joint) binds to that end (u = 0 or 1):
// it follows the other side.
enum class JointSide : int { kParent, kChild };
// section in (0, 1] is the share of the swept cross-section's growth (the bridge keeping its
// volume) the point takes: 1 within the limb's radius, radius / distance beyond (flesh around
// the limb, like a buttock by a hip, is not squeezed out with it).
struct JointBinding {
  double u = 0.0;
  double weight = 0.0;  // 0: not on the bridge
  double bridge = 0.0;
  double section = 1.0;
};
inline constexpr double kBridgeInner = 1.25;
inline constexpr int kBridgeSegments = 32;  // a bridge's samples: kBridgeSegments + 1
inline constexpr double kBridgeOuter = 2.0;

// The bridge's two clamped ends for one configuration (rest or posed), world axes.
struct BridgeEnds {
  Vec3 start = Vec3::Zero();           // on the parent's side: root - blend_length * start tangent
  Vec3 start_tangent = Vec3::UnitZ();  // unit
  Vec3 end = Vec3::Zero();             // the child's spine point blend_length along it
  Vec3 end_tangent = Vec3::UnitZ();    // unit
};

// The rest bridge's curve sampled at u_k = k / kBridgeSegments, made once per joint for binding.
struct RestBridge {
  BridgeEnds ends;
  std::array<Vec3, kBridgeSegments + 1> points;
};
RestBridge MakeRestBridge(const BridgeEnds& rest);

// `rest`: the bridge at rest (MakeRestBridge of RestBridgeEnds); `side` says how the point's
// own part relates to the joint. u is the nearest point of the rest bridge curve (linear between
// its samples); the radius test measures the distance to it.
JointBinding BindToJoint(const JointModel& joint, const RestBridge& rest, const Vec3& p,
                         JointSide side, double reach);

// The bridge sampled at u_k = k / kBridgeSegments: each sample maps a rest point q at
// bridge coordinate u_k to q' = centre + map * (q - rest_centre).
struct BridgeSamples {
  // The two sides' rigid motions: x -> turn * x + offset.
  Mat3 parent_turn = Mat3::Identity(), child_turn = Mat3::Identity();
  Vec3 parent_offset = Vec3::Zero(), child_offset = Vec3::Zero();
  std::array<Vec3, kBridgeSegments + 1> rest_centre;
  std::array<Vec3, kBridgeSegments + 1> centre;
  std::array<Mat3, kBridgeSegments + 1> map;   // the section's turn, then its growth
  std::array<Mat3, kBridgeSegments + 1> turn;  // the section's turn alone
  // Towards the bend's centre of curvature, over the distance the section may reach towards
  // it (1/m; zero where the bridge runs straight): the inside of a bend is squeezed softly
  // short of the centre, so sections never cross.
  std::array<Vec3, kBridgeSegments + 1> inward;
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

// The image of the rest-space point q at coordinate u (clamped to [0, 1]): `fraction` of the
// swept cross-section's motion (taking `section` of its growth; JointBinding::section), the
// rest the two sides' motions blended by smoothstep(u).
Vec3 ApplyJointBridge(const BridgeSamples& bridge, double u, double fraction, const Vec3& q,
                      double section = 1.0);

}  // namespace wirerig
