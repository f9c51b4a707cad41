// A surface's border and its exact change of volume (skin_quality.h) on a unit cube whose top
// is lifted: closed, open below (the hole stays put), and open on top (the hole moves).
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

#include "wirerig/rig/skin_quality.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

// Corner (x, y, z) in {0, 1}^3 is vertex x + 2y + 4z.
std::vector<Vec3> Cube() {
  std::vector<Vec3> corners;
  for (int v = 0; v < 8; ++v) corners.emplace_back(v & 1, (v >> 1) & 1, (v >> 2) & 1);
  return corners;
}

// Outward triangles, two per face: bottom (z = 0) first, top (z = 1) second.
const std::vector<Triangle> kBottom = {{0, 2, 3}, {0, 3, 1}};
const std::vector<Triangle> kTop = {{4, 5, 7}, {4, 7, 6}};
const std::vector<Triangle> kSides = {{0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                      {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};

std::vector<Triangle> Faces(bool bottom, bool top) {
  std::vector<Triangle> faces = kSides;
  if (bottom) faces.insert(faces.end(), kBottom.begin(), kBottom.end());
  if (top) faces.insert(faces.end(), kTop.begin(), kTop.end());
  return faces;
}

// The cube with its top (z = 1) raised by h and sheared by s along x: volume 1 + h.
std::vector<Vec3> Lifted(double h, double s) {
  std::vector<Vec3> p = Cube();
  for (int v = 4; v < 8; ++v) p[v] += Vec3(s, 0.0, h);
  return p;
}

TEST(SurfaceBorder, IsTheVerticesOfEdgesNotOnTwoTriangles) {
  EXPECT_TRUE(SurfaceBorder(Faces(true, true)).empty());
  EXPECT_EQ(SurfaceBorder(Faces(false, true)), (std::vector<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(SurfaceBorder(Faces(true, false)), (std::vector<std::uint32_t>{4, 5, 6, 7}));
  // A third triangle on the edge 0-1 makes it a seam.
  std::vector<Triangle> seam = Faces(true, true);
  seam.push_back({0, 1, 6});
  const std::vector<std::uint32_t> border = SurfaceBorder(seam);
  EXPECT_NE(std::find(border.begin(), border.end(), 0u), border.end());
  EXPECT_NE(std::find(border.begin(), border.end(), 1u), border.end());
}

TEST(SurfaceVolumeChange, IsTheLiftOfTheTopOnAClosedCube) {
  const std::vector<Triangle> faces = Faces(true, true);
  const std::vector<Vec3> rest = Cube();
  for (const auto& [h, s] : {std::pair{0.25, 0.0}, std::pair{-0.4, 0.3}, std::pair{1.5, -2.0}}) {
    const std::optional<double> change =
        SurfaceVolumeChange(rest, Lifted(h, s), faces, SurfaceBorder(faces));
    ASSERT_TRUE(change.has_value());
    EXPECT_NEAR(*change, h, 1e-14) << "h " << h << " shear " << s;
  }
}

TEST(SurfaceVolumeChange, HoldsWhileTheHoleStaysAndRefusesWhenItMoves) {
  const std::vector<Vec3> rest = Cube();
  const std::vector<Triangle> open_below = Faces(false, true);
  const std::optional<double> change =
      SurfaceVolumeChange(rest, Lifted(0.3, 0.2), open_below, SurfaceBorder(open_below));
  ASSERT_TRUE(change.has_value());
  EXPECT_NEAR(*change, 0.3, 1e-14);
  const std::vector<Triangle> open_above = Faces(true, false);
  EXPECT_FALSE(SurfaceVolumeChange(rest, Lifted(0.3, 0.0), open_above, SurfaceBorder(open_above)));
  // Rounding-sized motion of the border (1e-12 of the size) still counts as staying.
  std::vector<Vec3> nudged = Lifted(0.3, 0.0);
  for (int v = 4; v < 8; ++v) nudged[v] = rest[v] + Vec3(1e-12, 0.0, 0.0);
  EXPECT_TRUE(SurfaceVolumeChange(rest, nudged, open_above, SurfaceBorder(open_above)));
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
