// TriangleBvh: a bounding volume hierarchy over (a subset of) a mesh's triangles, for ray
// casting and closest-point queries. Build allocates; queries are const, allocation-free and
// safe to run from several threads.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "wirerig/rig/mesh.h"

namespace wirerig {

struct RayHit {
  double t = 0.0;              // distance along the (unit) ray direction, m
  std::uint32_t triangle = 0;  // index into the triangle array given to Build
  double u = 0.0, v = 0.0;     // barycentric: point = (1-u-v) a + u b + v c
  Vec3 point = Vec3::Zero();
};

struct ClosestPoint {
  Vec3 point = Vec3::Zero();
  std::uint32_t triangle = 0;
  double distance = 0.0;
};

class TriangleBvh {
 public:
  TriangleBvh() = default;

  // Builds over `triangles` of `positions` (#P by 3), restricted to the triangle indices in
  // `subset` when it is not empty. The spans must outlive the BVH. Degenerate triangles are
  // kept but never hit.
  static TriangleBvh Build(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                           std::span<const std::uint32_t> subset = {});

  // Nearest intersection with t in (t_min, t_max] along origin + t * direction (direction
  // need not be unit; t is then in units of |direction|), or nullopt. Both faces count.
  // Watertight: a ray through an edge or vertex shared by triangles hits one of them. t_max is
  // clamped to 1e300; a zero (or below 1e-150) direction hits nothing.
  std::optional<RayHit> Raycast(const Vec3& origin, const Vec3& direction, double t_min,
                                double t_max) const;

  // A fan of rays sharing their origin and plane: ray j runs from `origin` along direction_j =
  // cosines[j] * normal + sines[j] * binormal (computed exactly so), t > 0, for j < n =
  // hits.size() == cosines.size() == sines.size(), the rays' angles about the origin increasing
  // with j within one turn (e.g. the cosines and sines of 2 pi j / n). hits[j] is what
  // Raycast(origin, direction_j, 0, inf) returns: the same nearest t, and the same triangle and
  // point except where two triangles give exactly that t (a ray through their shared edge or
  // vertex), when either may be reported. One traversal of the ray tree for the whole fan
  // (triangle_bvh_fan.cpp): only the triangles reaching the fan's plane are tested, each
  // against the rays within the angular extent (with a margin) of its part within rounding of
  // the plane; the watertight test is Raycast's, operation for operation. It pays when the rays
  // outnumber the triangles the plane cuts. Fans that break the assumptions (more than
  // kMaxFanRays rays, normal and binormal (nearly) parallel, angles out of order, an origin
  // some 32 or more BVH sizes away) are cast ray by ray. Allocation-free.
  static constexpr std::size_t kMaxFanRays = 512;
  void RaycastFan(const Vec3& origin, const Vec3& normal, const Vec3& binormal,
                  std::span<const double> cosines, std::span<const double> sines,
                  std::span<std::optional<RayHit>> hits) const;

  // The closest point on any triangle of the BVH, or nullopt when the BVH is empty.
  std::optional<ClosestPoint> Closest(const Vec3& point) const;

  std::size_t triangle_count() const;

 private:
  // Binary tree, built by binned SAH; used for closest points (and its root box for rays).
  struct Node {
    Vec3 min = Vec3::Zero(), max = Vec3::Zero();  // padded bounds of its triangles
    std::uint32_t first = 0;  // leaf: first index into order_; inner: left child (right: +1)
    std::uint32_t count = 0;  // leaf: number of triangles (1..4); inner: 0
  };
  // Wide tree collapsed from the binary one, for ray casting: kRayWidth children per node.
  // Child boxes are floats in "unit" coordinates, (x - unit_centre_) / 2^unit_exponent_,
  // rounded outwards: box[side * 3 + axis][child] with side 0 the minimum, 1 the maximum.
  // Unused child slots have empty boxes.
  static constexpr int kRayWidth = 8;
  struct alignas(64) RayNode {
    float box[6][kRayWidth];
    // Inner node index, or kLeafRef | leaf index (into ray_vertices_ and ray_triangles_).
    std::uint32_t child[kRayWidth];
  };
  void BuildRayTree();

  std::span<const Vec3> positions_;
  std::span<const Triangle> triangles_;
  // Triangle indices, leaf ranges contiguous; the top bit marks degenerate triangles.
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;         // nodes_[0] is the root; empty for an empty BVH
  std::vector<RayNode> ray_nodes_;  // ray_nodes_[0] is the root; empty for an empty BVH
  // Ray triangles (the non-degenerate ones), four slots per leaf (a leaf with fewer repeats its
  // last triangle): leaf l's vertices, copied, are the 36 doubles from 36 l, two pairs of
  // triangles as [pair][vertex][axis][triangle of the pair]; its triangle indices (into the
  // triangle array) are the four from 4 l.
  std::vector<double> ray_vertices_;
  std::vector<std::uint32_t> ray_triangles_;
  double unit_centre_[3] = {0.0, 0.0, 0.0};
  int unit_exponent_ = 0;      // unit = 2^unit_exponent_ > half the root box's largest extent
  double inside_error_ = 0.0;  // bound on the rounding errors of rays starting inside
};

// Generalised winding number of `point` with respect to the triangles (Jacobson et al. 2013):
// 1 inside a closed, outward-oriented surface, 0 outside, fractional near holes. O(#F).
// Triangles whose plane contains the point add nothing, so on a closed surface it is the
// fraction of directions that enter the solid (1/2 on a flat face); finite everywhere.
double WindingNumber(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                     const Vec3& point);

}  // namespace wirerig
