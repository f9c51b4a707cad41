// Islands of a part's skin (MergePartIslands): a capsule split at mid-height into a parent
// (top) and a child (bottom) part, with patches of one painted inside the other, and a loose
// sphere beside it. What is known without the code: a child's small patch inside the parent's
// skin joins the parent; a parent's patch inside the child's skin, a patch holding a user's
// vertex, a patch too large to be a stray, and a whole separate piece keep their parts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <vector>

#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/part_assignment.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr int kTop = 0, kBottom = 1;

struct Scene {
  Mesh mesh;
  std::size_t capsule_vertices = 0;
  std::vector<int> part;
};

// The capsule (y from -0.1 to 1.1) with y > 0.5 on the top part, and a sphere beside it, all
// on the bottom part.
Scene MakeScene() {
  Scene scene;
  scene.mesh = MakeCapsule(0.1, 1.0, 32, 40, 8);
  scene.capsule_vertices = scene.mesh.welded_positions.size();
  Mesh sphere = MakeCapsule(0.03, 0.0, 8, 1, 3);
  for (Vec3& p : sphere.welded_positions) p += Vec3(0.5, 0.25, 0.0);
  for (Vec3& p : sphere.positions) p += Vec3(0.5, 0.25, 0.0);
  AppendMesh(scene.mesh, sphere);
  for (std::size_t v = 0; v < scene.mesh.welded_positions.size(); ++v)
    scene.part.push_back(
        v < scene.capsule_vertices && scene.mesh.welded_positions[v].y() > 0.5 ? kTop : kBottom);
  return scene;
}

// Capsule vertices within `radius` of `centre`, painted `part`.
std::vector<std::uint32_t> Paint(Scene& scene, const Vec3& centre, double radius, int part) {
  std::vector<std::uint32_t> painted;
  for (std::uint32_t v = 0; v < scene.capsule_vertices; ++v) {
    if ((scene.mesh.welded_positions[v] - centre).norm() > radius) continue;
    scene.part[v] = part;
    painted.push_back(v);
  }
  return painted;
}

std::size_t Merge(Scene& scene, const std::vector<bool>& fixed) {
  return MergePartIslands(scene.mesh.welded_triangles, {-1, kTop}, fixed, {false, false},
                          &scene.part);
}

bool AllOn(const Scene& scene, const std::vector<std::uint32_t>& vertices, int part) {
  return std::all_of(vertices.begin(), vertices.end(),
                     [&](std::uint32_t v) { return scene.part[v] == part; });
}

TEST(PartIslands, AChildsPatchInsideItsParentsSkinJoinsTheParent) {
  Scene scene = MakeScene();
  const std::vector<std::uint32_t> patch = Paint(scene, Vec3(0.1, 0.8, 0.0), 0.05, kBottom);
  ASSERT_GE(patch.size(), 3u);
  const std::vector<int> before = scene.part;
  EXPECT_EQ(Merge(scene, std::vector<bool>(scene.part.size(), false)), patch.size());
  EXPECT_TRUE(AllOn(scene, patch, kTop));
  for (std::size_t v = 0; v < before.size(); ++v) {  // nothing else moved
    if (std::find(patch.begin(), patch.end(), v) == patch.end()) {
      EXPECT_EQ(scene.part[v], before[v]);
    }
  }
}

TEST(PartIslands, AParentsPatchInsideItsChildsSkinStays) {
  Scene scene = MakeScene();
  const std::vector<std::uint32_t> patch = Paint(scene, Vec3(0.1, 0.2, 0.0), 0.05, kTop);
  ASSERT_GE(patch.size(), 3u);
  EXPECT_EQ(Merge(scene, std::vector<bool>(scene.part.size(), false)), 0u);
  EXPECT_TRUE(AllOn(scene, patch, kTop));
}

TEST(PartIslands, APatchHoldingAUsersVertexStays) {
  Scene scene = MakeScene();
  const std::vector<std::uint32_t> patch = Paint(scene, Vec3(0.1, 0.8, 0.0), 0.05, kBottom);
  std::vector<bool> fixed(scene.part.size(), false);
  fixed[patch.front()] = true;
  EXPECT_EQ(Merge(scene, fixed), 0u);
  EXPECT_TRUE(AllOn(scene, patch, kBottom));
}

TEST(PartIslands, APatchOverTheStrayFractionOfItsPartsRegionStays) {
  Scene scene = MakeScene();
  // A band all round the top half: cut off from the bottom's main region, and large.
  std::vector<std::uint32_t> band;
  for (std::uint32_t v = 0; v < scene.capsule_vertices; ++v) {
    const double y = scene.mesh.welded_positions[v].y();
    if (y > 0.7 && y < 0.8) {
      scene.part[v] = kBottom;
      band.push_back(v);
    }
  }
  const auto bottom = std::size_t(std::count(scene.part.begin(), scene.part.end(), kBottom));
  ASSERT_GT(double(band.size()), kIslandFraction * double(bottom - band.size()));
  EXPECT_EQ(Merge(scene, std::vector<bool>(scene.part.size(), false)), 0u);
  EXPECT_TRUE(AllOn(scene, band, kBottom));
}

TEST(PartIslands, ASeparatePieceKeepsItsPart) {
  Scene scene = MakeScene();
  // The sphere is the bottom part's only region on its piece of surface: not an island, though
  // far smaller than the bottom's skin on the capsule.
  Merge(scene, std::vector<bool>(scene.part.size(), false));
  for (std::size_t v = scene.capsule_vertices; v < scene.part.size(); ++v)
    EXPECT_EQ(scene.part[v], kBottom);
}

TEST(PartIslands, APatchJoinsTheNeighbourReachedByMostEdges) {
  // A child's patch astride the top and a sibling's region: it joins the one holding more of
  // its border. Three parts: top (root), bottom and side, both children of top.
  Scene scene = MakeScene();
  constexpr int kSide = 2;
  for (std::uint32_t v = 0; v < scene.capsule_vertices; ++v) {
    const Vec3& p = scene.mesh.welded_positions[v];
    if (p.y() > 0.6 && p.y() < 1.0 && p.x() < -0.03) scene.part[v] = kSide;
  }
  // Mostly inside the side's region, touching the top's at one end.
  const std::vector<std::uint32_t> patch = Paint(scene, Vec3(-0.1, 0.65, 0.0), 0.06, kBottom);
  ASSERT_GE(patch.size(), 3u);
  MergePartIslands(scene.mesh.welded_triangles, {-1, kTop, kTop},
                   std::vector<bool>(scene.part.size(), false), {false, false, false}, &scene.part);
  EXPECT_TRUE(AllOn(scene, patch, kSide));
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
