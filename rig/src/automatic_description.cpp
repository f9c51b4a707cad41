#include "wirerig/rig/automatic_description.h"

#include <cstdio>

#include <Eigen/Eigenvalues>

#include "wirerig/rig/curve_skeleton.h"
#include "wirerig/rig/skeleton_description.h"
#include "wirerig/rig/watertight_proxy.h"

namespace wirerig {
namespace {

// A sheet's thickness against its size: below this the mesh has no volume to rig.
constexpr double kFlatRatio = 0.02;

// "" unless the welded vertices lie within kFlatRatio of their largest extent of a plane
// (principal axes of the vertex cloud).
std::string FlatnessProblem(const Mesh& mesh) {
  const std::vector<Vec3>& points = mesh.welded_positions;
  if (points.size() < 4) return "it has fewer than 4 vertices";
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p;
  mean /= double(points.size());
  Mat3 covariance = Mat3::Zero();
  for (const Vec3& p : points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(covariance);
  const Vec3 spread = solver.eigenvalues().cwiseMax(0.0).cwiseSqrt();  // ascending
  if (!(spread.z() > 0.0)) return "its vertices are all at one point";
  if (spread.x() < kFlatRatio * spread.z())
    return "it is flat (a sheet, thickness under " + std::to_string(int(kFlatRatio * 100)) +
           "% of its size): no limbs to rig";
  return {};
}

}  // namespace

namespace {

// From the surface alone: the curve skeleton of the mesh, or of its alpha wrap.
Result<AutomaticDescription> DescribeFromSurface(const Mesh& mesh,
                                                 const AutomaticOptions& options) {
  const std::string problem = WatertightProblem(mesh);
  if (problem.empty()) {
    Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
    if (!skeleton) {
      std::string message = "no skeleton, no description, and no curve skeleton: ";
      return Error{message.append(skeleton.error())};
    }
    Result<RigDescription> automatic = DescribeFromCurveSkeleton(mesh, skeleton.value());
    if (!automatic) return Error{automatic.error()};
    return AutomaticDescription{std::move(automatic).value(), "the mesh's curve skeleton",
                                std::nullopt};
  }
  // Open, non-manifold or in pieces: the skeleton and the parts from a watertight wrap; the
  // profile curves are still traced on the mesh itself. A flat sheet has no limbs to find.
  if (std::string flat = FlatnessProblem(mesh); !flat.empty()) return Error{problem + "; " + flat};
  WrapOptions wrap_options;
  wrap_options.alpha = options.wrap_alpha;
  Result<WatertightProxy> wrap = WrapWatertight(mesh, wrap_options);
  if (!wrap) return Error{problem + ", and " + wrap.error()};
  Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(wrap.value().mesh);
  if (!skeleton) return Error{problem + "; the curve skeleton of its wrap: " + skeleton.error()};
  Result<RigDescription> automatic = DescribeFromCurveSkeleton(wrap.value().mesh, skeleton.value());
  if (!automatic) return Error{automatic.error()};
  char size[128];
  std::snprintf(size, sizeof size, "alpha %.4g m, offset %.3g m, %zu holes closed, %zu triangles",
                wrap.value().alpha, wrap.value().offset, wrap.value().holes_closed,
                wrap.value().mesh.triangles.size());
  return AutomaticDescription{
      std::move(automatic).value(),
      "the curve skeleton of an alpha wrap (" + std::string(size) + "): " + problem,
      std::move(wrap).value().mesh};
}

}  // namespace

Result<AutomaticDescription> DescribeAutomatically(const Mesh& mesh,
                                                   const AutomaticOptions& options) {
  if (mesh.joints.empty() || options.ignore_skeleton) return DescribeFromSurface(mesh, options);
  Result<RigDescription> from_skeleton = DescribeFromSkeleton(mesh);
  if (!from_skeleton) return Error{from_skeleton.error()};
  const std::string joints = std::to_string(mesh.joints.size()) + " joints";
  // A skeleton of one bone makes one rigid part: the surface's own skeleton, if it has one,
  // finds the limbs.
  if (from_skeleton.value().parts.size() < 2) {
    if (std::string flat = FlatnessProblem(mesh); !flat.empty())
      return Error{"the skeleton makes a single part, and " + flat};
    Result<AutomaticDescription> surface = DescribeFromSurface(mesh, options);
    if (surface && surface.value().description.parts.size() >= 2) {
      surface.value().source += " (the file's skeleton makes a single part)";
      return surface;
    }
  }
  return AutomaticDescription{std::move(from_skeleton).value(), "the skeleton (" + joints + ")",
                              std::nullopt};
}

}  // namespace wirerig
