// The octopus's second clip, "crawl" (samples/octopus, scripts/make_octopus.py), played
// headless: the body glides along the ground plane on its arms in a two-group gait, each arm
// holding its tip on a foothold (a reach target in world axes, wire IK every step) while the
// other group swings forwards.
//  * it travels along the ground: the mantle ends over one body size from where it started,
//    its height never changing by more than the settle;
//  * planted arms hold: while an arm's reach is at full weight its tip stays on its foothold
//    sideways (the lateral solve is exact) and within a few cm along the arm (the axial part is
//    out of reach of a lateral tip force: clip_reach.h);
//  * it walks on the ground: from the settle on, the lowest skin point is on the ground (within
//    3 cm above or below it) at every frame;
//  * every arm keeps up: each arm's tip travels over one body size;
//  * the skin holds: no edge stretched beyond 2x.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "sample_test_support.h"
#include "wirerig/rig/skin_quality.h"

namespace wirerig::samples {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kFrame = 1.0 / 20.0;  // s
constexpr double kSettle = 1.0;        // s: the body lowers onto its arms (make_octopus.py)

Vec3 Horizontal(const Vec3& p) { return Vec3(p.x(), 0.0, p.z()); }

TEST(OctopusCrawl, WalksAlongTheGroundOnPlantedArms) {
  std::unique_ptr<PlayedScene> played = PlaySample("octopus/octopus.scene.json", "crawl");
  ASSERT_NE(played, nullptr);
  const RigModel& model = played->scene.model;
  const std::vector<Vec3>& rest = played->scene.mesh.welded_positions;
  const double size = BodySize(rest);
  const std::optional<CameraHint>& camera = played->scene.description.camera;
  ASSERT_TRUE(camera.has_value() && camera->ground.has_value());
  const double ground = *camera->ground;
  const Clip& clip = played->playback->clip();
  const std::size_t mantle = played->Part("mantle");
  std::vector<std::size_t> arms;
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    if (!clip.parts[p].reach.target.IsEmpty()) arms.push_back(p);
  ASSERT_EQ(arms.size(), 8u);
  const SkinQualityReference reference = MakeSkinQualityReference(rest, model.triangles);

  double worst_slip = 0.0, worst_height = 0.0, worst_ground = 0.0, worst_stretch = 0.0;
  int planted_frames = 0, arm_frames = 0;
  std::vector<Vec3> first_tip(model.parts.size()), last_tip(model.parts.size());
  Vec3 start = Vec3::Zero();
  double lowest_root = 0.0, highest_root = 0.0;
  for (double t = 0.0; t <= clip.duration + 1e-9; t += kFrame) {
    played->Evaluate(t);
    const RigWorkspace& w = played->playback->workspace();
    const Vec3 root = w.spine_points[mantle].front();
    if (t == 0.0) start = root, lowest_root = highest_root = root.y();
    lowest_root = std::min(lowest_root, root.y());
    highest_root = std::max(highest_root, root.y());
    for (std::size_t p : arms) {
      const Vec3 tip = w.spine_points[p].back();
      if (t == 0.0) first_tip[p] = tip;
      last_tip[p] = tip;
      ++arm_frames;
      const double local = clip.LocalTime(t);
      if (clip.parts[p].reach.weight.Sample(local) < 1.0) continue;
      const Vec3 foothold = clip.parts[p].reach.target.Sample(local);
      worst_slip = std::max(worst_slip, (Horizontal(tip) - Horizontal(foothold)).norm());
      worst_height = std::max(worst_height, std::abs(tip.y() - foothold.y()));
      ++planted_frames;
    }
    if (t >= kSettle) {
      double lowest = played->positions.front().y();
      for (const Vec3& p : played->positions) lowest = std::min(lowest, p.y());
      worst_ground = std::max(worst_ground, std::abs(lowest - ground));
    }
    worst_stretch =
        std::max(worst_stretch, MeasureSkin(reference, played->positions).worst_stretch);
  }
  const Vec3 end = played->playback->workspace().spine_points[mantle].front();
  const double travel = (Horizontal(end) - Horizontal(start)).norm();
  EXPECT_GT(travel, 1.0 * size) << "body size " << size;
  EXPECT_LT(highest_root - lowest_root, 0.05 * size);
  EXPECT_GT(planted_frames, 0.4 * arm_frames);  // each arm planted about half the time
  EXPECT_LT(worst_slip, 0.01 * size);
  EXPECT_LT(worst_height, 0.03 * size);
  EXPECT_LT(worst_ground, 0.03);
  double slowest_arm = travel;
  for (std::size_t p : arms)
    slowest_arm =
        std::min(slowest_arm, (Horizontal(last_tip[p]) - Horizontal(first_tip[p])).norm());
  EXPECT_GT(slowest_arm, 1.0 * size);
  EXPECT_LT(worst_stretch, 2.0);
  std::printf(
      "octopus crawl: travel %.2f body sizes, slowest arm %.2f, planted tips: slip %.1e m, "
      "height %.3f m over %d of %d arm-frames; lowest skin within %.3f m of the ground; worst "
      "stretch "
      "%.2f\n",
      travel / size, slowest_arm / size, worst_slip, worst_height, planted_frames, arm_frames,
      worst_ground, worst_stretch);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::samples
