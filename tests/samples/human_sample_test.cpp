// The human samples (paper Figs. 11-12) and the dancer: played headless, their key numbers
// against closed forms written here.
//  * age: a leg's spine, held at its root and pushed by -30 N at its tip, shortens by F L / EA.
//  * shape: the chest's loaded stretches bulge forward by q L^4 / 384 EI at their middles.
//  * pose: every vertex stays finite and the skin keeps its topology (welded, closed pieces).
//  * dancer: a limb pinned at its joint keeps the joint in place, and under a torque
//    A cos(pi t) from rest it swings out and is back at rest after a whole period (t = 2 s).
#include <gtest/gtest.h>

#include <cmath>

#include "sample_test_support.h"

namespace wirerig::samples {
namespace {

TEST(HumanSamples, AgeShortensTheLegsByTheAxialClosedForm) {
  std::unique_ptr<PlayedScene> played = PlaySample("human/human_age.scene.json");
  ASSERT_NE(played, nullptr);
  const std::size_t leg = played->Part("leg_left");
  const PartModel& part = played->scene.model.parts[leg];
  played->Evaluate(2.0);  // the full -30 N
  const std::vector<Vec3>& spine = played->playback->workspace().spine_points[leg];
  const double expected = -30.0 * part.spine_length / part.spine_stiffness.axial;
  const Vec3 moved = spine.back() - part.spine_points.back();
  EXPECT_NEAR(moved.dot(part.spine_frames.back().tangent), expected, 1e-9 * std::abs(expected));
  EXPECT_LE((spine.front() - part.spine_points.front()).norm(), 1e-12);  // held at the root
  EXPECT_GT(std::abs(expected), 0.05 * part.spine_length);  // visibly younger: over 5% shorter
}

TEST(HumanSamples, ShapeBulgesTheChestByTheClampedWireFormula) {
  std::unique_ptr<PlayedScene> played = PlaySample("human/human_shape.scene.json");
  ASSERT_NE(played, nullptr);
  const std::size_t torso = played->Part("torso");
  const PartModel& part = played->scene.model.parts[torso];
  played->Evaluate(0.0);
  const auto rest = played->playback->workspace().profile_points[torso];
  played->Evaluate(2.0);
  const auto& points = played->playback->workspace().profile_points[torso];
  for (std::uint32_t p : {9u, 10u, 11u}) {
    const ProfileModel& profile = part.profiles[p];
    ASSERT_EQ(profile.local_points.size(), 24u);
    const double length = StretchLength(profile, 0.55, 0.95);
    const double peak = 0.03 * std::pow(length, 4) / (384.0 * profile.stiffness.bending);
    const Vec3 moved = points[p][18] - rest[p][18];  // u = 0.75, the stretch's middle
    EXPECT_NEAR(moved.z(), peak, 1e-6 * peak) << "profile " << p;
    EXPECT_LT(std::abs(moved.x()) + std::abs(moved.y()), 1e-6 * peak);
  }
}

TEST(HumanSamples, PoseKeepsEveryVertexFinite) {
  std::unique_ptr<PlayedScene> played = PlaySample("human/human_pose.scene.json");
  ASSERT_NE(played, nullptr);
  for (double t : {0.5, 1.0, 2.0}) {
    played->Evaluate(t);
    for (const Vec3& p : played->positions)
      ASSERT_TRUE(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()));
  }
}

TEST(DancerSample, PinnedLimbsSwingFromTheirJointsAndReturnAfterAPeriod) {
  std::unique_ptr<PlayedScene> played = PlaySample("dancer/dancer.scene.json");
  ASSERT_NE(played, nullptr);
  for (const char* name : {"arm_left", "leg_right"}) {
    SCOPED_TRACE(name);
    const std::size_t limb = played->Part(name);
    const PartModel& part = played->scene.model.parts[limb];
    double widest = 0.0;
    for (double t : {0.25, 0.5, 1.0, 1.5, 2.0}) {
      played->Evaluate(t);
      const std::vector<Vec3>& spine = played->playback->workspace().spine_points[limb];
      // The torso (a free body without forces) stays; the joint rides on it.
      EXPECT_LE((spine.front() - part.spine_points.front()).norm(), 1e-9) << t;
      const double swing = (spine.back() - part.spine_points.back()).norm();
      if (t < 2.0) widest = std::max(widest, swing);
      // theta(t) = A (1 - cos pi t) / (I pi^2): back at rest at t = 2, up to the coupling of
      // the limb's principal axes and the cubic keys' approximation of the cosine (measured:
      // 6% of the widest swing).
      if (t == 2.0) {
        EXPECT_LT(swing, 0.1 * widest) << widest;
      }
    }
    EXPECT_GT(widest, 0.05 * part.spine_length);  // it did swing visibly
  }
}

}  // namespace
}  // namespace wirerig::samples
