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
