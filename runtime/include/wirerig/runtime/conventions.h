// wirerig conventions: read once, they hold for every runtime header.
//
// UNITS        SI throughout: metres (m), newtons (N), pascals (Pa), kilograms (kg),
//              seconds (s). Line loads are N/m, stiffness EA is N, EI is N*m^2.
// AXES         glTF: right-handed, +Y up, +Z towards the viewer, 1 unit = 1 m.
// PARAMETER    A wire's parameter v lies in [0, 1] and is proportional to arc length:
//              s = L * v for a wire of physical length L (PHYSICS.md section 0).
// VECTORS      Vec3 is a column vector of doubles (Eigen::Vector3d).
// QUATERNIONS  Quat is Eigen::Quaterniond: constructed as (w, x, y, z), stored in memory
//              as (x, y, z, w), which is also glTF's component order. Unit length.
// MATRICES     Column-major (Eigen's default, also glTF's and OpenGL's); they act on
//              column vectors: p' = M * p.
// ANGLES       Radians.
// TRIANGLES    Counter-clockwise seen from outside: outward normals by the right-hand rule.
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace wirerig {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;
// Three vertex indices, counter-clockwise seen from outside (outward-facing).
using Triangle = std::array<std::uint32_t, 3>;

}  // namespace wirerig
