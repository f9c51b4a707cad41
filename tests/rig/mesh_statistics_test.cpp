// Tests for WeldByPosition, ComputeBounds and ComputeMeshStatistics on hand-built meshes whose
// topology is known: a tetrahedron, disjoint triangles, a fin of three triangles on one edge,
// degenerate triangles, a quad with a texture seam.
#include "wirerig/rig/mesh_statistics.h"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "wirerig/rig/mesh.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

Mesh MakeMesh(std::vector<Vec3> positions, std::vector<Triangle> triangles) {
  Mesh mesh;
  mesh.positions = std::move(positions);
  mesh.triangles = std::move(triangles);
  return mesh;
}

// Unit tetrahedron, faces outwards.
Mesh Tetrahedron() {
  return MakeMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                  {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

// The tetrahedron with a vertex per corner of every face (as STL files store it).
Mesh SplitTetrahedron() {
  const Mesh tet = Tetrahedron();
  Mesh split;
  for (const Triangle& t : tet.triangles) {
    const auto base = static_cast<std::uint32_t>(split.positions.size());
    for (const std::uint32_t v : t) split.positions.push_back(tet.positions[v]);
    split.triangles.push_back({base, base + 1, base + 2});
  }
  return split;
}

TEST(MeshStatistics, TetrahedronIsClosedWithOneComponent) {
  Mesh mesh = Tetrahedron();
  WeldByPosition(mesh);
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.vertices, 4u);
  EXPECT_EQ(stats.render_vertices, 4u);
  EXPECT_EQ(stats.triangles, 4u);
  EXPECT_EQ(stats.connected_components, 1u);
  EXPECT_EQ(stats.boundary_edges, 0u);
  EXPECT_EQ(stats.non_manifold_edges, 0u);
  EXPECT_EQ(stats.degenerate_triangles, 0u);
  EXPECT_TRUE(stats.closed());
}

TEST(MeshStatistics, OpenTetrahedronHasThreeBoundaryEdges) {
  Mesh mesh = Tetrahedron();
  mesh.triangles.pop_back();
  WeldByPosition(mesh);
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.boundary_edges, 3u);
  EXPECT_FALSE(stats.closed());
}

TEST(MeshStatistics, SplitCornersAreWeldedBeforeCounting) {
  Mesh mesh = SplitTetrahedron();
  WeldByPosition(mesh);
  EXPECT_EQ(mesh.positions.size(), 12u);
  EXPECT_EQ(mesh.welded_positions.size(), 4u);
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.vertices, 4u);
  EXPECT_EQ(stats.render_vertices, 12u);
  EXPECT_TRUE(stats.closed());
  EXPECT_EQ(stats.connected_components, 1u);
}

TEST(MeshStatistics, UnweldedMeshIsWeldedOnACopy) {
  const Mesh mesh = SplitTetrahedron();  // weld fields empty
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.vertices, 4u);
  EXPECT_TRUE(stats.closed());
  EXPECT_TRUE(mesh.weld_map.empty());
}

TEST(MeshStatistics, TwoDisjointTriangles) {
  Mesh mesh = MakeMesh(
      {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(5, 0, 0), Vec3(6, 0, 0), Vec3(5, 1, 0)},
      {{0, 1, 2}, {3, 4, 5}});
  WeldByPosition(mesh);
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.connected_components, 2u);
  EXPECT_EQ(stats.boundary_edges, 6u);
  EXPECT_EQ(stats.non_manifold_edges, 0u);
}

TEST(MeshStatistics, ThreeTrianglesOnOneEdgeAreNonManifold) {
  // A fin: three triangles hinged on the edge (0, 1).
  Mesh mesh =
      MakeMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), Vec3(0.5, -1, 0), Vec3(0.5, 0, 1)},
               {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  WeldByPosition(mesh);
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.non_manifold_edges, 1u);
  EXPECT_EQ(stats.boundary_edges, 6u);
  EXPECT_EQ(stats.connected_components, 1u);
  EXPECT_FALSE(stats.closed());
}

TEST(MeshStatistics, DegenerateTriangles) {
  // Repeated vertex, coincident positions (welded to a repeated vertex), collinear corners.
  Mesh mesh = MakeMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)},
                       {{0, 1, 2}, {0, 0, 1}, {0, 1, 3}, {0, 1, 4}});
  WeldByPosition(mesh);
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.degenerate_triangles, 3u);
  EXPECT_EQ(stats.triangles, 4u);
  // Triangles with a repeated vertex have no edges; the collinear one does.
  // Boundary: two edges of the good triangle and two of the collinear one; (0, 1) is shared.
  EXPECT_EQ(stats.boundary_edges, 4u);
  EXPECT_EQ(stats.connected_components, 1u);
}

TEST(MeshStatistics, TinyButValidTriangleIsNotDegenerate) {
  // Area relative to the bounding box: a 1e-4 triangle next to a unit one is fine.
  Mesh mesh = MakeMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(2, 0, 0),
                        Vec3(2.0001, 0, 0), Vec3(2, 0.0001, 0)},
                       {{0, 1, 2}, {3, 4, 5}});
  WeldByPosition(mesh);
  EXPECT_EQ(ComputeMeshStatistics(mesh).degenerate_triangles, 0u);
  mesh.positions[5] = Vec3(2, 1e-8, 0);  // area 5e-13 < 1e-12 * diagonal^2 (diagonal^2 = 5)
  WeldByPosition(mesh);
  EXPECT_EQ(ComputeMeshStatistics(mesh).degenerate_triangles, 1u);
}

TEST(MeshStatistics, OutOfRangeIndexIsCountedNotFollowed) {
  Mesh mesh = MakeMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}, {0, 1, 7}});
  WeldByPosition(mesh);
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.degenerate_triangles, 1u);
  EXPECT_EQ(stats.boundary_edges, 3u);
}

TEST(MeshStatistics, EmptyMesh) {
  Mesh mesh;
  WeldByPosition(mesh);
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.vertices, 0u);
  EXPECT_EQ(stats.connected_components, 0u);
  EXPECT_TRUE(stats.closed());
  const Bounds bounds = ComputeBounds(mesh);
  EXPECT_EQ(bounds.min, Vec3::Zero());
  EXPECT_EQ(bounds.Diagonal(), 0.0);
}

// ---------------------------------------------------------------------------------------------
// Welding.

// A unit quad whose two triangles have their own copies of the shared diagonal's vertices
// (different uvs: a texture seam along the diagonal).
TEST(WeldByPosition, TextureSeamIsMergedAndTopologyKept) {
  Mesh mesh = MakeMesh(
      {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)},
      {{0, 1, 2}, {3, 4, 5}});
  mesh.uvs = {Vec2(0, 0), Vec2(0.5, 0), Vec2(0.5, 0.5), Vec2(0.5, 0.5), Vec2(1, 1), Vec2(0.5, 1)};
  WeldByPosition(mesh);
  EXPECT_EQ(mesh.welded_positions.size(), 4u);
  EXPECT_EQ(mesh.weld_map, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  ASSERT_EQ(mesh.welded_triangles.size(), 2u);
  EXPECT_EQ(mesh.welded_triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(mesh.welded_triangles[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(mesh.positions.size(), 6u);  // render vertices untouched
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.boundary_edges, 4u);  // the seam is not a hole
  EXPECT_EQ(stats.connected_components, 1u);
}

TEST(WeldByPosition, ExactWeldingMergesSignedZeros) {
  Mesh mesh = MakeMesh({Vec3(0.0, 0.0, 1.0), Vec3(-0.0, 0.0, 1.0), Vec3(1e-300, 0.0, 1.0)}, {});
  WeldByPosition(mesh);
  EXPECT_EQ(mesh.weld_map, (std::vector<std::uint32_t>{0, 0, 1}));
}

TEST(WeldByPosition, ToleranceMergesNearbyAndKeepsFirstPosition) {
  const double tol = 1e-3;
  Mesh mesh = MakeMesh({Vec3(0, 0, 0), Vec3(0.5e-3, 0, 0), Vec3(1.2e-3, 0, 0),
                        Vec3(0.4e-3, 0.4e-3, 0.4e-3), Vec3(5, 5, 5), Vec3(5, 5, 5.0009)},
                       {});
  WeldByPosition(mesh, tol);
  // Within tolerance of the first position of a welded vertex; 1.2e-3 is too far from 0 and
  // starts its own (no chaining through the vertex at 0.5e-3).
  EXPECT_EQ(mesh.weld_map, (std::vector<std::uint32_t>{0, 0, 1, 0, 2, 2}));
  ASSERT_EQ(mesh.welded_positions.size(), 3u);
  EXPECT_EQ(mesh.welded_positions[0], Vec3(0, 0, 0));
  EXPECT_EQ(mesh.welded_positions[1], Vec3(1.2e-3, 0, 0));
  EXPECT_EQ(mesh.welded_positions[2], Vec3(5, 5, 5));
  // Exact welding keeps them all apart.
  WeldByPosition(mesh, 0.0);
  EXPECT_EQ(mesh.welded_positions.size(), 6u);
}

TEST(WeldByPosition, ToleranceWorksAcrossCellBoundaries) {
  // Points straddling a grid cell boundary (cells are `tolerance` wide).
  const double tol = 0.1;
  Mesh mesh = MakeMesh({Vec3(0.0999, 0.0999, 0.0999), Vec3(0.1001, 0.1001, 0.1001),
                        Vec3(-0.0001, 0, 0), Vec3(0.0001, 0, 0)},
                       {});
  WeldByPosition(mesh, tol);
  EXPECT_EQ(mesh.weld_map, (std::vector<std::uint32_t>{0, 0, 1, 1}));
}

TEST(WeldByPosition, DeterministicAndRepeatable) {
  Mesh a = SplitTetrahedron();
  Mesh b = SplitTetrahedron();
  WeldByPosition(a, 1e-6);
  WeldByPosition(b, 1e-6);
  WeldByPosition(b, 1e-6);  // welding again replaces, never accumulates
  EXPECT_EQ(a.weld_map, b.weld_map);
  EXPECT_EQ(a.welded_positions, b.welded_positions);
  EXPECT_EQ(b.welded_positions.size(), 4u);
  EXPECT_EQ(b.welded_triangles.size(), 4u);
}

TEST(ComputeBounds, UsesWeldedPositionsWhenWelded) {
  Mesh mesh = MakeMesh({Vec3(-1, 2, 3), Vec3(4, -5, 6), Vec3(0, 0, -7)}, {{0, 1, 2}});
  Bounds bounds = ComputeBounds(mesh);  // not welded: render positions
  EXPECT_EQ(bounds.min, Vec3(-1, -5, -7));
  EXPECT_EQ(bounds.max, Vec3(4, 2, 6));
  WeldByPosition(mesh);
  bounds = ComputeBounds(mesh);
  EXPECT_EQ(bounds.min, Vec3(-1, -5, -7));
  EXPECT_EQ(bounds.max, Vec3(4, 2, 6));
  EXPECT_DOUBLE_EQ(bounds.Diagonal(), Vec3(5, 7, 13).norm());
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
