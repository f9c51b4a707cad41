// The walk sample (samples/walk): human.zae walking for 10 s on its bone chain, played headless.
//  * the keyed poses drive the chain's articulated dynamics (PD tracking), and the simulated
//    knees and elbows bend past 60 degrees;
//  * the body travels: the pelvis ends over 5 m ahead of where it started;
//  * each foot, while it is down (its ankle within 1 cm of the ankle's lowest height over the
//    walk), keeps its sole on the ground (the foot's lowest skin point within 2.5 cm of the rest
//    mesh's lowest point) and does not slide (its ankle moves under 2.5 cm along the ground
//    over each contact);
//  * the skin holds on every frame: no folded edge, no edge stretched beyond 2x;
//  * the gait loops: every keyed joint angle repeats each 1 s cycle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "sample_test_support.h"
#include "wirerig/rig/skin_quality.h"

namespace wirerig::samples {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr double kFrame = 1.0 / 30.0;  // s
constexpr double kCycle = 1.0;         // s: the gait's period (scripts/make_walk.py)

// A looping gait: each part's keyed joint angles at t and t + one cycle agree (a key computed
// differently in one cycle, as a rounding of the phase once made the knee's toe-off key, fails).
TEST(WalkSample, EveryKeyedJointAngleRepeatsEachCycle) {
  std::unique_ptr<PlayedScene> played = PlaySample("walk/walk.scene.json");
  ASSERT_NE(played, nullptr);
  const Clip& clip = played->playback->clip();
  std::size_t tracks = 0;
  for (std::size_t p = 0; p < clip.parts.size(); ++p) {
    const Track<Vec3>& angles = clip.parts[p].joint_angles;
    if (angles.IsEmpty()) continue;
    ++tracks;
    // At the keys (20 per cycle): between them the cubic's tangents at the clip's ends differ.
    for (int k = 0; double(k) / 20.0 + kCycle <= clip.duration + 1e-9; ++k) {
      const double t = double(k) / 20.0;
      ASSERT_LT((angles.Sample(t + kCycle) - angles.Sample(t)).norm(), 0.01)
          << played->scene.model.parts[p].name << " at t = " << t;  // degrees
    }
  }
  EXPECT_GE(tracks, 12u);
}

TEST(WalkSample, KneesAndElbowsBendPastSixtyDegrees) {
  std::unique_ptr<PlayedScene> played = PlaySample("walk/walk.scene.json");
  ASSERT_NE(played, nullptr);
  const ArticulatedTracking* tracking = played->playback->tracking();
  ASSERT_NE(tracking, nullptr);  // the keyed poses drive the chain's dynamics
  const double duration = played->playback->clip().duration;
  for (const char* name : {"shin_l", "shin_r", "forearm_l", "forearm_r"}) {
    const std::size_t p = played->Part(name);
    double widest = 0.0;
    for (double t = 0.0; t <= duration; t += kFrame) {
      played->Evaluate(t);
      widest = std::max(widest, tracking->JointAngles(p).x());  // as simulated
    }
    EXPECT_GT(widest, 60.0) << name;
  }
}

// The dynamics lags the keys a little (PD tracking at 8 Hz, damping ratio 0.7, no ground
// contact in the model): the bounds below allow for that lag (the keys alone keep the sole
// within 1.1 cm).
TEST(WalkSample, TravelsWithFeetPlantedAndTheSkinWhole) {
  std::unique_ptr<PlayedScene> played = PlaySample("walk/walk.scene.json");
  ASSERT_NE(played, nullptr);
  const RigModel& model = played->scene.model;
  const std::vector<Vec3>& rest = played->scene.mesh.welded_positions;
  double ground = std::numeric_limits<double>::infinity();
  for (const Vec3& p : rest) ground = std::min(ground, p.y());
  const SkinQualityReference reference = MakeSkinQualityReference(rest, model.triangles);
  const std::size_t pelvis = played->Part("pelvis");
  struct Foot {
    std::size_t part;
    std::vector<double> sole, ankle_height;
    std::vector<Vec3> ankle;
  };
  std::vector<Foot> feet = {{played->Part("foot_l"), {}, {}, {}},
                            {played->Part("foot_r"), {}, {}, {}}};
  const double duration = played->playback->clip().duration;
  Vec3 start = Vec3::Zero(), end = Vec3::Zero();
  for (double t = 0.0; t <= duration + 1e-9; t += kFrame) {
    played->Evaluate(t);
    const SkinQuality quality = MeasureSkin(reference, played->positions);
    ASSERT_EQ(quality.folded_edges, 0u) << "t = " << t;
    ASSERT_LT(quality.worst_stretch, 2.0) << "t = " << t;
    const auto& spines = played->playback->workspace().spine_points;
    if (t == 0.0) start = spines[pelvis].front();
    end = spines[pelvis].front();
    for (Foot& foot : feet) {
      double sole = std::numeric_limits<double>::infinity();
      for (std::size_t v = 0; v < model.vertices.size(); ++v)
        if (model.vertices[v].part == foot.part) sole = std::min(sole, played->positions[v].y());
      foot.sole.push_back(sole);
      foot.ankle.push_back(spines[foot.part].front());
      foot.ankle_height.push_back(spines[foot.part].front().y());
    }
  }
  EXPECT_GT(end.z() - start.z(), 5.0);  // forward is +z
  for (const Foot& foot : feet) {
    SCOPED_TRACE(model.parts[foot.part].name);
    const double lowest = *std::min_element(foot.ankle_height.begin(), foot.ankle_height.end());
    std::size_t contacts = 0, down = 0;
    Vec3 touchdown = Vec3::Zero();
    double worst_slide = 0.0, worst_sole = 0.0;
    for (std::size_t k = 0; k < foot.sole.size(); ++k) {
      const bool is_down = foot.ankle_height[k] < lowest + 0.01;
      if (is_down) {
        ++down;
        if (k == 0 || !(foot.ankle_height[k - 1] < lowest + 0.01)) {
          ++contacts;
          touchdown = foot.ankle[k];
        }
        const Vec3 slide = foot.ankle[k] - touchdown;
        worst_slide = std::max(worst_slide, std::hypot(slide.x(), slide.z()));
        worst_sole = std::max(worst_sole, std::abs(foot.sole[k] - ground));
      }
    }
    EXPECT_GE(contacts, 9u);  // a step a second
    EXPECT_GT(down, foot.sole.size() / 4);
    EXPECT_LT(worst_sole, 0.025);
    EXPECT_LT(worst_slide, 0.025);
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::samples
