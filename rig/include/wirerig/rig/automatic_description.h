// A rig description for a mesh that comes without one: from its skeleton when it has joints
// (one part per bone), else from its curve skeleton (CGAL mean-curvature flow).
#pragma once

#include <string>

#include "wirerig/rig/mesh.h"
#include "wirerig/rig/result.h"
#include "wirerig/rig/rig_description.h"

namespace wirerig {

struct AutomaticDescription {
  RigDescription description;
  std::string source;  // for reports: "the skeleton (38 joints)" or "the mesh's curve skeleton"
};

// Errors say why neither way worked.
Result<AutomaticDescription> DescribeAutomatically(const Mesh& mesh);

}  // namespace wirerig
