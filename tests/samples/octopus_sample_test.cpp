// The octopus sample (samples/octopus, the demo's scene), played headless:
//  * it travels: its mantle, a rigid body pushed by jet pulses against the water's drag, ends
//    over one body size (the rest mesh's largest extent) from where it started;
//  * its arms move: the farthest skin point of the arms moves, relative to the mantle, by over
//    a third of an arm's length at some frame (the strokes);
//  * its arms have inertia (playback.wires): played again with static wires, the same clip
//    puts the arm tips elsewhere by a visible amount (the lag and swing of the dynamics);
//  * its arms curl (large_deflection): at the peak of a stroke an arm's tip, seen from the
//    mantle, has moved over half the arm's length and turned past 120 degrees;
//  * arm 0 reaches (wire IK in the clip): at full weight its tip is on the target, a point
//    riding with the mantle, to 1e-6 of the arm's length;
//  * the skin holds on every frame sampled: no edge stretched beyond 2x;
//  * determinism, with every kind of dynamics it plays (rigid body, wires, flesh, reach): the
//    clip baked twice and exported gives byte-identical .glb files, and a playback scrubbed
//    forward then back gives, bit for bit, a fresh playback's frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>

#include "sample_test_support.h"
#include "wirerig/anim/bake.h"
#include "wirerig/anim/gltf_export.h"
#include "wirerig/rig/skin_quality.h"
#include "wirerig/runtime/spine_interpolation.h"

namespace wirerig::samples {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kFrame = 1.0 / 10.0;  // s

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
  double stroke = 0.0, lag = 0.0, worst_stretch = 0.0, curl = 0.0, turn = 0.0, reach_miss = 0.0;
  int reach_frames = 0;
  const PartModel& arm_model = model.parts[arm];
  const ReachChannels<Track>& reach = played->playback->clip().parts[arm].reach;
  ASSERT_FALSE(reach.target.IsEmpty());
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
    // The mantle's motion (its spine's root frame, rest -> now), undone from the arm's tip.
    const Mat3 mantle_turn = FrameAxes(w.spine_frames[mantle].front()) *
                             FrameAxes(model.parts[mantle].spine_frames.front()).transpose();
    const Vec3 seen = mantle_turn.transpose() * (w.spine_points[arm].back() - root) +
                      model.parts[mantle].spine_points.front();
    const Vec3 seen_tangent = mantle_turn.transpose() * w.spine_frames[arm].back().tangent;
    curl = std::max(curl, (seen - arm_model.spine_points.back()).norm() / arm_length);
    turn = std::max(turn, std::acos(std::clamp(
                              seen_tangent.dot(arm_model.spine_frames.back().tangent), -1.0, 1.0)));
    const double local = played->playback->clip().LocalTime(t);
    if (reach.weight.Sample(local) >= 1.0) {
      const Vec3 target =
          mantle_turn * (reach.target.Sample(local) - model.parts[mantle].spine_points.front()) +
          root;
      reach_miss = std::max(reach_miss, (w.spine_points[arm].back() - target).norm());
      ++reach_frames;
    }
  }
  const double travel = (played->playback->workspace().spine_points[mantle].front() - start).norm();
  EXPECT_GT(travel, 1.0 * size) << "body size " << size;
  EXPECT_GT(stroke, arm_length / 3.0);
  EXPECT_GT(lag, 0.05 * arm_length);
  EXPECT_LT(worst_stretch, 2.0);
  EXPECT_GT(curl, 0.5) << "tip turn " << turn * 180.0 / std::numbers::pi << " degrees";
  EXPECT_GT(turn, 120.0 * std::numbers::pi / 180.0);
  EXPECT_GT(reach_frames, 10);
  EXPECT_LT(reach_miss, 1e-6 * arm_length);
  std::printf(
      "octopus: travel %.2f body sizes, curl %.2f arm lengths, tip turn %.0f degrees, "
      "reach miss %.1e m over %d frames, worst stretch %.2f\n",
      travel / size, curl, turn * 180.0 / std::numbers::pi, reach_miss, reach_frames,
      worst_stretch);
}

std::vector<char> BakedBytes(const PlayedScene& played, const std::filesystem::path& out) {
  const BuiltScene& scene = played.scene;
  BakeOptions options;
  options.fps = 10.0;
  Result<BakedAnimation> bake = BakeClip(scene.mesh, scene.model, played.playback->clip(),
                                         scene.description.playback, options);
  EXPECT_TRUE(bake.ok()) << bake.error();
  if (!bake.ok()) return {};
  Result<GltfExportReport> exported = ExportGltf(scene.mesh, bake.value(), {}, out);
  EXPECT_TRUE(exported.ok()) << exported.error();
  std::ifstream file(out, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

TEST(OctopusSample, BakesTheSameBytesTwiceAndScrubsBackToAFreshFrame) {
  std::unique_ptr<PlayedScene> played = PlaySample("octopus/octopus.scene.json");
  ASSERT_NE(played, nullptr);
  const PlaybackOptions& options = played->scene.description.playback;
  ASSERT_GT(options.wires.modes, 0);
  ASSERT_GT(options.profile_wires.modes, 0);
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / "wirerig_octopus_determinism";
  std::filesystem::create_directories(folder);
  const std::vector<char> first = BakedBytes(*played, folder / "first.glb");
  const std::vector<char> second = BakedBytes(*played, folder / "second.glb");
  ASSERT_GT(first.size(), 1000u);
  EXPECT_TRUE(first == second) << "the two bakes differ";
  std::filesystem::remove_all(folder);
  // Forward to 8.7 s (past the reach and many jets), back to 3.3 s: a fresh playback's frame.
  played->Evaluate(8.7);
  played->Evaluate(3.3);
  std::unique_ptr<PlayedScene> fresh = PlaySample("octopus/octopus.scene.json");
  ASSERT_NE(fresh, nullptr);
  fresh->Evaluate(3.3);
  for (std::size_t v = 0; v < fresh->positions.size(); ++v)
    ASSERT_EQ(played->positions[v], fresh->positions[v]) << "vertex " << v;
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::samples
