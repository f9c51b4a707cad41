// samples/trunk (paper Fig. 7): a tree trunk bent by a force at its top, as a cantilever
// without rotation at the free end (guided, force F, t = 1 s) and with rotation (free, force
// F/2, t = 2 s). The played spine is checked against the textbook tip-load curves, written out
// here (x up from the clamped root, P the force):
//   free    y(x) = P x^2 (3 L - x) / (6 EI):   tip P L^3 / 3 EI, tip slope P L^2 / 2 EI
//   guided  y(x) = P x^2 (3 L - 2 x) / (12 EI): tip P L^3 / 12 EI, tip slope 0
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sample_test_support.h"

namespace wirerig::samples {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr const char* kScene = "trunk/trunk.scene.json";
constexpr double kEI = 10.0e9 * 1.6e-4;  // wood's E and the scene's I
constexpr double kF = 170000.0;          // N, the guided case; the free one gets F/2

struct Measured {
  double max_error = 0.0;  // largest |measured - formula| over the samples, m
  double tip = 0.0;        // tip deflection along +X, m
  double tip_slope = 0.0;  // dx/dy of the tip tangent
  double root_slope = 0.0;
};

template <typename Formula>
Measured Measure(PlayedScene& played, double t, Formula formula) {
  played.Evaluate(t);
  const RigWorkspace& w = played.playback->workspace();
  const PartModel& trunk = played.scene.model.parts[0];
  Measured m;
  for (std::size_t k = 0; k < trunk.spine_points.size(); ++k) {
    const Vec3 moved = w.spine_points[0][k] - trunk.spine_points[k];
    const double x = trunk.spine_points[k].y() - trunk.spine_points.front().y();
    m.max_error = std::max(m.max_error, std::abs(moved.x() - formula(x)));
    m.max_error = std::max(m.max_error, std::abs(moved.y()) + std::abs(moved.z()));
  }
  m.tip = (w.spine_points[0].back() - trunk.spine_points.back()).x();
  const Vec3 tip = w.spine_frames[0].back().tangent, root = w.spine_frames[0].front().tangent;
  m.tip_slope = tip.x() / tip.y();
  m.root_slope = root.x() / root.y();
  return m;
}

TEST(TrunkSample, FreeEndWithHalfTheForceBendsTwiceAsFarAsGuided) {
  std::unique_ptr<PlayedScene> played = PlaySample(kScene);
  ASSERT_NE(played, nullptr);
  const PartModel& trunk = played->scene.model.parts[0];
  ASSERT_DOUBLE_EQ(trunk.spine_stiffness.bending, kEI);
  const double length = (trunk.spine_points.back() - trunk.spine_points.front()).norm();
  ASSERT_NEAR(trunk.spine_points.back().x(), 0.0, 1e-12);  // straight, upright

  const Measured guided = Measure(
      *played, 1.0, [&](double x) { return kF * x * x * (3.0 * length - 2.0 * x) / (12.0 * kEI); });
  const double guided_tip = kF * std::pow(length, 3) / (12.0 * kEI);
  EXPECT_LT(guided.max_error, 1e-6 * guided_tip);
  EXPECT_NEAR(guided.tip, guided_tip, 1e-6 * guided_tip);
  EXPECT_LT(std::abs(guided.tip_slope), 1e-12);  // no rotation at the free end
  EXPECT_LT(std::abs(guided.root_slope), 1e-12);

  const double p = 0.5 * kF;
  const Measured free =
      Measure(*played, 2.0, [&](double x) { return p * x * x * (3.0 * length - x) / (6.0 * kEI); });
  const double free_tip = p * std::pow(length, 3) / (3.0 * kEI);
  const double free_slope = p * length * length / (2.0 * kEI);
  EXPECT_LT(free.max_error, 1e-6 * free_tip);
  EXPECT_NEAR(free.tip, free_tip, 1e-6 * free_tip);
  EXPECT_NEAR(free.tip_slope, free_slope, 1e-6 * free_slope);
  EXPECT_LT(std::abs(free.root_slope), 1e-12);

  // The paper's point: half the force, yet twice the tip deflection once the end may turn.
  EXPECT_NEAR(free.tip / guided.tip, 2.0, 1e-6);
  // Within the small-deflection range: no warning.
  EXPECT_LT(free_tip, 0.1 * length);
  EXPECT_FALSE(played->warnings[0].beyond_small_deflection);
}

TEST(TrunkSample, RefusesBadShapesAndBoundaries) {
  nlohmann::json scene = ReadJson(SampleScenePath(kScene));
  scene["mesh"]["parameters"]["top_radius"] = 0.3;
  EXPECT_NE(SceneError(scene).find("/mesh/parameters/top_radius"), std::string::npos)
      << SceneError(scene);
  scene = ReadJson(SampleScenePath(kScene));
  scene["mesh"]["parameters"]["branches"] = 3;
  EXPECT_NE(SceneError(scene).find("/mesh/parameters/branches: unknown parameter of trunk"),
            std::string::npos)
      << SceneError(scene);
  scene = ReadJson(SampleScenePath(kScene));
  scene["clips"][0]["parts"][0]["boundary"][1]["time"] = 3.0;  // beyond the clip
  EXPECT_NE(SceneError(scene).find("/clips/0"), std::string::npos) << SceneError(scene);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::samples
