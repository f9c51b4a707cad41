// Topological and geometric statistics of a welded mesh.
#include "wirerig/rig/mesh_statistics.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "disjoint_sets.h"

namespace wirerig {
namespace {

MeshStatistics Compute(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                       double diagonal) {
  MeshStatistics stats;
  stats.vertices = points.size();
  stats.triangles = triangles.size();
  const double area_threshold = 1e-12 * diagonal * diagonal;
  const std::size_t n = points.size();

  std::vector<std::uint64_t> edges;  // (low << 32) | high
  edges.reserve(3 * triangles.size());
  std::vector<bool> used(n, false);
  DisjointSets sets(n);
  for (const Triangle& t : triangles) {
    if (t[0] >= n || t[1] >= n || t[2] >= n) {
      ++stats.degenerate_triangles;  // names a vertex that does not exist
      continue;
    }
    for (const std::uint32_t v : t) used[v] = true;
    sets.Union(t[0], t[1]);
    sets.Union(t[1], t[2]);
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      // A repeated vertex: no surface, so its "edges" are not counted.
      ++stats.degenerate_triangles;
      continue;
    }
    const Vec3& a = points[t[0]];
    const Vec3& b = points[t[1]];
    const Vec3& c = points[t[2]];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    if (area <= area_threshold) ++stats.degenerate_triangles;
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t u = t[k];
      const std::uint64_t v = t[(k + 1) % 3];
      edges.push_back(u < v ? (u << 32) | v : (v << 32) | u);
    }
  }

  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    const std::size_t uses = j - i;
    if (uses == 1) ++stats.boundary_edges;
    if (uses >= 3) ++stats.non_manifold_edges;
    i = j;
  }

  for (std::uint32_t v = 0; v < n; ++v) {
    if (used[v] && sets.Find(v) == v) ++stats.connected_components;
  }
  return stats;
}

}  // namespace

MeshStatistics ComputeMeshStatistics(const Mesh& mesh) {
  const bool welded = mesh.weld_map.size() == mesh.positions.size() &&
                      mesh.welded_triangles.size() == mesh.triangles.size() &&
                      (mesh.positions.empty() || !mesh.welded_positions.empty());
  MeshStatistics stats;
  if (welded) {
    stats = Compute(mesh.welded_positions, mesh.welded_triangles, ComputeBounds(mesh).Diagonal());
  } else {
    // Not welded (or stale): weld a copy exactly rather than report render-vertex seams.
    Mesh copy;
    copy.positions = mesh.positions;
    copy.triangles = mesh.triangles;
    WeldByPosition(copy, 0.0);
    stats = Compute(copy.welded_positions, copy.welded_triangles, ComputeBounds(copy).Diagonal());
  }
  stats.render_vertices = mesh.positions.size();
  return stats;
}

}  // namespace wirerig
