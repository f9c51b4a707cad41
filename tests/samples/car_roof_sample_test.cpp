// Car roof (paper Fig. 9): a region of the milk truck's cargo-box roof, bounded by the first and
// last of 7 profile wires and the ends of their loaded stretch, dented by a uniform line load.
// Each loaded stretch is a clamped wire: its midpoint sinks by q L^4 / 384 EI (L its arc
// length); profile wires outside the region and the spine do not move.
#include <gtest/gtest.h>

#include <cmath>

#include "sample_test_support.h"

namespace wirerig::samples {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr char kScene[] = "car_roof/car_roof.scene.json";
constexpr double kLoad = 800.0;  // N/m, along world -Y at the clip's end (t = 2 s)
constexpr double kFrom = 0.6, kTo = 0.9;

TEST(CarRoofSample, SevenProfileStretchesDentAsClampedWires) {
  std::unique_ptr<PlayedScene> played = PlaySample(kScene);
  ASSERT_NE(played, nullptr);
  const std::size_t body = played->Part("body");
  const PartModel& model = played->scene.model.parts[body];
  played->Evaluate(0.0);
  const std::vector<std::vector<Vec3>> rest = played->playback->workspace().profile_points[body];
  const std::vector<Vec3> spine_rest = played->playback->workspace().spine_points[body];
  played->Evaluate(2.0);
  const auto& points = played->playback->workspace().profile_points[body];
  int dented = 0;
  for (std::uint32_t p = 0; p < model.profiles.size(); ++p) {
    const ProfileModel& profile = model.profiles[p];
    const std::size_t m = profile.local_points.size();
    const bool loaded = p >= 2 && p <= 8;
    if (!loaded) {
      for (std::size_t q = 0; q < m; ++q)
        EXPECT_LE((points[p][q] - rest[p][q]).norm(), 1e-12) << "profile " << p;
      continue;
    }
    ASSERT_TRUE(profile.closed);
    const double ei = profile.stiffness.bending;
    const double length = StretchLength(profile, kFrom, kTo);
    const double peak = kLoad * std::pow(length, 4) / (384.0 * ei);
    // The stretch's middle, u = 0.75, is point 24 of 32.
    ASSERT_EQ(m, 32u);
    const Vec3 moved = points[p][24] - rest[p][24];
    EXPECT_NEAR(-moved.y(), peak, 1e-6 * peak) << "profile " << p;
    EXPECT_LT(std::abs(moved.x()) + std::abs(moved.z()), 1e-6 * peak);
    // Outside the stretch the loop holds.
    EXPECT_LE((points[p][4] - rest[p][4]).norm(), 1e-12);
    dented += peak > 0.01;
  }
  EXPECT_EQ(dented, 7);
  for (std::size_t k = 0; k < spine_rest.size(); ++k)
    EXPECT_LE((played->playback->workspace().spine_points[body][k] - spine_rest[k]).norm(), 1e-12);
}

TEST(CarRoofSample, RefusesTooManySubdivisionLevels) {
  nlohmann::json scene = ReadJson(SampleScenePath(kScene));
  scene["mesh"]["subdivide"] = 9;
  EXPECT_EQ(SceneError(scene), "/mesh/subdivide: must be a whole number of levels in [0, 4]");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::samples
