// Profile wires with inertia (the skin jiggles) against textbook answers: a body pushed at a
// constant acceleration a leaves each of its profile loops, a wire clamped at its first point
// under the inertial load -rho A a whose first mode swings at the flesh's frequency at its
// perimeter L, f_L = f (1 m / L), settled at the closed form of that load (midspan
// w L^4 / 384 EI = a beta_1^4 / (384 (2 pi f_L)^2), BendingJob's exact solution everywhere);
// on the way the loop overshoots and swings at f_L;
// scrubbing back gives the state of a fresh playback; a still clip leaves the skin at rest.
#include "wirerig/anim/profile_dynamics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "anim_test_rigs.h"
#include "wirerig/anim/playback.h"
#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/spine_interpolation.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using testing::Constant;

struct Pushed {
  RigModel model;
  Clip clip;
  double a = 0.0;                // m/s^2 along +X
  double mass_per_length = 0.0;  // of the base's profile wires
  double frequency = 5.0;        // Hz, of a loop of 1 m perimeter (the option)
  double period = 0.0;           // s, of the middle loop's first mode
};

double Perimeter(const ProfileModel& profile) {
  const std::size_t m = profile.local_points.size();
  double length = 0.0;
  for (std::size_t q = 0; q < m; ++q)
    length += (profile.local_points[(q + 1) % m] - profile.local_points[q]).norm();
  return length;
}

// The base of `model` pushed by a constant force `push` (N) along +X at its centre.
Clip PushClip(const RigModel& model, double push, double duration) {
  RawClip raw;
  raw.name = "push";
  raw.duration = duration;
  RawPartTracks part;
  part.part = "base";
  RigidForceChannels<RawTrack> force;
  force.at = model.parts[0].mass.center;
  force.force = Constant(Vec3(push, 0, 0));
  part.channels.rigid_forces.push_back(force);
  raw.parts.push_back(part);
  return BuildClip(raw, model).value();
}

// The jointed cylinder's base as a free rigid body pushed along +X at its centre.
Pushed PushedBase() {
  static const testing::TestRig jointed = testing::MakeJointedCylinderRig(SpineKind::kDeformable);
  Pushed out;
  out.model = jointed.model;
  out.model.parts[0].kind = SpineKind::kRigid;
  const PartModel& base = out.model.parts[0];
  double perimeters = 0.0;
  for (const ProfileModel& profile : base.profiles) perimeters += Perimeter(profile);
  out.mass_per_length = base.mass.mass / perimeters;
  out.period = Perimeter(base.profiles[base.profiles.size() / 2]) / out.frequency;
  const double push = 2.0 * base.mass.mass;  // N: 2 m/s^2
  out.a = push / base.mass.mass;
  out.clip = PushClip(out.model, push, 80.0 * out.period);
  return out;
}

PlaybackOptions WithProfileWires(const Pushed& pushed, int modes, double zeta) {
  PlaybackOptions options;
  options.rigid_step = pushed.period / 100.0;
  options.profile_wires.modes = modes;
  options.profile_wires.damping_ratio = zeta;
  options.profile_wires.frequency = pushed.frequency;
  return options;
}

// Profile `i` of the base, deformed, minus the same without profile wires, in the profile's
// rest frame axes (the base only translates: its frames keep their rest axes).
std::vector<Vec3> ProfileOffset(Playback& with, Playback& without, double t, std::size_t i) {
  std::vector<Vec3> positions(with.model().vertices.size());
  EXPECT_TRUE(with.Evaluate(t, positions, {}).ok());
  EXPECT_TRUE(without.Evaluate(t, positions, {}).ok());
  const PartModel& base = with.model().parts[0];
  Vec3 origin;
  const Mat3 axes = FrameAxes(
      InterpolateSpine(base.spine_points, base.spine_frames, base.profiles[i].spine_v, &origin));
  const std::vector<Vec3>& a = with.workspace().profile_points[0][i];
  const std::vector<Vec3>& b = without.workspace().profile_points[0][i];
  std::vector<Vec3> out(a.size());
  for (std::size_t q = 0; q < a.size(); ++q) out[q] = axes.transpose() * (a[q] - b[q]);
  return out;
}

TEST(ProfileDynamics, APushedBodysLoopsSettleAtTheClampedWiresInertialDeflection) {
  const Pushed pushed = PushedBase();
  const PartModel& base = pushed.model.parts[0];
  Playback with =
      Playback::Make(pushed.model, pushed.clip, WithProfileWires(pushed, 8, 0.4)).value();
  Playback without = Playback::Make(pushed.model, pushed.clip, PlaybackOptions{}).value();
  const std::size_t i = base.profiles.size() / 2;
  const ProfileModel& profile = base.profiles[i];
  const std::size_t m = profile.local_points.size();
  const double length = Perimeter(profile);
  const std::vector<Vec3> offset = ProfileOffset(with, without, pushed.clip.duration, i);
  // The reference: the loop as a clamped wire of its perimeter under w = -rho A a (frame axes).
  Vec3 origin;
  const Mat3 axes =
      FrameAxes(InterpolateSpine(base.spine_points, base.spine_frames, profile.spine_v, &origin));
  const Vec3 w = -pushed.mass_per_length * (axes.transpose() * Vec3(pushed.a, 0, 0));
  const LineLoad load{0.0, 1.0, w};
  // The flesh's EI: the clamped wire's first mode at f_L, omega_1 = beta_1^2 sqrt(EI / rho A L^4).
  const double beta = 4.730041, omega = 2.0 * std::numbers::pi * pushed.frequency / length;
  const double stiffness =
      pushed.mass_per_length * std::pow(length, 4) * omega * omega / std::pow(beta, 4);
  std::vector<double> v(m);
  for (std::size_t q = 0; q < m; ++q) v[q] = double(q) / double(m);
  std::vector<Vec3> reference(m);
  BendingJob bending;
  bending.boundary = BoundaryCondition::kClamped;
  bending.length = length;
  bending.bending_stiffness = stiffness;
  bending.line_loads = std::span<const LineLoad>(&load, 1);
  bending.samples = v;
  bending.displacement = reference;
  ASSERT_TRUE(bending.Run().ok());
  // Eased into the bound: limit times the loop's mean radius.
  double radius = 0.0;
  for (const Vec3& x : profile.local_points) radius += x.norm() / double(m);
  const double reach = ProfileWireOptions{}.limit * radius;
  const auto eased = [reach](double x) { return reach * std::tanh(x / reach); };
  const double midspan = eased(pushed.a * std::pow(beta, 4) / (384.0 * omega * omega));
  double worst = 0.0;
  for (std::size_t q = 0; q < m; ++q) {
    const double n = reference[q].norm();
    if (n > 0.0) reference[q] *= eased(n) / n;
    worst = std::max(worst, (offset[q] - reference[q]).norm());
  }
  std::printf(
      "[measure] pushed body's loop: midspan %.6e m (textbook w L^4/384EI = a beta^4 / 384 "
      "omega^2 %.6e), worst point off the closed form %.1e of it\n",
      offset[m / 2].norm(), midspan, worst / midspan);
  ASSERT_EQ(m % 2, 0u);
  EXPECT_NEAR(offset[m / 2].norm(), midspan, 1e-6 * midspan);
  EXPECT_LT(worst, 1e-6 * midspan);
  EXPECT_GT(midspan, 1e-4 * length);  // a deflection one can see
}

// However hard the body is shoved, no loop point moves further than the limit (of its mean
// radius), and a hard shove takes it nearly there; the end loops, where the part meets its
// neighbours, stay put.
TEST(ProfileDynamics, AHardShoveNeverMovesTheSkinBeyondItsLimit) {
  Pushed pushed = PushedBase();
  const PartModel& base = pushed.model.parts[0];
  pushed.clip = PushClip(pushed.model, 500.0 * base.mass.mass, 2.0 * pushed.period);  // 50 g
  PlaybackOptions options = WithProfileWires(pushed, 8, 0.1);
  options.profile_wires.limit = 0.1;
  Playback with = Playback::Make(pushed.model, pushed.clip, options).value();
  Playback without = Playback::Make(pushed.model, pushed.clip, PlaybackOptions{}).value();
  double worst = 0.0;  // of every loop's largest motion over its reach
  for (int k = 1; k <= 40; ++k)
    for (std::size_t i = 0; i < base.profiles.size(); ++i) {
      const ProfileModel& profile = base.profiles[i];
      double radius = 0.0;
      for (const Vec3& x : profile.local_points)
        radius += x.norm() / double(profile.local_points.size());
      for (const Vec3& d : ProfileOffset(with, without, 0.05 * k * pushed.period, i)) {
        worst = std::max(worst, d.norm() / (0.1 * radius));
        if (i == 0 || i + 1 == base.profiles.size()) {
          EXPECT_LT(d.norm(), 1e-12) << "loop " << i;  // rounding of the positions
        }
      }
    }
  std::printf("[measure] 50 g shove: the skin's largest motion %.4f of its limit\n", worst);
  EXPECT_LE(worst, 1.0 + 1e-9);  // rounding of the positions
  EXPECT_GT(worst, 0.9);
}

// Undamped enough to swing: on the way to the settled shape the loop overshoots it (a step
// response of a lightly damped oscillator peaks near 1 + exp(-pi zeta / sqrt(1 - zeta^2))),
// crossing it every half of the damped period 1 / (f sqrt(1 - zeta^2)).
TEST(ProfileDynamics, ALoopOvershootsAndSwingsAtTheFleshsFrequencyAndScrubbingBackIsFresh) {
  const Pushed pushed = PushedBase();
  const std::size_t i = pushed.model.parts[0].profiles.size() / 2;
  const PlaybackOptions options = WithProfileWires(pushed, 8, 0.1);
  Playback with = Playback::Make(pushed.model, pushed.clip, options).value();
  Playback without = Playback::Make(pushed.model, pushed.clip, PlaybackOptions{}).value();
  const std::size_t mid = pushed.model.parts[0].profiles[i].local_points.size() / 2;
  double peak = 0.0;
  for (int k = 1; k <= 80; ++k)
    peak = std::max(peak, ProfileOffset(with, without, 0.025 * k * pushed.period, i)[mid].norm());
  const double settled = ProfileOffset(with, without, pushed.clip.duration, i)[mid].norm();
  std::printf("[measure] loop's first peak %.3f x its settled deflection\n", peak / settled);
  EXPECT_GT(peak, 1.5 * settled);
  EXPECT_LT(peak, 2.0 * settled);
  // The crossings of the settled deflection, at every rigid step over three periods.
  std::vector<double> crossings;
  const double step = options.rigid_step;
  double before = -settled;
  for (int k = 1; k <= 300; ++k) {
    const double t = k * step;
    const double now = ProfileOffset(with, without, t, i)[mid].norm() - settled;
    if ((before < 0.0) != (now < 0.0)) crossings.push_back(t - step * now / (now - before));
    before = now;
  }
  ASSERT_GE(crossings.size(), 4u);
  const double damped = pushed.period / std::sqrt(1.0 - 0.1 * 0.1);
  const double measured = (crossings[3] - crossings[1]);
  std::printf("[measure] loop's period %.6f s (damped first mode %.6f s)\n", measured, damped);
  EXPECT_NEAR(measured, damped, 5e-3 * damped);
  // Back to an earlier time: the same as a fresh playback there.
  const double t = 0.37 * pushed.period;
  const std::vector<Vec3> scrubbed = ProfileOffset(with, without, t, i);
  Playback fresh = Playback::Make(pushed.model, pushed.clip, options).value();
  const std::vector<Vec3> first = ProfileOffset(fresh, without, t, i);
  for (std::size_t q = 0; q < first.size(); ++q) EXPECT_EQ(scrubbed[q], first[q]);
}

TEST(ProfileDynamics, AStillClipLeavesTheSkinAtRestAndBadOptionsAreNamed) {
  const testing::TestRig jointed = testing::MakeJointedCylinderRig(SpineKind::kDeformable);
  RawClip raw;
  raw.name = "still";
  raw.duration = 1.0;
  const Clip clip = BuildClip(raw, jointed.model).value();
  PlaybackOptions options;
  options.profile_wires.modes = 4;
  Playback with = Playback::Make(jointed.model, clip, options).value();
  EXPECT_FALSE(with.profile_wires().empty());
  Playback without = Playback::Make(jointed.model, clip, PlaybackOptions{}).value();
  std::vector<Vec3> a(jointed.model.vertices.size()), b(a.size());
  ASSERT_TRUE(with.Evaluate(0.6, a, {}).ok());
  ASSERT_TRUE(without.Evaluate(0.6, b, {}).ok());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k], b[k]);
  options.profile_wires.modes = 33;
  Result<Playback> bad = Playback::Make(jointed.model, clip, options);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().rfind("profile_wires: modes", 0), 0u) << bad.error();
  options.profile_wires.modes = 4;
  options.profile_wires.frequency = -1.0;
  EXPECT_EQ(Playback::Make(jointed.model, clip, options).error(),
            "profile_wires: frequency: must be in (0, 1000] Hz");
  options.profile_wires.frequency = 3.0;
  options.profile_wires.parts = {"bse"};  // a misspelt part gets the nearest name
  EXPECT_EQ(Playback::Make(jointed.model, clip, options).error(),
            "profile_wires: parts[0]: the rig has no part named \"bse\"; did you mean \"base\"? "
            "(parts: base, arm)");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
