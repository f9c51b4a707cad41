// Rotation helpers shared by the motion importers (motion_import.h).
#pragma once

#include <optional>

#include "wirerig/rig/mesh_import.h"
#include "wirerig/runtime/joint.h"

namespace wirerig {

// The rotation taking a source up axis to +Y, as mesh import applies it: Z-up
// (x, y, z) -> (x, z, -y), X-up (x, y, z) -> (-y, x, z).
Mat3 SourceUpRotation(UpAxis axis);

// The least rotation taking unit vector `from` onto unit vector `to`.
Mat3 LeastRotation(const Vec3& from, const Vec3& to);

// The axis-angle vector of a rotation, chosen among its equivalent vectors (angle + 2 pi k
// about the same axis) nearest to `previous`, so a track of them stays continuous.
Vec3 ContinuousRotationVector(const Mat3& rotation, const std::optional<Vec3>& previous);

// The joint angles (degrees, X then Y then Z about the joint's rest axes, joint.h) of a turn
// given in rest world axes; Y in [-90, 90].
Vec3 JointAnglesOf(const JointModel& joint, const Mat3& turn);

// The rotation nearest to a matrix (polar decomposition, determinant +1).
Mat3 NearestRotation(const Mat3& m);

}  // namespace wirerig
