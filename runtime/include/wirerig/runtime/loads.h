// Loads on a wire. Positions are the wire parameter v in [0, 1] (s = L v); forces are in
// newtons, line loads in newtons per metre of wire. Lateral (bending) loads are vectors and
// every component is solved independently (linear, small deflection; only the components
// normal to the wire have physical meaning). Axial loads are scalars along +v.
#pragma once

#include "wirerig/runtime/conventions.h"

namespace wirerig {

// A concentrated lateral force at v = at.
struct PointLoad {
  double at = 0.0;            // v in [0, 1]
  Vec3 force = Vec3::Zero();  // N
};

// A uniform lateral line load over v in [from, to], from < to.
struct LineLoad {
  double from = 0.0;                     // v in [0, 1]
  double to = 1.0;                       // v in [0, 1]
  Vec3 force_per_length = Vec3::Zero();  // N/m of wire
};

// A lateral line load varying linearly over v in [from, to], from < to: start_force_per_length
// at v = from, end_force_per_length at v = to, straight in between (a trapezoid; a triangle when
// one end is zero), none outside. LineLoad is the special case start = end. Examples: the
// inertial load of a wire whose support turns (it grows with the distance from the support),
// a load tapering along a limb.
struct LinearLineLoad {
  double from = 0.0;                           // v in [0, 1]
  double to = 1.0;                             // v in [0, 1]
  Vec3 start_force_per_length = Vec3::Zero();  // N/m of wire, at v = from
  Vec3 end_force_per_length = Vec3::Zero();    // N/m of wire, at v = to
};

// A concentrated axial force at v = at, positive along +v (towards v = 1).
struct AxialPointLoad {
  double at = 0.0;     // v in [0, 1]
  double force = 0.0;  // N
};

// A uniform axial line load over v in [from, to], from < to, positive along +v.
struct AxialLineLoad {
  double from = 0.0;              // v in [0, 1]
  double to = 1.0;                // v in [0, 1]
  double force_per_length = 0.0;  // N/m of wire
};

}  // namespace wirerig
