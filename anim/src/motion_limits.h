// Joint limits in retargeting (motion_import.h, docs/motion-import.md): the parts' wanted world
// rotations turned into per-part turns that stay within each joint's limits, the rotation a
// joint's limits refuse handed up its parent chain.
#pragma once

#include <vector>

#include "wirerig/runtime/joint.h"
#include "wirerig/runtime/rig_model.h"

namespace wirerig {

// `turn` (rest world axes) within the joint's type and limits: the joint angles of the turn
// (X, Y, Z, joint.h) clamped to them (ClampJointAngles); `turn` itself, and *bound false, when
// no angle passes its limit by more than 1e-9 degrees.
Mat3 ClampTurn(const JointModel& joint, const Mat3& turn, bool* bound);

// The fraction of a joint's range (from its rest angles, 0 clamped to the limits, to each
// limit) that a part handing up keeps before its parents turn: the skin holds each limit alone
// but folds where a neck sits at several at once (bent back 40, twisted 45 and turned 20).
inline constexpr double kComfortableRange = 0.75;

// The joint with its limits narrowed to kComfortableRange of its range.
JointModel ComfortableRange(const JointModel& joint);

// Whether part p hands the rotation beyond its comfortable range to its parent: p continues its
// parent's chain (`chain_child[parent] == p`: the neck below the chest, not the arms), both turn
// as balls, the parent is driven and is not the root. So the spine, neck and head share their
// turns; the root (it carries the whole body) and the limbs (a hinge's excess would swing them)
// do not: there the turn is only clamped.
std::vector<char> HandsUpToParent(const RigModel& model, const std::vector<int>& chain_child,
                                  const std::vector<char>& driven);

// Fits turns to wanted world rotations, frame by frame (buffers kept between frames).
class JointLimitFit {
 public:
  // driven[p]: part p has a wanted world rotation; an undriven part rides on its parent (turn
  // I). hands_up[p]: see HandsUpToParent. clamp false: no limits (turns are wanted exactly).
  JointLimitFit(const RigModel& model, std::vector<char> driven, std::vector<char> hands_up,
                bool clamp);

  // Parts in the model's order (parents first). The root's turn is its wanted rotation. A
  // driven child's turn is T_p = W_parent^T wanted_p, clamped to its limits; where the clamp
  // binds and p hands up, p is first clamped to its comfortable range (ComfortableRange), its
  // parent turns (within its own limits) so that p's world rotation W_parent T_p comes as near
  // wanted_p as the parent allows, what the parent cannot take goes on up while the parent hands
  // up too, and p then takes what is left, up to its own limits. Parts already fitted below a moved
  // ancestor keep their turns (their world moves with it); later parts fit against the moved
  // worlds. With single-axis excess the error left is exactly what the chain's limits cannot take.
  // Deterministic; `wanted` holds one rotation per part (ignored for undriven parts).
  void Fit(const std::vector<Mat3>& wanted);

  const std::vector<Mat3>& turns() const { return turns_; }  // rest world axes, per part
  const std::vector<Mat3>& world() const { return world_; }  // W_p = W_parent T_p

 private:
  // Ancestors of `part` (with its turn set) turn within their (comfortable) limits so that its
  // world rotation comes as near `wanted` as they allow; worlds are brought up to date.
  void HandUp(int part, const Mat3& wanted, bool comfortable);

  const RigModel& model_;
  std::vector<char> driven_, hands_up_;
  bool clamp_;
  std::vector<Mat3> turns_, world_;
};

}  // namespace wirerig
