// Topological and geometric statistics of a welded mesh.
#pragma once

#include <cstddef>

#include "wirerig/rig/mesh.h"

namespace wirerig {

struct MeshStatistics {
  std::size_t vertices = 0;  // welded
  std::size_t render_vertices = 0;
  std::size_t triangles = 0;
  std::size_t connected_components = 0;  // over welded vertices that triangles use
  std::size_t boundary_edges = 0;        // edges used by exactly one triangle
  std::size_t non_manifold_edges = 0;    // edges used by three or more triangles
  // Repeated welded vertex, area <= 1e-12 * bounds diagonal^2, or an index out of range.
  // Triangles with a repeated or out-of-range vertex add no edges; flat ones do.
  std::size_t degenerate_triangles = 0;
  bool closed() const { return boundary_edges == 0 && non_manifold_edges == 0; }
};

// Needs a welded mesh (WeldByPosition); an unwelded one is welded exactly on a copy.
MeshStatistics ComputeMeshStatistics(const Mesh& mesh);

}  // namespace wirerig
