#include "wirerig/viewer/picking.h"

#include <vector>

#include <gtest/gtest.h>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

class PickingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    camera_.yaw = 0.0f;
    camera_.pitch = 0.0f;
    camera_.distance = 4.0f;
    for (int i = 0; i <= 10; ++i) vertical_.emplace_back(0.0f, -1.0f + 0.2f * float(i), 0.0f);
    for (int i = 0; i <= 10; ++i) horizontal_.emplace_back(-1.0f + 0.2f * float(i), 0.5f, 1.0f);
    lines_.resize(2);
    lines_[0].points = vertical_;
    lines_[0].id = 7;
    lines_[1].points = horizontal_;
    lines_[1].id = 9;
  }
  Vec2f Pixel(const Vec3f& p) const {
    Vec2f pixel;
    EXPECT_TRUE(ProjectToPixel(camera_, size_, p, &pixel));
    return pixel;
  }

  Camera camera_;
  Size size_{800, 600};
  std::vector<Vec3f> vertical_, horizontal_;
  std::vector<RenderPolyline> lines_;
};

TEST_F(PickingTest, PicksTheWireUnderTheCursorWithItsParameter) {
  const WirePick pick = PickPolyline(lines_, camera_, size_, Pixel(Vec3f(0.0f, 0.0f, 0.0f)));
  ASSERT_TRUE(pick.hit);
  EXPECT_EQ(pick.polyline, 0);
  EXPECT_EQ(pick.id, 7u);
  EXPECT_NEAR(pick.parameter, 0.5f, 1e-3f);
  EXPECT_LT((pick.point - Vec3f(0.0f, 0.0f, 0.0f)).norm(), 1e-3f);
}

TEST_F(PickingTest, NearbyPixelStillPicksAndFarPixelMisses) {
  const Vec2f on = Pixel(Vec3f(0.0f, -0.6f, 0.0f));
  const WirePick near_pick = PickPolyline(lines_, camera_, size_, on + Vec2f(4.0f, 0.0f));
  ASSERT_TRUE(near_pick.hit);
  EXPECT_NEAR(near_pick.pixel_distance, 4.0f, 1e-2f);
  EXPECT_NEAR(near_pick.parameter, 0.2f, 1e-3f);
  EXPECT_FALSE(PickPolyline(lines_, camera_, size_, on + Vec2f(20.0f, 0.0f)).hit);
}

TEST_F(PickingTest, CrossingWiresPreferTheOneNearerTheEye) {
  // Both pass through the same pixel where they cross; the horizontal one is at z = 1.
  const WirePick pick = PickPolyline(lines_, camera_, size_, Pixel(Vec3f(0.0f, 0.5f, 1.0f)));
  ASSERT_TRUE(pick.hit);
  EXPECT_EQ(pick.id, 9u);
}

TEST_F(PickingTest, UnpickableWiresAreSkipped) {
  lines_[0].pickable = false;
  EXPECT_FALSE(PickPolyline(lines_, camera_, size_, Pixel(Vec3f(0.0f, 0.0f, 0.0f))).hit);
}

TEST_F(PickingTest, ClosedLoopParameterRunsBackToTheStart) {
  const std::vector<Vec3f> square = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 1, 0),
                                     Vec3f(0, 1, 0)};
  RenderPolyline loop;
  loop.points = square;
  loop.closed = true;
  EXPECT_TRUE(PointAtParameter(loop, 0.875f).isApprox(Vec3f(0.0f, 0.5f, 0.0f)));
  EXPECT_TRUE(PointAtParameter(loop, 1.0f).isApprox(Vec3f(0.0f, 0.0f, 0.0f)));
  const WirePick pick = PickPolyline({&loop, 1}, camera_, size_, Pixel(Vec3f(0.0f, 0.5f, 0.0f)));
  ASSERT_TRUE(pick.hit);
  EXPECT_NEAR(pick.parameter, 0.875f, 1e-3f);
}

TEST_F(PickingTest, PointAtParameterInvertsThePick) {
  for (float v : {0.0f, 0.13f, 0.5f, 0.97f, 1.0f}) {
    SCOPED_TRACE(v);
    const Vec3f p = PointAtParameter(lines_[0], v);
    const WirePick pick = PickPolyline(lines_, camera_, size_, Pixel(p));
    ASSERT_TRUE(pick.hit);
    EXPECT_NEAR(pick.parameter, v, 2e-3f);
  }
}

TEST_F(PickingTest, EmptyAndDegenerateInputsMiss) {
  EXPECT_FALSE(PickPolyline({}, camera_, size_, Vec2f(400.0f, 300.0f)).hit);
  const std::vector<Vec3f> one = {Vec3f::Zero()};
  RenderPolyline dot;
  dot.points = one;
  EXPECT_FALSE(PickPolyline({&dot, 1}, camera_, size_, Vec2f(400.0f, 300.0f)).hit);
  EXPECT_TRUE(PointAtParameter(dot, 0.5f).isApprox(Vec3f::Zero()));
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
