// A rig description for a mesh that comes without one: from its skeleton when it has joints
// (one part per bone), else from its curve skeleton (CGAL mean-curvature flow).
#pragma once

#include <optional>
#include <string>

#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/rig/rig_description.h"

namespace wirerig {

struct AutomaticDescription {
  RigDescription description;
  std::string source;  // for reports: "the skeleton (38 joints)" or "the mesh's curve skeleton"
  std::optional<Mesh> wrap;  // the watertight stand-in the description came from, if any
};

struct AutomaticOptions {
  bool ignore_skeleton = false;  // describe from the surface even when the mesh has a skeleton
  double wrap_alpha = 0.0;       // m; 0: chosen from the mesh (watertight_proxy.h)
};

// From the mesh's skeleton if it has one; else from its curve skeleton, extracted from the mesh
// itself when it is one closed 2-manifold piece, else from its alpha wrap (watertight_proxy.h;
// `source` then says why and the wrap's size). Errors say why neither way worked.
Result<AutomaticDescription> DescribeAutomatically(const Mesh& mesh,
                                                   const AutomaticOptions& options = {});

}  // namespace wirerig
