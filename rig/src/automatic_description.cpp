#include "wirerig/rig/automatic_description.h"

#include "wirerig/rig/curve_skeleton.h"
#include "wirerig/rig/skeleton_description.h"

namespace wirerig {

Result<AutomaticDescription> DescribeAutomatically(const Mesh& mesh) {
  if (!mesh.joints.empty()) {
    Result<RigDescription> from_skeleton = DescribeFromSkeleton(mesh);
    if (!from_skeleton) return Error{from_skeleton.error()};
    return AutomaticDescription{std::move(from_skeleton).value(),
                                "the skeleton (" + std::to_string(mesh.joints.size()) + " joints)"};
  }
  Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
  if (!skeleton) {
    std::string message = "no skeleton, no description, and no curve skeleton: ";
    return Error{message.append(skeleton.error())};
  }
  Result<RigDescription> automatic = DescribeFromCurveSkeleton(mesh, skeleton.value());
  if (!automatic) return Error{automatic.error()};
  return AutomaticDescription{std::move(automatic).value(), "the mesh's curve skeleton"};
}

}  // namespace wirerig
