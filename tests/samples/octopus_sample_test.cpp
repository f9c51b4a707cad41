// The octopus sample (samples/octopus, the demo's scene), played headless:
//  * it travels: its mantle, a rigid body pushed by jet pulses against the water's drag, ends
//    over one body size (the rest mesh's largest extent) from where it started;
//  * its arms move: the farthest skin point of the arms moves, relative to the mantle, by over
//    a third of an arm's length at some frame (the strokes);
//  * its arms have inertia (playback.wires): played again with static wires, the same clip
//    puts the arm tips elsewhere by a visible amount (the lag and swing of the dynamics);
//  * the skin holds on every frame sampled: no edge stretched beyond 2x.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sample_test_support.h"
#include "wirerig/rig/skin_quality.h"

namespace wirerig::samples {
namespace {

constexpr double kFrame = 1.0 / 10.0;  // s

double BodySize(const std::vector<Vec3>& rest) {
  Vec3 lo = rest.front(), hi = rest.front();
  for (const Vec3& p : rest) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).maxCoeff();
}

TEST(OctopusSample, TravelsOverABodySizeAndItsArmsStrokeAndTrail) {
  std::unique_ptr<PlayedScene> played = PlaySample("octopus/octopus.scene.json");
  ASSERT_NE(played, nullptr);
  const RigModel& model = played->scene.model;
  const std::vector<Vec3>& rest = played->scene.mesh.welded_positions;
  const double size = BodySize(rest);
  const std::size_t mantle = played->Part("mantle"), arm = played->Part("tentacle_0");
  ASSERT_EQ(model.parts[mantle].kind, SpineKind::kRigid);
  ASSERT_GT(played->scene.description.playback.wires.modes, 0);
  const double arm_length = model.parts[arm].spine_length;
  const double duration = played->playback->clip().duration;
  const SkinQualityReference reference = MakeSkinQualityReference(rest, model.triangles);
  // Static wires, the same clip: where the arm tip would be without inertia.
  PlaybackOptions still_options = played->scene.description.playback;
  still_options.wires.modes = 0;
  Playback still = Playback::Make(model, played->playback->clip(), still_options).value();
  std::vector<Vec3> still_positions(rest.size());
  double stroke = 0.0, lag = 0.0, worst_stretch = 0.0;
  Vec3 start = Vec3::Zero();
  for (double t = 0.0; t <= duration + 1e-9; t += kFrame) {
    played->Evaluate(t);
    const RigWorkspace& w = played->playback->workspace();
    const Vec3 root = w.spine_points[mantle].front();
    if (t == 0.0) start = root;
    const Vec3 tip = w.spine_points[arm].back() - root;
    const Vec3 rest_tip =
        model.parts[arm].spine_points.back() - model.parts[mantle].spine_points.front();
    stroke = std::max(stroke, (tip - rest_tip).norm());
    ASSERT_TRUE(still.Evaluate(t, still_positions, {}).ok());
    lag = std::max(
        lag, (w.spine_points[arm].back() - still.workspace().spine_points[arm].back()).norm());
    worst_stretch =
        std::max(worst_stretch, MeasureSkin(reference, played->positions).worst_stretch);
  }
  const double travel = (played->playback->workspace().spine_points[mantle].front() - start).norm();
  EXPECT_GT(travel, 1.0 * size) << "body size " << size;
  EXPECT_GT(stroke, arm_length / 3.0);
  EXPECT_GT(lag, 0.05 * arm_length);
  EXPECT_LT(worst_stretch, 2.0);
}

}  // namespace
}  // namespace wirerig::samples
