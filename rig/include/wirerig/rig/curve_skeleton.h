// Automatic central curves for a closed mesh with neither skeleton nor description: the
// mean-curvature-flow curve skeleton (CGAL), split into parts at its branch points.
#pragma once

#include <vector>

#include "wirerig/rig/mesh.h"
#include "wirerig/rig/result.h"
#include "wirerig/rig/rig_description.h"

namespace wirerig {

// The curve skeleton as a graph of polylines between nodes (branch points and ends).
struct CurveSkeleton {
  std::vector<Vec3> nodes;
  struct Branch {
    int from = -1, to = -1;    // node indices
    std::vector<Vec3> points;  // polyline from nodes[from] to nodes[to], inclusive
  };
  std::vector<Branch> branches;
};

// Needs a welded, closed mesh (refuses otherwise, saying why).
Result<CurveSkeleton> ExtractCurveSkeleton(const Mesh& mesh);

// Parts from the skeleton: the root is the branch that carries the most others (a torso);
// other branches hang from it. Names parts by shape for quadrupeds and bipeds ("torso",
// "head", "tail", "leg_front_left", ...; "branch_N" when unsure). Central curves run from the
// attachment towards the free end.
Result<RigDescription> DescribeFromCurveSkeleton(const Mesh& mesh, const CurveSkeleton& skeleton);

}  // namespace wirerig
