#include "wirerig/viewer/camera.h"

#include <cmath>

#include <gtest/gtest.h>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(Camera, YawZeroLooksFromPlusZ) {
  Camera camera;
  camera.yaw = 0.0f;
  camera.pitch = 0.0f;
  camera.distance = 2.0f;
  EXPECT_TRUE(camera.Eye().isApprox(Vec3f(0.0f, 0.0f, 2.0f)));
  EXPECT_TRUE(camera.Forward().isApprox(Vec3f(0.0f, 0.0f, -1.0f)));
  EXPECT_TRUE(camera.Right().isApprox(Vec3f(1.0f, 0.0f, 0.0f)));
  EXPECT_TRUE(camera.Up().isApprox(Vec3f(0.0f, 1.0f, 0.0f)));
}

TEST(Camera, TargetProjectsToTheImageCentre) {
  Camera camera;
  camera.target = Vec3f(1.0f, 2.0f, -3.0f);
  const Size size{640, 480};
  Vec2f pixel;
  float depth = 0.0f;
  ASSERT_TRUE(ProjectToPixel(camera, size, camera.target, &pixel, &depth));
  EXPECT_NEAR(pixel.x(), 320.0f, 1e-3f);
  EXPECT_NEAR(pixel.y(), 240.0f, 1e-3f);
  EXPECT_NEAR(depth, camera.distance, 1e-4f);
}

TEST(Camera, UpAndRightMoveUpAndRightOnScreen) {
  Camera camera;
  const Size size{640, 480};
  Vec2f up, right;
  ASSERT_TRUE(ProjectToPixel(camera, size, camera.target + 0.1f * camera.Up(), &up));
  ASSERT_TRUE(ProjectToPixel(camera, size, camera.target + 0.1f * camera.Right(), &right));
  EXPECT_LT(up.y(), 240.0f);
  EXPECT_GT(right.x(), 320.0f);
}

TEST(Camera, PointBehindTheEyeDoesNotProject) {
  Camera camera;
  Vec2f pixel(-1.0f, -1.0f);
  EXPECT_FALSE(ProjectToPixel(camera, {100, 100}, camera.Eye() - camera.Forward(), &pixel));
  EXPECT_EQ(pixel.x(), -1.0f);
}

TEST(Camera, PixelRayThroughAProjectedPointHitsIt) {
  Camera camera;
  camera.yaw = -0.4f;
  camera.pitch = 0.7f;
  const Size size{800, 600};
  const Vec3f point(0.3f, -0.2f, 0.5f);
  Vec2f pixel;
  ASSERT_TRUE(ProjectToPixel(camera, size, point, &pixel));
  const Ray ray = PixelRay(camera, size, pixel);
  const Vec3f to_point = point - ray.origin;
  const float off_ray = (to_point - to_point.dot(ray.direction) * ray.direction).norm();
  EXPECT_LT(off_ray, 1e-4f);
}

TEST(Camera, DragPointStaysOnTheCameraFacingPlane) {
  Camera camera;
  const Size size{640, 480};
  const Vec3f anchor(0.1f, 0.2f, 0.0f);
  const Vec3f p = DragPoint(camera, size, Vec2f(500.0f, 100.0f), anchor);
  EXPECT_NEAR((p - anchor).dot(camera.Forward()), 0.0f, 1e-5f);
  Vec2f back;
  ASSERT_TRUE(ProjectToPixel(camera, size, p, &back));
  EXPECT_NEAR(back.x(), 500.0f, 1e-2f);
  EXPECT_NEAR(back.y(), 100.0f, 1e-2f);
}

TEST(Camera, FrameCameraFitsTheBoundsInTheImage) {
  for (float aspect : {0.5f, 1.0f, 16.0f / 9.0f}) {
    SCOPED_TRACE(aspect);
    Camera camera;
    FrameBounds bounds;
    bounds.min = Vec3f(-1.0f, 0.0f, -0.5f);
    bounds.max = Vec3f(3.0f, 2.0f, 0.5f);
    bounds.empty = false;
    FrameCamera(camera, bounds, aspect);
    EXPECT_TRUE(camera.target.isApprox(bounds.Center()));
    const Size size{int(480 * aspect), 480};
    Vec2f lo, hi;
    ASSERT_TRUE(ProjectBounds(camera, size, bounds, &lo, &hi));
    EXPECT_GE(lo.x(), 0.0f);
    EXPECT_GE(lo.y(), 0.0f);
    EXPECT_LE(hi.x(), float(size.width));
    EXPECT_LE(hi.y(), float(size.height));
    // Not tiny either: the box spans a good part of the narrower direction.
    EXPECT_GT(
        std::max((hi.x() - lo.x()) / float(size.width), (hi.y() - lo.y()) / float(size.height)),
        0.5f);
  }
}

TEST(Camera, FrameCameraIgnoresEmptyBounds) {
  Camera camera;
  const Camera before = camera;
  FrameCamera(camera, FrameBounds{}, 1.0f);
  EXPECT_EQ(camera.distance, before.distance);
  EXPECT_TRUE(camera.target.isApprox(before.target));
}

TEST(RenderFrame, BoundsCoverMeshesAndWires) {
  const std::vector<Vec3f> points = {Vec3f(0, 0, 0), Vec3f(1, 2, 3)};
  const std::vector<Vec3f> wire = {Vec3f(-1, 0, 0), Vec3f(0, 5, 0)};
  RenderMesh mesh;
  mesh.positions = points;
  RenderPolyline line;
  line.points = wire;
  RenderFrame frame;
  frame.meshes = {&mesh, 1};
  frame.polylines = {&line, 1};
  const FrameBounds b = ComputeFrameBounds(frame);
  ASSERT_FALSE(b.empty);
  EXPECT_TRUE(b.min.isApprox(Vec3f(-1, 0, 0)));
  EXPECT_TRUE(b.max.isApprox(Vec3f(1, 5, 3)));
  EXPECT_TRUE(ComputeFrameBounds(RenderFrame{}).empty);
}

TEST(RenderFrame, VertexNormalsOfATrianglePointAlongTheRightHandRule) {
  const std::vector<Vec3f> p = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0), Vec3f(5, 5, 5)};
  const std::vector<Triangle> t = {{0, 1, 2}};
  std::vector<Vec3f> n(p.size());
  ComputeVertexNormals(p, t, n);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(n[i].isApprox(Vec3f::UnitZ()));
  EXPECT_TRUE(n[3].isApprox(Vec3f::UnitY()));  // unused vertex
}

TEST(RenderFrame, ColorMapEndsAndClamping) {
  EXPECT_TRUE(EvaluateColorMap(ColorMap::kCoolWarm, -5.0f)
                  .isApprox(EvaluateColorMap(ColorMap::kCoolWarm, 0.0f)));
  EXPECT_TRUE(EvaluateColorMap(ColorMap::kViridis, 7.0f)
                  .isApprox(EvaluateColorMap(ColorMap::kViridis, 1.0f)));
  const Vec3f cold = EvaluateColorMap(ColorMap::kCoolWarm, 0.0f);
  const Vec3f warm = EvaluateColorMap(ColorMap::kCoolWarm, 1.0f);
  EXPECT_GT(cold.z(), cold.x());
  EXPECT_GT(warm.x(), warm.z());
  EXPECT_TRUE(EvaluateColorMap(ColorMap::kCoolWarm, std::nanf("")).allFinite());
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
