// Large curls in the rig's evaluation (SpineLoads::large_deflection) and reach targets in clips
// (clip_reach.h), against independent answers: a tip couple bends a uniform cantilever into a
// circular arc of radius EI / M (exact elastica), a perpendicular tip force into the elliptic-
// integral elastica (tests/support/elastica_reference.h), small loads reproduce the linear
// closed form, and a reach puts the spine's tip on its target.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "anim_test_rigs.h"
#include "support/elastica_reference.h"
#include "wirerig/anim/playback.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using testing::Constant;
using testing::Keys;

using testing::Beam;

// The spine (points and frames, world) of the beam under `loads`.
struct Spine {
  std::vector<Vec3> points;
  std::vector<Frame> frames;
};
Spine Evaluate(const SpineLoads& loads) {
  const RigModel& model = Beam().model;
  RigWorkspace workspace = MakeRigWorkspace(model);
  std::vector<PartPose> poses(1);
  poses[0].loads = loads;
  std::vector<Vec3> positions(model.vertices.size());
  EvaluateRigJob job;
  job.model = &model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  const Status status = job.Run();
  EXPECT_TRUE(status.ok()) << ToString(status);
  return {workspace.spine_points[0], workspace.spine_frames[0]};
}

// A sample's position relative to the root in the root's rest (tangent, normal) plane.
struct Planar {
  double along, across;
};
Planar InPlane(const Spine& spine, std::size_t k) {
  const PartModel& beam = Beam().model.parts[0];
  const Frame& f = beam.spine_frames.front();
  const Vec3 d = spine.points[k] - beam.spine_points.front();
  return {d.dot(f.tangent), d.dot(f.normal)};
}

double Length() { return Beam().model.parts[0].spine_length; }
double Stiffness() { return Beam().model.parts[0].spine_stiffness.bending; }

TEST(LargeCurl, ATipCoupleCurlsTheSpineOntoItsExactCircleWellPastAFullTurn) {
  const double length = Length();
  for (const double turns : {0.25, 0.5, 1.0, 1.5}) {
    const double angle = 2.0 * std::numbers::pi * turns;  // tip rotation M L / EI
    SpineLoads loads;
    loads.tip_couple = Vec3(angle * Stiffness() / length, 0.0, 0.0);
    loads.large_deflection = true;
    const Spine spine = Evaluate(loads);
    const double radius = length / angle;
    const std::size_t n = spine.points.size();
    const PartModel& beam = Beam().model.parts[0];
    for (std::size_t k = 0; k < n; ++k) {
      // Arc length s = v L turns the tangent by s / R: the point (R sin, R (1 - cos)).
      const double theta = angle * double(k) / double(n - 1);
      const Planar p = InPlane(spine, k);
      EXPECT_NEAR(p.along, radius * std::sin(theta), 2e-4 * length) << turns << " " << k;
      EXPECT_NEAR(p.across, radius * (1.0 - std::cos(theta)), 2e-4 * length) << turns << " " << k;
      // The frame turned by theta about the binormal, without flipping past half a turn.
      const Frame& rest = beam.spine_frames[k];
      const Vec3 expected = std::cos(theta) * rest.tangent + std::sin(theta) * rest.normal;
      EXPECT_NEAR((spine.frames[k].tangent - expected).norm(), 0.0, 1e-9) << turns << " " << k;
      EXPECT_NEAR((spine.frames[k].binormal - rest.binormal).norm(), 0.0, 1e-9);
    }
  }
}

TEST(LargeCurl, APerpendicularTipForceBendsTheSpineIntoTheExactElastica) {
  const double length = Length();
  for (const double degrees : {30.0, 60.0, 80.0}) {
    const testing::ElasticaTip exact =
        testing::ExactElasticaTip(std::numbers::pi / 2.0, degrees * std::numbers::pi / 180.0);
    SpineLoads loads;
    loads.tip_force = Vec3(0.0, exact.alpha * Stiffness() / (length * length), 0.0);
    loads.large_deflection = true;
    loads.curl_segments = 128;
    const Spine spine = Evaluate(loads);
    const PartModel& beam = Beam().model.parts[0];
    const Frame& f = beam.spine_frames.front();
    const Vec3 d = spine.points.back() - beam.spine_points.front();
    EXPECT_NEAR(d.dot(f.tangent), exact.x * length, 1e-4 * length) << degrees;
    EXPECT_NEAR(d.dot(f.binormal), exact.y * length, 1e-4 * length) << degrees;
    EXPECT_NEAR(d.dot(f.normal), 0.0, 1e-12) << degrees;
  }
}

TEST(LargeCurl, SmallLoadsGiveTheLinearClosedForm) {
  SpineLoads loads;
  loads.tip_force = Vec3(1e-6, -2e-6, 0.0) * Stiffness() / (Length() * Length());
  const LineLoad line{0.2, 0.9, Vec3(3e-6, 1e-6, 0.0) * Stiffness() / std::pow(Length(), 3)};
  loads.bending_line_loads = std::span<const LineLoad>(&line, 1);
  const Spine linear = Evaluate(loads);
  loads.large_deflection = true;
  const Spine curled = Evaluate(loads);
  const PartModel& beam = Beam().model.parts[0];
  for (std::size_t k = 0; k < linear.points.size(); ++k) {
    const Vec3 rest_offset = linear.points[k] - beam.spine_points[k];
    EXPECT_NEAR((curled.points[k] - linear.points[k]).norm(), 0.0,
                1e-6 * rest_offset.norm() + 1e-15)
        << k;
    EXPECT_NEAR((curled.frames[k].tangent - linear.frames[k].tangent).norm(), 0.0, 1e-10) << k;
  }
}

TEST(LargeCurl, OnlyCantileversCurlAndTheCoupleOnlyOnAFreeTip) {
  const RigModel& model = Beam().model;
  RigWorkspace workspace = MakeRigWorkspace(model);
  std::vector<PartPose> poses(1);
  std::vector<Vec3> positions(model.vertices.size());
  EvaluateRigJob job;
  job.model = &model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  poses[0].loads.boundary = BoundaryCondition::kClamped;
  poses[0].loads.large_deflection = true;
  Status status = job.Run();
  EXPECT_EQ(status.field, "poses");
  EXPECT_NE(ToString(status).find("cantilever"), std::string::npos) << ToString(status);
  poses[0].loads.boundary = BoundaryCondition::kCantileverGuided;
  poses[0].loads.tip_couple = Vec3(1.0, 0.0, 0.0);
  status = job.Run();
  EXPECT_EQ(status.field, "poses");
  EXPECT_NE(ToString(status).find("free cantilevers"), std::string::npos) << ToString(status);
}

// A clip reaching the beam's tip for a world point.
Clip ReachClip(const Vec3& target, bool large) {
  RawClip raw;
  raw.name = "reach";
  raw.duration = 1.0;
  RawPartTracks part;
  part.part = "beam";
  part.channels.large_deflection = large;
  part.channels.reach.target = Constant(target);
  // A load the reach replaces as its weight comes in.
  LineLoadChannels<RawTrack> line;
  line.force_per_length = Constant(Vec3(0.0, 0.05 * Stiffness(), 0.0));
  part.channels.line_loads.push_back(line);
  part.channels.reach.weight = Keys({{0.0, 0.0}, {0.5, 1.0}});
  raw.parts.push_back(part);
  Result<Clip> clip = BuildClip(raw, Beam().model);
  EXPECT_TRUE(clip.ok()) << clip.error();
  return std::move(clip).value();
}

Vec3 TipAt(const Clip& clip, double t, ReachReport* report) {
  Result<Playback> playback = Playback::Make(Beam().model, clip);
  EXPECT_TRUE(playback.ok()) << playback.error();
  std::vector<Vec3> positions(Beam().model.vertices.size());
  const Status status = playback.value().Evaluate(t, positions, {});
  EXPECT_TRUE(status.ok()) << ToString(status);
  *report = playback.value().reach().reports()[0];
  return playback.value().workspace().spine_points[0].back();
}

TEST(LargeCurl, AReachPutsTheTipOnReachableTargetsAndSaysWhenItCannot) {
  const double length = Length();
  const PartModel& beam = Beam().model.parts[0];
  const Vec3 root = beam.spine_points.front();
  const Frame& f = beam.spine_frames.front();
  ReachReport report;
  // Small deflection: a lateral offset of 5% of the length.
  const Vec3 near =
      beam.spine_points.back() + 0.05 * length * f.normal - 0.02 * length * f.binormal;
  Vec3 tip = TipAt(ReachClip(near, false), 0.75, &report);
  EXPECT_TRUE(report.reached_target);
  EXPECT_NEAR((tip - near).norm(), 0.0, 1e-9 * length);
  // Large curls: the tips of exact elasticas (a tip force perpendicular to the root, and one
  // pointing back at 135 degrees), reachable by construction.
  Vec3 far = Vec3::Zero();
  for (const auto& [beta, degrees] : {std::pair{90.0, 70.0}, std::pair{135.0, 120.0}}) {
    const testing::ElasticaTip exact = testing::ExactElasticaTip(
        beta * std::numbers::pi / 180.0, degrees * std::numbers::pi / 180.0);
    far = root + exact.x * length * f.tangent + exact.y * length * f.binormal;
    tip = TipAt(ReachClip(far, true), 0.75, &report);
    EXPECT_TRUE(report.reached_target) << degrees << ": missed by " << report.miss;
    EXPECT_NEAR((tip - far).norm(), 0.0, 1e-9 * length) << degrees;
  }
  // Halfway in, the weight is one half: the tip has not arrived.
  tip = TipAt(ReachClip(far, true), 0.25, &report);
  EXPECT_DOUBLE_EQ(report.weight, 0.5);
  EXPECT_GT((tip - far).norm(), 0.05 * length);
  // Beyond the wire's length: the closest point, and why.
  const Vec3 beyond = root + 1.3 * length * f.tangent + 0.3 * length * f.normal;
  tip = TipAt(ReachClip(beyond, true), 0.75, &report);
  EXPECT_FALSE(report.reached_target);
  EXPECT_TRUE(report.beyond_length);
  EXPECT_GT(report.miss, 0.3 * length);
  EXPECT_NEAR((tip - beyond).norm(), report.miss, 1e-6 * length);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
