// Wire dynamics in playback against textbook answers: a cantilever spine under a suddenly
// applied tip force swings about F L^3 / 3EI at its first natural frequency
// 1.8751^2 sqrt(EI / (rho A L^4)) (rho A = the part's mass over its length) and, damped,
// settles there; scrubbing back gives the state of a fresh playback; bad options are named.
#include "wirerig/anim/wire_dynamics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "anim_test_rigs.h"
#include "wirerig/anim/playback.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using testing::Constant;
using testing::Keys;

using testing::Beam;

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

// 6000 rigid steps over `duration` and wires of 8 modes, damping ratio 0.4.
PlaybackOptions FineStepsWithWires(double duration) {
  PlaybackOptions options;
  options.rigid_step = duration / 6000.0;
  options.wires.modes = 8;
  options.wires.damping_ratio = 0.4;
  return options;
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
  const PlaybackOptions options = FineStepsWithWires(duration);
  Playback playback = Playback::Make(model, clip, options).value();
  std::vector<Vec3> positions(model.vertices.size());
  ASSERT_TRUE(playback.Evaluate(duration, positions, {}).ok());
  const Vec3 shift = playback.bodies()[0].position - base.mass.center;
  const Vec3 tip = playback.workspace().spine_points[1].back() - arm.spine_points.back() - shift;
  EXPECT_NEAR(tip.x(), -expected, 1e-6 * expected);
  EXPECT_NEAR(tip.z(), 0.0, 1e-9 * expected);
  EXPECT_GT(expected, 1e-3 * length);  // a deflection one can see, not a rounding error
}

// The same push, keyed instead of simulated: the root's translation keyed as a t^2 / 2 along +X
// (cubic keys, exact for a quadratic between interior keys). The keyed motion's acceleration is
// the child's support acceleration, so (damped) it settles at the same rho A a L^4 / 8EI against
// the push; the same clip with static wires leaves the child straight.
TEST(WireDynamics, AKeyedParentsAccelerationLeavesItsChildTrailingByTheInertialLoad) {
  static const testing::TestRig jointed = testing::MakeJointedCylinderRig(SpineKind::kDeformable);
  const RigModel& model = jointed.model;
  const PartModel& arm = model.parts[1];
  ASSERT_EQ(arm.parent, 0);
  const double mass_per_length = arm.mass.mass / arm.spine_length;
  const double ei = arm.spine_stiffness.bending, length = arm.spine_length;
  const double omega =
      1.875104 * 1.875104 * std::sqrt(ei / (mass_per_length * std::pow(length, 4)));
  const double duration = 60.0 * 2.0 * std::numbers::pi / omega;
  const double a = 2e-3 * ei / (mass_per_length * std::pow(length, 3));  // tip ~ L / 4000
  const double expected = mass_per_length * a * std::pow(length, 4) / (8.0 * ei);
  RawClip raw;
  raw.name = "keyed push";
  raw.duration = duration;
  RawPartTracks part;
  part.part = "base";
  // Keys over the whole clip; the wire is looked at 0.9 of the way, far from the end segments
  // (whose one-sided tangents are not exact for a quadratic) and after ~50 damped periods.
  for (int k = 0; k <= 36; ++k) {
    const double t = duration * k / 36.0;
    part.channels.translation.keys.push_back(
        {t, Vec3(0.5 * a * t * t, 0.0, 0.0), Interpolation::kCubic});
  }
  raw.parts.push_back(part);
  Result<Clip> built = BuildClip(raw, model);
  ASSERT_TRUE(built.ok()) << built.error();
  const Clip& clip = built.value();
  const PlaybackOptions options = FineStepsWithWires(duration);
  Playback playback = Playback::Make(model, clip, options).value();
  std::vector<Vec3> positions(model.vertices.size());
  const double t = 0.9 * duration;
  ASSERT_TRUE(playback.Evaluate(t, positions, {}).ok());
  const Vec3 tip = playback.workspace().spine_points[1].back() - arm.spine_points.back() -
                   Vec3(0.5 * a * t * t, 0.0, 0.0);
  std::printf(
      "[measure] keyed push: child tip %.6e m against the push (expected %.6e, error "
      "%.1e)\n",
      -tip.x(), expected, std::abs(-tip.x() - expected) / expected);
  EXPECT_NEAR(tip.x(), -expected, 1e-6 * expected);
  EXPECT_NEAR(tip.z(), 0.0, 1e-6 * expected);
  EXPECT_GT(expected, 1e-4 * length);
  // Without wires the keyed push leaves the child straight: the lag is the wires' inertia.
  PlaybackOptions still = options;
  still.wires.modes = 0;
  Playback static_playback = Playback::Make(model, clip, still).value();
  ASSERT_TRUE(static_playback.Evaluate(t, positions, {}).ok());
  const Vec3 straight = static_playback.workspace().spine_points[1].back() -
                        arm.spine_points.back() - Vec3(0.5 * a * t * t, 0.0, 0.0);
  EXPECT_LT(straight.norm(), 1e-9 * length);
}

// A rigid root spun up from rest by a constant keyed torque tau about world z (a principal axis
// of the cylinder, so it turns at the constant alpha = tau / I_zz from Euler's equations, with
// omega along z) carries a deformable child hanging along -y from the root's lower end, h
// below the root's centre of mass. In the root's frame the point of the child at s from the
// joint accelerates by alpha x (r_joint + s t) = alpha (h + s) along +x (the centripetal part is
// along the child, not modelled), so the child (damped) settles lagging behind the turn by
//   rho A alpha (h L^4 / 8 + 11 L^5 / 120) / EI
// at its tip (the textbook uniform and triangular cantilever loads): first it lags, then it
// overshoots, then it settles.
TEST(WireDynamics, ASpunUpParentLeavesItsChildLaggingByTheTurningLoad) {
  static const testing::TestRig jointed = testing::MakeJointedCylinderRig(SpineKind::kDeformable);
  RigModel model = jointed.model;
  model.parts[0].kind = SpineKind::kRigid;  // the root: a free rigid body
  const PartModel &base = model.parts[0], &arm = model.parts[1];
  ASSERT_EQ(arm.parent, 0);
  const Vec3 joint = arm.spine_points.front();
  // The joint lies on the axis, h below the root's centre of mass.
  const double lever = base.mass.center.y() - joint.y();
  ASSERT_GT(lever, 0.0);
  ASSERT_LT(std::hypot(base.mass.center.x() - joint.x(), base.mass.center.z() - joint.z()),
            1e-9 * lever);
  const double mass_per_length = arm.mass.mass / arm.spine_length;
  const double ei = arm.spine_stiffness.bending, length = arm.spine_length;
  const double omega =
      1.875104 * 1.875104 * std::sqrt(ei / (mass_per_length * std::pow(length, 4)));
  // alpha from the rest inertia about the centre (world axes at rest), tau = I alpha.
  const Mat3& inertia = base.mass.inertia;
  const double alpha = 0.2 / length;  // rad/s^2: the tip accelerates ~0.2 m/s^2 across the arm
  const Vec3 torque = inertia * Vec3(0.0, 0.0, alpha);
  ASSERT_LT(std::abs(torque.x()) + std::abs(torque.y()), 1e-9 * torque.norm());  // z principal
  const double expected = mass_per_length * alpha *
                          (lever * std::pow(length, 4) / 8.0 + 11.0 * std::pow(length, 5) / 120.0) /
                          ei;
  const double duration = 60.0 * 2.0 * std::numbers::pi / omega;
  RawClip raw;
  raw.name = "spin";
  raw.duration = duration;
  RawPartTracks part;
  part.part = "base";
  part.channels.rigid_torque = Constant(torque);
  raw.parts.push_back(part);
  const Clip clip = BuildClip(raw, model).value();
  const PlaybackOptions options = FineStepsWithWires(duration);
  Playback playback = Playback::Make(model, clip, options).value();
  std::vector<Vec3> positions(model.vertices.size());
  // The tip's lag behind the rigid turn, along the turn's direction at the tip (the root's
  // rest x, turned with it); positive when it leads.
  const auto lag = [&](double t) -> Vec3 {
    EXPECT_TRUE(playback.Evaluate(t, positions, {}).ok());
    const PartPose& pose = playback.sample().poses[0];
    const Vec3 root = base.spine_points.front();
    const Mat3 r = pose.rotation.toRotationMatrix();
    const Vec3 rigid_tip = r * (arm.spine_points.back() - root) + root + pose.translation;
    return r.transpose() * (playback.workspace().spine_points[1].back() - rigid_tip);
  };
  const double period = 2.0 * std::numbers::pi / omega;
  double peak = 0.0;
  for (int i = 1; i <= 40; ++i) peak = std::min(peak, lag(i * period / 40.0).x());
  // Right after the torque starts the child is still nearly straight in the turning frame.
  EXPECT_LT(std::abs(lag(0.02 * period).x()), 0.05 * expected);
  const Vec3 settled = lag(duration);
  const RigidBodyState& body = playback.bodies()[0];
  const Vec3 spin = body.orientation * body.angular_velocity;  // alpha t (Euler's equations)
  EXPECT_LT((spin - Vec3(0.0, 0.0, alpha * duration)).norm(), 1e-9 * alpha * duration);
  // First overshoot of the first mode alone: 1 + exp(-pi zeta / sqrt(1 - zeta^2)) = 1.254.
  const double overshoot = 1.0 + std::exp(-std::numbers::pi * 0.4 / std::sqrt(1.0 - 0.16));
  std::printf(
      "[measure] spun-up parent: child tip lag %.6e m (expected %.6e, error %.1e), first "
      "overshoot %.3f x (first mode alone %.3f), parent at %.1f rad/s after %.0f s\n",
      -settled.x(), expected, std::abs(settled.x() / -expected - 1.0), peak / -expected, overshoot,
      spin.z(), duration);
  EXPECT_NEAR(settled.x(), -expected, 1e-6 * expected);
  EXPECT_NEAR(settled.z(), 0.0, 1e-9 * expected);
  EXPECT_NEAR(peak / -expected, overshoot, 0.03);  // it lags, overshoots, then settles
  EXPECT_GT(expected, 1e-3 * length);
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

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
