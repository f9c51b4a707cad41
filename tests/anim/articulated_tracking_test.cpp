// Keyed poses through the chain's articulated dynamics (articulated_tracking.h), on a capsule
// rigged as an upper and a lower segment joined by a hinge:
//  * a hinge keyed to 40 degrees from the start follows the critically damped response
//    theta(t) = 40 (1 - (1 + w t) e^{-w t}), w = 2 pi f (the gains scale with the inertia the
//    joint drives, so f and zeta are the joint's own natural frequency and damping ratio);
//  * with damping ratio 0.3 it overshoots by the textbook exp(-pi zeta / sqrt(1 - zeta^2));
//  * scrubbing back and forth gives the same frames (fixed steps from cached states);
//  * a keyed force, a keyed torque and gravity each hold the hinge where the PD spring balances
//    their moment;
//  * bad options are refused naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "wirerig/anim/playback.h"
#include "wirerig/anim/scene.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using nlohmann::json;

json ArmScene(double frequency, double damping_ratio) {
  json scene = json::parse(R"({
    "format": "wirerig.scene", "version": 1, "name": "arm",
    "mesh": {"procedural": "capsule", "parameters": {"radius": 0.05, "height": 1.0}},
    "rig": {"description": {"parts": [
      {"name": "upper", "central_curve": [[0, 1.02, 0], [0, 0.5, 0]], "profile_count": 8},
      {"name": "lower", "parent": "upper", "central_curve": [[0, 0.5, 0], [0, -0.02, 0]],
       "profile_count": 8, "joint": {"type": "hinge", "axis": [1, 0, 0], "blend": 0.0}}]}},
    "default_kind": "rigid",
    "clips": [{"name": "bend", "duration": 2, "parts": [
      {"part": "lower", "joint_angles": {"interpolation": "step",
                                          "keys": [{"time": 0, "value": [0, 0, 0]},
                                                   {"time": 0.1, "value": [40, 0, 0]}]}}]}]
  })");
  scene["playback"]["tracking"] = {
      {"frequency", frequency}, {"damping_ratio", damping_ratio}, {"gravity", {0, 0, 0}}};
  return scene;
}

struct Played {
  BuiltScene scene;
  std::unique_ptr<Playback> playback;
  std::vector<Vec3> positions;
};

std::unique_ptr<Played> Play(const json& document) {
  Result<SceneDescription> description = ParseScene(document, ".");
  EXPECT_TRUE(description.ok()) << description.error();
  if (!description) return nullptr;
  Result<BuiltScene> built = BuildScene(description.value());
  EXPECT_TRUE(built.ok()) << built.error();
  if (!built) return nullptr;
  auto played = std::make_unique<Played>();
  played->scene = std::move(built).value();
  Result<Playback> playback = Playback::Make(played->scene.model, played->scene.clips[0],
                                             played->scene.description.playback);
  EXPECT_TRUE(playback.ok()) << playback.error();
  if (!playback) return nullptr;
  played->playback = std::make_unique<Playback>(std::move(playback).value());
  played->positions.resize(played->scene.model.vertices.size());
  return played;
}

double HingeDegrees(Played& played, double t) {
  EXPECT_TRUE(played.playback->Evaluate(t, played.positions, {}).ok());
  return played.playback->tracking()->JointAngles(1).x();
}

TEST(ArticulatedTracking, KeyedHingeFollowsTheCriticallyDampedResponse) {
  constexpr double kFrequency = 2.0;
  std::unique_ptr<Played> played = Play(ArmScene(kFrequency, 1.0));
  ASSERT_NE(played, nullptr);
  // The key steps to 40 degrees at 0.1 s: from the first fixed step at or after it.
  const double step = played->scene.description.playback.tracking.step;
  std::size_t k = 0;
  while (double(k) * step < 0.1) ++k;
  const double start = double(k) * step;
  const double w = 2.0 * std::numbers::pi * kFrequency;
  double worst = 0.0;
  for (double t = 0.15; t <= 1.6; t += 0.05) {
    const double s = std::floor(t / step + 1e-9) * step - start;  // the state's time
    const double expected = 40.0 * (1.0 - (1.0 + w * s) * std::exp(-w * s));
    worst = std::max(worst, std::abs(HingeDegrees(*played, t) - expected));
  }
  std::printf("[ measured ] worst %.4f degrees\n", worst);
  EXPECT_LT(worst, 0.5);  // degrees, of 40
}

TEST(ArticulatedTracking, LightDampingOvershootsByTheTextbookRatio) {
  constexpr double kZeta = 0.3;
  std::unique_ptr<Played> played = Play(ArmScene(2.0, kZeta));
  ASSERT_NE(played, nullptr);
  double peak = 0.0;
  for (double t = 0.1; t <= 1.1; t += 1.0 / 240.0) peak = std::max(peak, HingeDegrees(*played, t));
  const double overshoot = std::exp(-std::numbers::pi * kZeta / std::sqrt(1.0 - kZeta * kZeta));
  std::printf("[ measured ] overshoot %.4f, textbook %.4f\n", peak / 40.0 - 1.0, overshoot);
  EXPECT_NEAR(peak / 40.0 - 1.0, overshoot, 0.02);
}

TEST(ArticulatedTracking, ScrubbingGivesTheSameFrames) {
  std::unique_ptr<Played> played = Play(ArmScene(3.0, 0.5));
  ASSERT_NE(played, nullptr);
  ASSERT_TRUE(played->playback->Evaluate(1.3, played->positions, {}).ok());
  const std::vector<Vec3> first = played->positions;
  ASSERT_TRUE(played->playback->Evaluate(0.2, played->positions, {}).ok());
  ASSERT_TRUE(played->playback->Evaluate(1.3, played->positions, {}).ok());
  EXPECT_EQ(played->positions, first);
}

// The lower segment's PD stiffness about the hinge: kp = (2 pi f)^2 I, I its inertia about the
// hinge (from its mass properties; body axes: X is the hinge).
double HingeStiffness(const Played& played, double frequency) {
  const ArticulatedBodyDesc& lower = played.playback->tracking()->model().body(1);
  const Vec3 c = lower.center_of_mass;
  const double inertia = lower.inertia(0, 0) + lower.mass * (c.y() * c.y() + c.z() * c.z());
  return std::pow(2.0 * std::numbers::pi * frequency, 2) * inertia;
}

// The hinge at time t holds `balance` (rad, a visible turn), to 1%.
void ExpectHingeAt(Played& played, double t, double balance) {
  const double simulated = std::abs(HingeDegrees(played, t)) * std::numbers::pi / 180.0;
  std::printf("[ measured ] hinge %.5f rad, balance %.5f rad\n", simulated, balance);
  EXPECT_GT(balance, 0.05);
  EXPECT_NEAR(simulated, balance, 0.01 * balance);
}

// A keyed force at the lower segment's tip, fixed in the world across the arm, holds the hinge
// where the PD spring balances its moment: kp |phi| = F L cos(phi).
TEST(ArticulatedTracking, KeyedForceBalancesTheTrackingSpring) {
  constexpr double kFrequency = 2.0, kForce = 4.0;
  json scene = ArmScene(kFrequency, 1.0);
  scene["clips"][0]["parts"][0].erase("joint_angles");
  scene["clips"][0]["parts"][0]["rigid_forces"] = {
      {{"at", {0, 0.0, 0}}, {"force", {{"keys", {{0, {0, 0, kForce}}}}}}}};
  std::unique_ptr<Played> played = Play(scene);
  ASSERT_NE(played, nullptr);
  const ArticulatedModel& model = played->playback->tracking()->model();
  const double kp = HingeStiffness(*played, kFrequency);
  // The joint's world position (the root's frame is the world's axes at its joint) down to the
  // force's point (0, 0, 0).
  const double arm = (model.body(0).joint_position + model.body(1).joint_position).y();
  double phi = 0.0;  // kp phi = F L cos(phi), by fixed-point iteration
  for (int k = 0; k < 50; ++k) phi = kForce * arm * std::cos(phi) / kp;
  ExpectHingeAt(*played, 3.0, phi);
}

// A keyed torque about the hinge holds it where the PD spring balances it: kp |phi| = T.
TEST(ArticulatedTracking, KeyedTorqueBalancesTheTrackingSpring) {
  constexpr double kFrequency = 2.0, kTorque = 2.0;
  json scene = ArmScene(kFrequency, 1.0);
  scene["clips"][0]["parts"][0].erase("joint_angles");
  scene["clips"][0]["parts"][0]["rigid_torque"] = {{"keys", {{0, {kTorque, 0, 0}}}}};
  std::unique_ptr<Played> played = Play(scene);
  ASSERT_NE(played, nullptr);
  ExpectHingeAt(*played, 3.0, kTorque / HingeStiffness(*played, kFrequency));
}

// Gravity across the hanging arm (along -Z, the hinge about X) swings the lower segment until
// the PD spring balances its weight's moment: kp |phi| = m g d cos(phi), d the distance of the
// segment's centre of mass from the hinge (it hangs straight below the joint at rest).
TEST(ArticulatedTracking, GravityBalancesTheTrackingSpring) {
  constexpr double kFrequency = 1.2, kGravity = 9.81;
  json scene = ArmScene(kFrequency, 1.0);
  scene["clips"][0]["parts"][0].erase("joint_angles");
  scene["playback"]["tracking"]["gravity"] = {0, 0, -kGravity};
  std::unique_ptr<Played> played = Play(scene);
  ASSERT_NE(played, nullptr);
  const ArticulatedBodyDesc& lower = played->playback->tracking()->model().body(1);
  const double d = std::hypot(lower.center_of_mass.y(), lower.center_of_mass.z());
  const double kp = HingeStiffness(*played, kFrequency);
  double phi = 0.0;  // kp phi = m g d cos(phi), by fixed-point iteration
  for (int k = 0; k < 50; ++k) phi = lower.mass * kGravity * d * std::cos(phi) / kp;
  ExpectHingeAt(*played, 5.0, phi);
}

TEST(ArticulatedTracking, BadOptionsAreRefusedNamingTheField) {
  json scene = ArmScene(2.0, 1.0);
  scene["playback"]["tracking"]["frequency"] = -1;
  Result<SceneDescription> parsed = ParseScene(scene, ".");
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error(), "/playback/tracking/frequency: must be in (0, 100] Hz");
  scene = ArmScene(2.0, 1.0);
  scene["playback"]["tracking"]["damping_ratio"] = "high";
  EXPECT_FALSE(ParseScene(scene, ".").ok());
  scene = ArmScene(2.0, 1.0);
  scene["playback"]["tracking"]["stiffness"] = 3;
  parsed = ParseScene(scene, ".");
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error(),
            "/playback/tracking/stiffness: unknown field (known fields: frequency, "
            "damping_ratio, gravity)");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
