// Midpoint subdivision keeps the surface (same area and enclosed volume), stays closed and
// welded, quadruples the triangles per level, shares midpoints, and keeps parts contiguous.
#include "wirerig/rig/mesh_subdivision.h"

#include <gtest/gtest.h>

#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/mesh_statistics.h"
#include "wirerig/runtime/rigid_body.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

double Area(const Mesh& mesh) {
  double area = 0.0;
  for (const Triangle& t : mesh.triangles)
    area += 0.5 * (mesh.positions[t[1]] - mesh.positions[t[0]])
                      .cross(mesh.positions[t[2]] - mesh.positions[t[0]])
                      .norm();
  return area;
}

TEST(MeshSubdivision, KeepsTheSurfaceClosedAndWelded) {
  Mesh mesh = MakeCylinder(0.3, 1.0, 12, 3);
  AppendMesh(mesh, MakeTorus(1.0, 0.2, 10, 8));
  const Mesh fine = SubdivideMidpoint(mesh, 2);
  EXPECT_EQ(fine.triangles.size(), 16 * mesh.triangles.size());
  EXPECT_NEAR(Area(fine), Area(mesh), 1e-12 * Area(mesh));
  const MeshStatistics stats = ComputeMeshStatistics(fine);
  EXPECT_TRUE(stats.closed());
  EXPECT_EQ(stats.connected_components, 2u);
  // Euler: a closed mesh of F triangles has E = 3F/2 edges; V = E - F + 2 per sphere-like piece
  // (the torus has genus 1: V = E - F). Midpoints are shared, so V grows by E per level.
  const MeshStatistics coarse = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.vertices,
            coarse.vertices + 3 * mesh.triangles.size() / 2 + 3 * (4 * mesh.triangles.size()) / 2);
  MassProperties before, after;
  ASSERT_TRUE(ComputeSolidMassProperties(
                  mesh.positions,
                  std::vector<Triangle>(mesh.triangles.begin(),
                                        mesh.triangles.begin() + mesh.parts[0].triangle_count),
                  1.0, &before)
                  .ok());
  ASSERT_TRUE(ComputeSolidMassProperties(
                  fine.positions,
                  std::vector<Triangle>(fine.triangles.begin(),
                                        fine.triangles.begin() + fine.parts[0].triangle_count),
                  1.0, &after)
                  .ok());
  EXPECT_NEAR(after.volume, before.volume, 1e-12);
  ASSERT_EQ(fine.parts.size(), 2u);
  EXPECT_EQ(fine.parts[1].first_triangle, 16 * mesh.parts[1].first_triangle);
  EXPECT_EQ(fine.normals.size(), fine.positions.size());
  for (const Vec3& n : fine.normals) EXPECT_NEAR(n.norm(), 1.0, 1e-12);
}

TEST(MeshSubdivision, ZeroLevelsIsTheSameMesh) {
  const Mesh mesh = MakeCone(0.2, 0.1, 0.5, 8, 2);
  const Mesh same = SubdivideMidpoint(mesh, 0);
  EXPECT_EQ(same.triangles, mesh.triangles);
  EXPECT_EQ(same.welded_positions.size(), mesh.welded_positions.size());
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
