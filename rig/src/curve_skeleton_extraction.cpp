// Curve skeleton extraction (CGAL mean curvature flow); the parts described from it live in
// curve_skeleton.cpp. Built only with WIRERIG_WITH_CGAL (without_cgal.cpp stands in otherwise).
//
// All CGAL includes live in this file: CGAL is header-only and heavy to compile, and its
// Surface_mesh_skeletonization package (GPL-3.0-or-later) stays an implementation detail.
// Needs CGAL_EIGEN3_ENABLED (the contraction solves sparse systems with Eigen) and links GMP and
// MPFR (the Delaunay triangulation used for the medial poles has exact constructions).
#include "wirerig/rig/curve_skeleton.h"

#include "wirerig/io/finite.h"
#include "wirerig/io/floating_point_hold.h"
#include "wirerig/rig/watertight_proxy.h"

#include <fenv.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/extract_mean_curvature_flow_skeleton.h>

namespace wirerig {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using CgalPoint = Kernel::Point_3;
using CgalMesh = CGAL::Surface_mesh<CgalPoint>;
using Skeletonization = CGAL::Mean_curvature_flow_skeletonization<CgalMesh>;
using CgalSkeleton = Skeletonization::Skeleton;
using MesoSkeleton = Skeletonization::Meso_skeleton;  // CGAL's working copy (a Polyhedron_3)
using MesoEdge = boost::graph_traits<MesoSkeleton>::edge_descriptor;

}  // namespace
}  // namespace wirerig

// Determinism. CGAL's edge collapse keeps its candidate edges in a std::set<edge_descriptor>,
// which orders Polyhedron_3 edges by the address of their halfedges, so the collapse order and
// hence the skeleton depended on the heap's history (the same mesh gave 17 or 20 nodes depending
// on earlier allocations in the process). This specialisation orders them by halfedge id
// instead; ContractUntilConvergence numbers the halfedges in list order before every collapse
// pass, so the ids are unique and deterministic. Addresses only break ties between distinct
// edges with equal ids, which the numbering rules out.
namespace std {
template <>
struct less<wirerig::MesoEdge> {
  bool operator()(const wirerig::MesoEdge& x, const wirerig::MesoEdge& y) const {
    const auto hx = x.halfedge(), hy = y.halfedge();
    const std::size_t kx = std::min(hx->id(), hx->opposite()->id());
    const std::size_t ky = std::min(hy->id(), hy->opposite()->id());
    if (kx != ky) return kx < ky;
    const std::less<const void*> address;
    const void* ax = address(&*hx, &*hx->opposite()) ? &*hx : &*hx->opposite();
    const void* ay = address(&*hy, &*hy->opposite()) ? &*hy : &*hy->opposite();
    return address(ax, ay);
  }
};
}  // namespace std

namespace wirerig {
namespace {

// Skeletonization::contract_until_convergence(), with the halfedges numbered before each
// collapse pass (see std::less<MesoEdge> above).
void ContractUntilConvergence(Skeletonization& skeletonization, double original_area) {
  auto& meso = const_cast<MesoSkeleton&>(skeletonization.meso_skeleton());
  double last_area = 0.0;
  for (std::size_t iteration = 0;;) {
    skeletonization.contract_geometry();
    std::size_t id = 0;
    for (auto h = meso.halfedges_begin(); h != meso.halfedges_end(); ++h) h->id() = id++;
    skeletonization.collapse_edges();
    skeletonization.split_faces();
    skeletonization.detect_degeneracies();
    const double area = CGAL::Polygon_mesh_processing::area(meso);
    if (std::abs(last_area - area) / original_area < skeletonization.area_variation_factor()) {
      break;
    }
    last_area = area;
    if (++iteration >= skeletonization.max_iterations()) break;
  }
}

// The contracted skeleton can cut across a concave crease (between a leg and the belly, say)
// and leave the surface for a short stretch. Such points move to just inside the surface,
// beyond their nearest surface point, so that every skeleton point is inside the mesh (rays
// cast from central curves need that). Points still outside after the largest step stay.
void PullInside(const CgalMesh& mesh, std::vector<Vec3>& points) {
  using Inside = CGAL::Side_of_triangle_mesh<CgalMesh, Kernel>;
  Inside::AABB_tree tree(faces(mesh).first, faces(mesh).second, mesh);
  const Inside inside(tree);
  const CGAL::Bbox_3 box = tree.bbox();
  const double diagonal =
      std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                CGAL::square(box.zmax() - box.zmin()));
  bool accelerated = false;
  for (Vec3& point : points) {
    const CgalPoint p(point.x(), point.y(), point.z());
    if (inside(p) == CGAL::ON_BOUNDED_SIDE) continue;
    if (!accelerated) {
      tree.accelerate_distance_queries();
      accelerated = true;
    }
    const CgalPoint q = tree.closest_point(p);
    const Vec3 nearest(q.x(), q.y(), q.z());
    Vec3 inward = nearest - point;
    const double norm = inward.norm();
    if (!(norm > 0.0)) continue;
    inward /= norm;
    for (const double step : {0.002, 0.005, 0.01, 0.02}) {
      const Vec3 moved = nearest + step * diagonal * inward;
      if (inside(CgalPoint(moved.x(), moved.y(), moved.z())) == CGAL::ON_BOUNDED_SIDE) {
        point = moved;
        break;
      }
    }
  }
}

// The surface handed to CGAL: only the vertices that triangles use, and a vertex of its own
// for every fan of triangles around a pinched vertex (two closed sheets touching at a point,
// as when a file repeats a vertex that welding then merges). Needs ClosedManifoldProblem to have
// passed: then the link of every vertex (b -> c for each triangle (v, b, c)) is a permutation,
// and each of its cycles is one fan.
struct FanSplitMesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
};

FanSplitMesh SplitFans(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles) {
  const std::size_t vertex_count = positions.size();
  // Corners grouped by vertex: (link source, link target, corner = 3 * triangle + k).
  struct Corner {
    std::uint32_t from, to;
    std::size_t corner;
    bool operator<(const Corner& other) const { return from < other.from; }
  };
  std::vector<std::size_t> first(vertex_count + 1, 0);
  for (const Triangle& t : triangles) {
    for (std::uint32_t v : t) ++first[v + 1];
  }
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<Corner> corners(first.back());
  std::vector<std::size_t> fill(first.begin(), first.end() - 1);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    for (int k = 0; k < 3; ++k) {
      corners[fill[t[k]]++] = {t[(k + 1) % 3], t[(k + 2) % 3], 3 * f + static_cast<std::size_t>(k)};
    }
  }

  FanSplitMesh result;
  result.triangles = triangles;
  std::vector<std::uint32_t> new_index(vertex_count, 0);
  std::vector<char> used(vertex_count, 0);
  for (const Triangle& t : triangles) {
    for (std::uint32_t v : t) used[v] = 1;
  }
  for (std::size_t v = 0; v < vertex_count; ++v) {
    if (!used[v]) continue;
    new_index[v] = static_cast<std::uint32_t>(result.positions.size());
    result.positions.push_back(positions[v]);
  }
  for (Triangle& t : result.triangles) {
    for (std::uint32_t& v : t) v = new_index[v];
  }
  std::vector<char> visited(corners.size(), 0);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const auto begin = corners.begin() + static_cast<std::ptrdiff_t>(first[v]);
    const auto end = corners.begin() + static_cast<std::ptrdiff_t>(first[v + 1]);
    if (begin == end) continue;
    std::sort(begin, end);
    bool first_fan = true;
    for (auto start = begin; start != end; ++start) {
      if (visited[start - corners.begin()]) continue;
      std::uint32_t index = new_index[v];
      if (!first_fan) {
        index = static_cast<std::uint32_t>(result.positions.size());
        result.positions.push_back(positions[v]);
      }
      first_fan = false;
      // Walk the cycle through `start`.
      auto at = start;
      while (!visited[at - corners.begin()]) {
        visited[at - corners.begin()] = 1;
        result.triangles[at->corner / 3][at->corner % 3] = index;
        at = std::lower_bound(begin, end, Corner{at->to, 0, 0});
        if (at == end) break;  // cannot happen once ClosedManifoldProblem passed
      }
    }
  }
  return result;
}

// Turns the skeleton graph into nodes (vertices of degree != 2) and the polylines between
// them. Deterministic: nodes in increasing vertex order, branches in order of their first node
// and its neighbours. A cycle without any node gets its lowest vertex as a node.
CurveSkeleton ToCurveSkeleton(const std::vector<Vec3>& points,
                              const std::vector<std::vector<std::size_t>>& adjacency) {
  const std::size_t n = points.size();
  CurveSkeleton result;
  std::vector<int> node_of(n, -1);
  for (std::size_t v = 0; v < n; ++v) {
    if (adjacency[v].size() != 2) {
      node_of[v] = static_cast<int>(result.nodes.size());
      result.nodes.push_back(points[v]);
    }
  }
  // Each undirected edge is walked once.
  std::map<std::pair<std::size_t, std::size_t>, bool> walked;
  auto edge_key = [](std::size_t a, std::size_t b) {
    return std::make_pair(std::min(a, b), std::max(a, b));
  };
  auto walk_from = [&](std::size_t start) {
    for (std::size_t next : adjacency[start]) {
      if (walked[edge_key(start, next)]) continue;
      CurveSkeleton::Branch branch;
      branch.from = node_of[start];
      branch.points.push_back(points[start]);
      std::size_t previous = start, at = next;
      walked[edge_key(previous, at)] = true;
      while (node_of[at] < 0) {
        branch.points.push_back(points[at]);
        const std::size_t following =
            adjacency[at][0] == previous ? adjacency[at][1] : adjacency[at][0];
        previous = at;
        at = following;
        walked[edge_key(previous, at)] = true;
      }
      branch.points.push_back(points[at]);
      branch.to = node_of[at];
      result.branches.push_back(std::move(branch));
    }
  };
  for (std::size_t v = 0; v < n; ++v) {
    if (node_of[v] >= 0) walk_from(v);
  }
  // Cycles made only of degree-2 vertices.
  for (std::size_t v = 0; v < n; ++v) {
    if (node_of[v] >= 0 || adjacency[v].size() != 2) continue;
    if (walked[edge_key(v, adjacency[v][0])]) continue;
    node_of[v] = static_cast<int>(result.nodes.size());
    result.nodes.push_back(points[v]);
    walk_from(v);
  }
  return result;
}

}  // namespace

Result<CurveSkeleton> ExtractCurveSkeleton(const Mesh& mesh) {
  if (mesh.welded_triangles.empty()) {
    if (!mesh.triangles.empty()) {
      return Error{"curve skeleton: the mesh is not welded (call WeldByPosition first)"};
    }
    return Error{"curve skeleton: the mesh has no triangles"};
  }
  const std::vector<Vec3>& positions = mesh.welded_positions;
  const std::vector<Triangle>& triangles = mesh.welded_triangles;
  if (std::string why = ClosedManifoldProblem(positions, triangles); !why.empty()) {
    return Error{"curve skeleton: " + why};
  }

  const FanSplitMesh surface = SplitFans(positions, triangles);
  CgalMesh cgal_mesh;
  for (const Vec3& p : surface.positions) cgal_mesh.add_vertex(CgalPoint(p.x(), p.y(), p.z()));
  for (std::size_t f = 0; f < surface.triangles.size(); ++f) {
    const Triangle& t = surface.triangles[f];
    if (cgal_mesh.add_face(CgalMesh::Vertex_index(t[0]), CgalMesh::Vertex_index(t[1]),
                           CgalMesh::Vertex_index(t[2])) == CgalMesh::null_face()) {
      return Error{"curve skeleton: triangle " + std::to_string(f) +
                   " cannot join the surface (not 2-manifold)"};
    }
  }

  const double area = CGAL::Polygon_mesh_processing::area(cgal_mesh);
  if (!(area > 0.0) || !std::isfinite(area)) {
    return Error{"curve skeleton: the mesh has no area (all its triangles are degenerate)"};
  }

  CgalSkeleton skeleton;
  try {
    ScopedFloatingPointHold hold;
    Skeletonization skeletonization(cgal_mesh);
    // Both weights raised from CGAL's defaults (0.1 and 0.2): the contraction then follows the
    // surface and the medial axis more closely. With the defaults the skeleton cut across
    // concave creases (16 of 291 cow skeleton points, 37 of 140 cactus points outside the
    // mesh) and stopped short of thin tips; with 0.5 none of the cow's or cactus's points leave
    // the mesh, for about 1.4x the time.
    skeletonization.set_quality_speed_tradeoff(0.5);
    skeletonization.set_medially_centered_speed_tradeoff(0.5);
    ContractUntilConvergence(skeletonization, area);
    skeletonization.convert_to_skeleton(skeleton);
  } catch (const std::exception& e) {
    return Error{std::string("curve skeleton: CGAL failed: ") + e.what()};
  }

  const std::size_t n = boost::num_vertices(skeleton);
  if (n == 0) return Error{"curve skeleton: CGAL returned an empty skeleton"};
  std::vector<Vec3> points(n);
  for (std::size_t v = 0; v < n; ++v) {
    const CgalPoint& p = skeleton[v].point;
    points[v] = Vec3(p.x(), p.y(), p.z());
    if (!IsFinite(points[v])) {
      return Error{"curve skeleton: CGAL produced a non-finite skeleton point (degenerate mesh?)"};
    }
  }
  try {
    ScopedFloatingPointHold hold;
    PullInside(cgal_mesh, points);
  } catch (const std::exception& e) {
    return Error{std::string("curve skeleton: CGAL failed: ") + e.what()};
  }
  std::vector<std::vector<std::size_t>> adjacency(n);
  for (auto [e, e_end] = boost::edges(skeleton); e != e_end; ++e) {
    const std::size_t a = boost::source(*e, skeleton), b = boost::target(*e, skeleton);
    if (a == b) continue;
    adjacency[a].push_back(b);
    adjacency[b].push_back(a);
  }
  for (auto& neighbours : adjacency) {
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
  }
  return ToCurveSkeleton(points, adjacency);
}

}  // namespace wirerig
