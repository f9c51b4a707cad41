// Joints between a part and its parent: a rest frame, a type (ball, hinge, fixed), limits, and
// the skin bridge that carries the skin across the joint.
//
// Angles. A joint is posed by three angles in degrees about its own rest axes, applied in the
// order X, then Y, then Z (intrinsic): X is the hinge (first bend) axis, Y the second bend axis,
// Z runs along the child's bone. The resulting rotation, in rest world axes about the child's
// root point, is what PartPose::rotation holds for the child.
//
// The skin bridge (paper sections 3 and 5): the stretch of spine across the joint, from
// blend_length before the child's root point (on the parent's side, moved by the parent) to
// blend_length after it (moved by the child), is a wire clamped at both ends with position and
// tangent continuity (boundary family 2). Its homogeneous solution is the cubic Hermite curve
// through the two clamped ends; the tangent handles are those of the circular arc that turns
// between the two end tangents, so a rigid bend gives (to within 0.03%) a circle. The skin's
// cross-sections ride rigidly on the bridge (their perimeter is kept), turn with a rotation that
// spreads the joint's swing and twist evenly along it (no candy-wrapper), and grow in area by
// rest length / bent length so the volume between them is kept (paper section 7): evenly where
// the bend leaves room, across the bend where growing towards its inside would make the
// sections cross.
#pragma once

#include <array>
#include <cstdint>

#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

enum class JointType : int {
  kBall = 0,   // three angles
  kHinge = 1,  // the X angle only (about the hinge axis); Y and Z held at 0
  kFixed = 2,  // no rotation
};

struct JointModel {
  JointType type = JointType::kBall;
  // Rest world axes of the joint: columns X (hinge / first bend axis), Y = Z x X, Z along the
  // child's bone at its root. Orthonormal, right-handed.
  Mat3 axes = Mat3::Identity();
  Vec3 min_degrees = Vec3::Constant(-180.0);  // per axis, <= max_degrees
  Vec3 max_degrees = Vec3::Constant(180.0);
  // The parent's bone direction into the joint, rest world, unit: where the child continues
  // its parent's chain, from the parent's root point to the joint (an elbow bent at rest
  // bends its bridge too); for a limb off its parent's side, the child's own bone axis.
  Vec3 parent_axis = Vec3::UnitZ();
  // Half-length of the skin bridge, m (0: no bridge, the skin follows each side rigidly).
  double blend_length = 0.0;
  // Radius of the limb at the joint, m: the skin within it of the bone line follows the bridge
  // fully, fading out to 2 radii (set when the rig is built, used only to bind).
  double radius = 0.0;
  // The same on the parent's side (a thicker upper arm above an elbow), m; 0: radius.
  double parent_radius = 0.0;
  // How much of the bridge curve's shortening its cross-sections take up as area growth
  // (SampleJointBridge), per bend direction (GrowthDirection): 1 keeps the volume of a tube of
  // constant section along the curve; the rig builder fits each to the mesh's limb volume
  // (FitJointGrowth: an elbow bent at rest takes less, a wrist bent back more), in
  // [kMinGrowthScale, kMaxGrowthScale].
  std::array<double, 4> growth_scales = {1.0, 1.0, 1.0, 1.0};
};
inline constexpr double kMinGrowthScale = -2.0;
inline constexpr double kMaxGrowthScale = 4.0;

// The bend directions of JointModel::growth_scales: about +X, -X, +Y, -Y.
enum GrowthDirection : int { kGrowPlusX = 0, kGrowMinusX = 1, kGrowPlusY = 2, kGrowMinusY = 3 };

// The growth scale of a bend by `swing` (a rotation about an axis across the joint's Z, rest
// world axes): the directions' scales weighted by the squares of the swing axis's X and Y
// components, blended towards the four scales' mean below a few degrees of bend so that it is
// continuous through the rest pose.
double BendGrowthScale(const JointModel& joint, const Quat& swing);

// Empty reason when the joint is valid: finite orthonormal right-handed axes, limits finite with
// min <= max, blend_length and radius finite and >= 0. Fields named "axes", "limits",
// "blend_length", "radius".
Status ValidateJoint(const JointModel& joint);

// The angles clamped to the joint's limits and type (hinge: Y = Z = 0; fixed: all 0).
Vec3 ClampJointAngles(const JointModel& joint, const Vec3& degrees);

// The rotation (rest world axes) of the given angles, clamped first.
Quat JointRotation(const JointModel& joint, const Vec3& degrees);

// The swing and twist of a rotation about a unit axis: rotation = swing * twist, twist about
// `axis`, swing about an axis perpendicular to it. A half-turn swing takes twist = identity.
void SwingTwist(const Quat& rotation, const Vec3& axis, Quat* swing, Quat* twist);

// The fraction t of a unit quaternion's rotation (same axis, t times the angle, shortest way).
Quat ScaleRotation(const Quat& rotation, double t);

}  // namespace wirerig
