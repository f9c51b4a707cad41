// The skin bridge across a joint (joint.h): binding skin points to it at rest, and its shape
// each frame, sampled so the per-vertex work is two interpolations and a matrix product.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "wirerig/runtime/joint.h"
#include "wirerig/runtime/simd_pack.h"

namespace wirerig {

// Where a rest skin point of the joint's parent or child lies on the joint's bridge. u in
// [0, 1] runs from the parent's end (blend_length before the child's root point, along the
// joint's parent axis) to the child's end. weight (1, or 0: not on the bridge) is how fully the
// joint, rather than the point's own part, moves it. bridge in [0, 1] is how much of that
// follows the swept cross-sections rather than the two sides' rigid motions blended by
// smoothstep(u): 1 within radius * kBridgeInner of the bridge curve, fading smoothly to 0 at
// radius * kBridgeOuter, where radius runs from joint.parent_radius over the parent's half
// (u <= 1/4) to joint.radius (u >= 1/2) (skin far from the limb, like a thumb by the wrist, is
// no cross-section of it). At its ends the bridge's swept sections still bend (the curve is
// curved there, and squeezed short of its centre of curvature), so a point of a side up to
// kBridgeEndFade x blend_length beyond the bridge's own end binds to that end (u = 0 or 1) with
// its bridge fading to 0 over that distance: the skin goes over from the bent sections to its
// side's rigid motion across several edges, not one. A point of one side up to `reach` beyond
// the bridge's far end (a vertex its part claimed across the joint) binds to that end (u = 0
// or 1): it follows the other side.
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
inline constexpr int kBridgeSegments = 16;  // a bridge's samples: kBridgeSegments + 1
inline constexpr double kBridgeOuter = 2.0;
inline constexpr double kBridgeEndFade = 1.0;

// The bridge's two clamped ends for one configuration (rest or posed), world axes.
struct BridgeEnds {
  Vec3 start = Vec3::Zero();           // on the parent's side: root - blend_length * start tangent
  Vec3 start_tangent = Vec3::UnitZ();  // unit
  Vec3 end = Vec3::Zero();             // the child's spine point blend_length along it
  Vec3 end_tangent = Vec3::UnitZ();    // unit
  // How the sides' flesh at the two ends is scaled in the plane across the bone (about the bone
  // line) and, at the child's end, stretched along it (1 + axial strain): 1 at rest; a
  // deformable side under axial load stretches, and scales when it keeps its volume. (The
  // start stays blend_length before the child's root: the parent's half holds its rest length.)
  double start_scale = 1.0, end_scale = 1.0;
  double end_stretch = 1.0;
};

// The rest bridge's curve sampled at u_k = k / kBridgeSegments, made once per joint (for
// binding, and for sampling the posed bridge against it).
struct RestBridge {
  BridgeEnds ends;
  std::array<Vec3, kBridgeSegments + 1> points;
  std::array<double, kBridgeSegments + 1> curvature;  // 1/m
  std::array<double, kBridgeSegments + 1> speed;      // |dX/du|, m
};
RestBridge MakeRestBridge(const BridgeEnds& rest);

// `rest`: the bridge at rest (MakeRestBridge of RestBridgeEnds); `side` says how the point's
// own part relates to the joint. u is the nearest point of the rest bridge curve (linear between
// its samples); the radius test measures the distance to it.
JointBinding BindToJoint(const JointModel& joint, const RestBridge& rest, const Vec3& p,
                         JointSide side, double reach);

// The bridge sampled at u_k = k / kBridgeSegments, for a pose, as affine images of rest points:
// a rest point q at bridge coordinate u_k goes to map q + map_offset (the section's turn, then
// its growth) and, turned alone, to turn q + turn_offset; between samples the two samples'
// images are blended linearly. Scalar is double, or float for the float evaluation.
template <class Scalar>
struct BasicBridgeSamples {
  using V = Eigen::Matrix<Scalar, 3, 1>;
  using M = Eigen::Matrix<Scalar, 3, 3>;
  struct Sample {
    M map = M::Identity();
    V map_offset = V::Zero();
    M turn = M::Identity();
    V turn_offset = V::Zero();
    V centre = V::Zero();
    // Towards the bend's centre of curvature, over the distance the section may reach towards
    // it (1/m; zero where the bridge runs straight): the inside of a bend is squeezed softly
    // short of the centre, so sections never cross.
    V inward = V::Zero();
  };
  // The two sides' motions: x -> turn * x + offset, each a rotation times its end's scale
  // across the bone (BridgeEnds::start_scale, end_scale).
  M parent_turn = M::Identity(), child_turn = M::Identity();
  V parent_offset = V::Zero(), child_offset = V::Zero();
  std::array<Sample, kBridgeSegments + 1> samples;

  template <class Other>
  BasicBridgeSamples<Other> Cast() const;
};
using BridgeSamples = BasicBridgeSamples<double>;

// Samples the bridge for a pose: `rest` and `posed` ends, and the rotations the parent's and
// the child's sides have turned by (rest world axes -> world). The rotation field spreads the
// relative turn's swing and twist (about the rest bone axis joint.axes.col(2)) evenly in u;
// the cross-sections are scaled in their plane by the ends' scales blended by smoothstep(u) and
// grow in area by 1 + c 4u(1 - u), c such that the bridge keeps the volume (area x length) of
// its flesh (the rest bridge's, with the ends' scales and the child's stretch blended alike)
// times the bend's growth scale (BendGrowthScale), evenly or, where that would reach within
// joint.radius of the bend's centre of curvature, across the bend. At rest (posed == rest,
// rotations identity, scales and stretch 1) every map is the identity. Allocation-free.
void SampleJointBridge(const JointModel& joint, const RestBridge& rest, const BridgeEnds& posed,
                       const Mat3& parent_rotation, const Mat3& child_rotation, BridgeSamples* out);

// One segment [u_k, u_k+1] of a bridge, its samples broadcast into packs (simd_pack.h), for the
// images of many rest points at once.
template <class P>
struct BridgeSegment {
  using Real = typename P::Real;
  using Value = typename P::Value;
  using V = simd::V3<Value>;
  simd::M3<P> map[2], turn[2], parent_turn, child_turn;
  V map_offset[2], turn_offset[2], centre[2], inward[2], parent_offset, child_offset;

  // Always inlined (simd_pack.h): into passes compiled for wider instruction sets too.
  [[gnu::always_inline]] BridgeSegment(const BasicBridgeSamples<Real>& bridge, int k) {
    for (int i = 0; i < 2; ++i) {
      const auto& s = bridge.samples[k + i];
      map[i] = simd::M3<P>::Splat(s.map);
      turn[i] = simd::M3<P>::Splat(s.turn);
      map_offset[i] = simd::Splat<P>(s.map_offset);
      turn_offset[i] = simd::Splat<P>(s.turn_offset);
      centre[i] = simd::Splat<P>(s.centre);
      inward[i] = simd::Splat<P>(s.inward);
    }
    parent_turn = simd::M3<P>::Splat(bridge.parent_turn);
    child_turn = simd::M3<P>::Splat(bridge.child_turn);
    parent_offset = simd::Splat<P>(bridge.parent_offset);
    child_offset = simd::Splat<P>(bridge.child_offset);
  }

  // The image of rest points q at f in [0, 1] along the segment and t = u in [0, 1] along the
  // bridge: `fraction` of the swept cross-section's motion (taking `section` of its growth), the
  // rest the two sides' motions blended by smoothstep(t); *parent_image and *child_image (if
  // given): each side's rigid motion of q.
  [[gnu::always_inline]] V Image(Value f, Value t, Value fraction, Value section, const V& q,
                                 V* parent_image, V* child_image = nullptr) const {
    const Value one = P::Broadcast(Real(1)), zero = P::Broadcast(Real(0));
    const Value g = one - f;
    V swept = g * (map[0] * q + map_offset[0]) + f * (map[1] * q + map_offset[1]);
    const V turned = g * (turn[0] * q + turn_offset[0]) + f * (turn[1] * q + turn_offset[1]);
    swept = turned + section * (swept - turned);
    // Softly short of the centre of curvature: reach r along the inward normal becomes
    // limit s / sqrt(1 + s^2), s = r / limit (1:1 near the centre line, never past the limit).
    const V in = g * inward[0] + f * inward[1];
    const Value reach = simd::Dot(in, swept - (g * centre[0] + f * centre[1]));
    const Value in2 = simd::Dot(in, in);
    const auto squeeze =
        P::And(P::Greater(reach, zero), P::Greater(in2, P::Broadcast(Real(1e-30))));
    const Value pull =
        (reach / P::Sqrt(one + reach * reach) - reach) / P::Select(squeeze, in2, one);
    swept = swept + P::Select(squeeze, pull, zero) * in;
    const V parent = parent_turn * q + parent_offset;
    const V child = child_turn * q + child_offset;
    const Value blend = t * t * (P::Broadcast(Real(3)) - P::Broadcast(Real(2)) * t);
    *parent_image = parent;
    if (child_image != nullptr) *child_image = child;
    return fraction * swept + (one - fraction) * (parent + blend * (child - parent));
  }
};

// Where u lies among the samples: segment k and the fraction f within it (u clamped to [0, 1]).
template <class Real>
void BridgeSegmentOf(Real u, int* k, Real* f) {
  const Real x = std::clamp(u, Real(0), Real(1)) * Real(kBridgeSegments);
  *k = std::min(static_cast<int>(x), kBridgeSegments - 1);
  *f = x - Real(*k);
}

// The image of the rest-space point q at coordinate u (clamped to [0, 1]): `fraction` of the
// swept cross-section's motion (taking `section` of its growth; JointBinding::section), the
// rest the two sides' motions blended by smoothstep(u). The evaluation computes the same per
// vertex with BridgeSegment.
template <class Scalar>
Eigen::Matrix<Scalar, 3, 1> ApplyJointBridge(const BasicBridgeSamples<Scalar>& bridge, Scalar u,
                                             Scalar fraction, const Eigen::Matrix<Scalar, 3, 1>& q,
                                             Scalar section = Scalar(1)) {
  int k = 0;
  Scalar f = 0;
  BridgeSegmentOf(u, &k, &f);
  const BridgeSegment<simd::OneLane<Scalar>> segment(bridge, k);
  simd::V3<Scalar> parent;
  const simd::V3<Scalar> image = segment.Image(f, std::clamp(u, Scalar(0), Scalar(1)), fraction,
                                               section, {q.x(), q.y(), q.z()}, &parent);
  return {image.x, image.y, image.z};
}

template <class Scalar>
template <class Other>
BasicBridgeSamples<Other> BasicBridgeSamples<Scalar>::Cast() const {
  BasicBridgeSamples<Other> out;
  out.parent_turn = parent_turn.template cast<Other>();
  out.child_turn = child_turn.template cast<Other>();
  out.parent_offset = parent_offset.template cast<Other>();
  out.child_offset = child_offset.template cast<Other>();
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const Sample& s = samples[k];
    auto& o = out.samples[k];
    o.map = s.map.template cast<Other>();
    o.map_offset = s.map_offset.template cast<Other>();
    o.turn = s.turn.template cast<Other>();
    o.turn_offset = s.turn_offset.template cast<Other>();
    o.centre = s.centre.template cast<Other>();
    o.inward = s.inward.template cast<Other>();
  }
  return out;
}

}  // namespace wirerig
