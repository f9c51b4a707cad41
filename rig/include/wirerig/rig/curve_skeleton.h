// Automatic central curves for a closed mesh with neither skeleton nor description: the
// mean-curvature-flow curve skeleton (CGAL), split into parts at its branch points.
#pragma once

#include <vector>

#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/rig/rig_description.h"

namespace wirerig {

// The curve skeleton as a graph of polylines between nodes (branch points and ends). Nodes are
// the skeleton vertices of degree other than 2; a closed loop without any gets one node, its
// branch then starting and ending there (from == to).
struct CurveSkeleton {
  std::vector<Vec3> nodes;
  struct Branch {
    int from = -1, to = -1;    // node indices
    std::vector<Vec3> points;  // polyline from nodes[from] to nodes[to], inclusive
  };
  std::vector<Branch> branches;
};

// Needs a welded, closed mesh: every welded edge in exactly two triangles, run once each way
// (refuses otherwise, saying why). A vertex where separate fans of triangles touch is split.
// Every skeleton point lies inside the surface (points where the contraction cut across a
// crease are moved just inside). Deterministic; about 0.4 s for a 3k-vertex mesh.
Result<CurveSkeleton> ExtractCurveSkeleton(const Mesh& mesh);

// Parts from the skeleton, +Y up. Short leaf branches (ears, horns, toes, bumps) are dropped;
// the root "torso" is the thick, central branch between two junction regions; every other
// branch hangs from the part it leaves, its central curve starting at the attachment and
// running towards the free end (free ends are extended to 80% of the way to the surface).
// Names by shape: a quadruped (horizontal torso, four branches ending near the ground) gets
// "head" (the thicker of the two ends along the torso), "tail", "leg_front_left",
// "leg_front_right", "leg_back_left", "leg_back_right", its torso running from the hips
// forwards, left being the animal's own left (up x front: -Z for a head towards +X); a biped
// (upright torso, two branches ending near the ground) gets "head", "arm_left", "arm_right",
// "leg_left", "leg_right", assumed to face +Z (left = +X; -Z when its feet spread along Z),
// its torso running upwards; everything else is "branch_N". Arms and legs are chains: each is
// split at its sharpest bend between 30% and 70% of its length (over 15 degrees), else at its
// narrowest point there, else in the middle, into an upper and a lower segment (a biped's
// "upper_arm_l"/"forearm_l", "thigh_l"/"shin_l" and _r; a quadruped's "leg_front_left_upper"/
// "leg_front_left_lower", ...), the lower hanging from the upper. Profile counts keep their
// defaults; the mesh path, import options and vertex_part are left empty.
Result<RigDescription> DescribeFromCurveSkeleton(const Mesh& mesh, const CurveSkeleton& skeleton);

}  // namespace wirerig
