// Wire dynamics in playback against textbook answers: a cantilever spine under a suddenly
// applied tip force swings about F L^3 / 3EI at its first natural frequency
// 1.8751^2 sqrt(EI / (rho A L^4)) (rho A = the part's mass over its length) and, damped,
// settles there; scrubbing back gives the state of a fresh playback; bad options are named.
#include "wirerig/anim/wire_dynamics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "anim_test_rigs.h"
#include "wirerig/anim/playback.h"

namespace wirerig {
namespace {

using testing::Constant;
using testing::Keys;

const testing::TestRig& Beam() {
  static const testing::TestRig rig = testing::MakeCylinderRig(SpineKind::kDeformable);
  return rig;
}

// A tip force switched on over the first millisecond and held.
Clip StepLoadClip(double force, double duration) {
  RawClip raw;
  raw.name = "step";
  raw.duration = duration;
  RawPartTracks part;
  part.part = "beam";
  PointLoadChannels<RawTrack> load;
  load.at = Keys({{0.0, 1.0}});
  load.magnitude = Keys({{0.0, 0.0}, {1e-3, force}, {duration, force}});
  load.direction = Constant(Vec3(1, 0, 0));
  part.channels.point_loads.push_back(load);
  raw.parts.push_back(part);
  return BuildClip(raw, Beam().model).value();
}

struct BeamNumbers {
  double length, ei, mass_per_length, static_tip, omega;
};
BeamNumbers Numbers(double force) {
  const PartModel& beam = Beam().model.parts[0];
  BeamNumbers n;
  n.length = beam.spine_length;
  n.ei = beam.spine_stiffness.bending;
  n.mass_per_length = beam.mass.mass / beam.spine_length;
  n.static_tip = force * std::pow(n.length, 3) / (3.0 * n.ei);
  n.omega = 1.875104 * 1.875104 * std::sqrt(n.ei / (n.mass_per_length * std::pow(n.length, 4)));
  return n;
}

double TipDeflection(Playback& playback, double t) {
  std::vector<Vec3> positions(Beam().model.vertices.size());
  const Status status = playback.Evaluate(t, positions, {});
  EXPECT_TRUE(status.ok()) << ToString(status);
  const PartModel& beam = Beam().model.parts[0];
  return (playback.workspace().spine_points[0].back() - beam.spine_points.back())
      .dot(beam.spine_frames.back().normal);
}

TEST(WireDynamics, ASuddenTipForceSwingsAtTheFirstNaturalFrequency) {
  const double force = 1e-3;
  const BeamNumbers n = Numbers(force);
  ASSERT_GT(n.mass_per_length, 0.0);
  const double period = 2.0 * std::numbers::pi / n.omega;
  const Clip clip = StepLoadClip(force, 3.0 * period);
  PlaybackOptions options;
  options.rigid_step = period / 2000.0;
  options.wires.modes = 8;
  options.wires.damping_ratio = 0.0;
  Playback playback = Playback::Make(Beam().model, clip, options).value();
  // Crossings of the static deflection, upwards, over three periods.
  std::vector<double> crossings;
  double previous = TipDeflection(playback, 0.0) - n.static_tip, peak = 0.0;
  const int steps = 6000;
  for (int i = 1; i <= steps; ++i) {
    const double t = 3.0 * period * i / steps;
    const double x = TipDeflection(playback, t) - n.static_tip;
    peak = std::max(peak, x + n.static_tip);
    if (previous < 0.0 && x >= 0.0) crossings.push_back(t - x / (x - previous) * (t / i));
    previous = x;
  }
  ASSERT_GE(crossings.size(), 2u);
  const double measured = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  // The tip's motion is mostly the first mode: its period within 1% (higher modes shift the
  // crossings a little); an undamped step response overshoots to about twice the static tip.
  EXPECT_NEAR(measured / period, 1.0, 0.01);
  EXPECT_GT(peak, 1.6 * n.static_tip);
  EXPECT_LT(peak, 2.1 * n.static_tip);
}

TEST(WireDynamics, DampedWireSettlesOnTheStaticClosedForm) {
  const double force = 1e-3;
  const BeamNumbers n = Numbers(force);
  const double period = 2.0 * std::numbers::pi / n.omega;
  const Clip clip = StepLoadClip(force, 40.0 * period);
  PlaybackOptions options;
  options.rigid_step = period / 200.0;
  options.wires.modes = 8;
  options.wires.damping_ratio = 0.3;
  Playback playback = Playback::Make(Beam().model, clip, options).value();
  EXPECT_NEAR(TipDeflection(playback, 40.0 * period), n.static_tip, 1e-9 * n.static_tip);
  // Scrubbing back to an earlier time gives what a fresh playback gives there.
  const double early = 0.5 * period / std::sqrt(1.0 - 0.09);  // the first overshoot
  const double scrubbed = TipDeflection(playback, early);
  Playback fresh = Playback::Make(Beam().model, clip, options).value();
  EXPECT_EQ(TipDeflection(fresh, early), scrubbed);
  EXPECT_GT(scrubbed - n.static_tip, 0.2 * n.static_tip);  // exp(-0.3 pi / 0.954) = 0.37
}

// A rigid root pushed sideways at constant acceleration a carries a deformable child: in the
// root's frame the child feels the inertial line load -rho A a, and (damped) settles at its
// static shape, tip deflection rho A a L^4 / 8EI against the push.
TEST(WireDynamics, AnAcceleratingParentLeavesItsChildTrailingByTheInertialLoad) {
  static const testing::TestRig jointed = testing::MakeJointedCylinderRig(SpineKind::kDeformable);
  RigModel model = jointed.model;
  model.parts[0].kind = SpineKind::kRigid;  // the base: a free rigid body
  const PartModel &base = model.parts[0], &arm = model.parts[1];
  ASSERT_EQ(arm.parent, 0);
  const double push = 0.1;  // N at the base's centre, along +X (across the arm)
  const double a = push / base.mass.mass;
  const double mass_per_length = arm.mass.mass / arm.spine_length;
  const double ei = arm.spine_stiffness.bending, length = arm.spine_length;
  const double expected = mass_per_length * a * std::pow(length, 4) / (8.0 * ei);
  const double omega =
      1.875104 * 1.875104 * std::sqrt(ei / (mass_per_length * std::pow(length, 4)));
  const double duration = 60.0 * 2.0 * std::numbers::pi / omega;
  RawClip raw;
  raw.name = "push";
  raw.duration = duration;
  RawPartTracks part;
  part.part = "base";
  RigidForceChannels<RawTrack> force;
  force.at = base.mass.center;
  force.force = Constant(Vec3(push, 0, 0));
  part.channels.rigid_forces.push_back(force);
  raw.parts.push_back(part);
  const Clip clip = BuildClip(raw, model).value();
  PlaybackOptions options;
  options.rigid_step = duration / 6000.0;
  options.wires.modes = 8;
  options.wires.damping_ratio = 0.4;
  Playback playback = Playback::Make(model, clip, options).value();
  std::vector<Vec3> positions(model.vertices.size());
  ASSERT_TRUE(playback.Evaluate(duration, positions, {}).ok());
  const Vec3 shift = playback.bodies()[0].position - base.mass.center;
  const Vec3 tip = playback.workspace().spine_points[1].back() - arm.spine_points.back() - shift;
  EXPECT_NEAR(tip.x(), -expected, 1e-6 * expected);
  EXPECT_NEAR(tip.z(), 0.0, 1e-9 * expected);
  EXPECT_GT(expected, 1e-3 * length);  // a deflection one can see, not a rounding error
}

TEST(WireDynamics, StaticWiresWithoutModesAndBadOptionsNamed) {
  const Clip clip = StepLoadClip(1e-3, 1.0);
  PlaybackOptions options;
  EXPECT_TRUE(WireDynamics::Make(Beam().model, clip, options.wires, 0.01).value().empty());
  options.wires.modes = 33;
  EXPECT_EQ(Playback::Make(Beam().model, clip, options).error(),
            "wires: modes: must be in [0, 32]");
  options.wires.modes = 8;
  options.wires.damping_ratio = -0.1;
  EXPECT_EQ(Playback::Make(Beam().model, clip, options).error(),
            "wires: damping_ratio: must be in [0, 100]");
}

}  // namespace
}  // namespace wirerig
