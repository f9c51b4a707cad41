// Clips: the raw rules and the rig's rules name what is wrong; loop modes map time; sampling
// turns tracks into the runtime's loads exactly as documented.
#include "wirerig/anim/clip.h"
#include "wirerig/anim/clip_json.h"
#include "wirerig/io/json_fields.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <numbers>

#include "anim_test_rigs.h"
#include "wirerig/anim/clip_sampling.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using testing::Constant;
using testing::Keys;

RawClip PointLoadClip() {
  RawClip raw;
  raw.name = "push";
  raw.duration = 2.0;
  RawPartTracks part;
  part.part = "beam";
  PointLoadChannels<RawTrack> load;
  load.at = Keys({{0.0, 1.0}});
  load.magnitude = Keys({{0.0, 0.0}, {2.0, 10.0}});
  load.direction = Constant(Vec3(2, 0, 0));
  part.channels.point_loads.push_back(load);
  raw.parts.push_back(part);
  return raw;
}

using testing::Beam;

TEST(Clip, BuildsAgainstTheRigAndCollectsKeyTimes) {
  Result<Clip> clip = BuildClip(PointLoadClip(), Beam().model);
  ASSERT_TRUE(clip.ok()) << clip.error();
  EXPECT_EQ(clip.value().parts.size(), 1u);
  EXPECT_EQ(clip.value().key_times, (std::vector<double>{0.0, 2.0}));
  EXPECT_FALSE(clip.value().HasDynamics());
}

TEST(Clip, RefusesUnknownPartsAndProfilesByName) {
  RawClip raw = PointLoadClip();
  raw.parts[0].part = "tentacle";
  EXPECT_EQ(BuildClip(raw, Beam().model).error(),
            "parts[0].part: no part of the rig is named \"tentacle\" (parts: beam)");
  raw = PointLoadClip();
  RawProfileTracks bulge;
  bulge.part = "beam";
  bulge.channels.profiles = {1, 99};
  raw.profiles.push_back(bulge);
  const std::string error = BuildClip(raw, Beam().model).error();
  EXPECT_EQ(error.rfind("profiles[0].profiles[1]: part \"beam\" has", 0), 0u) << error;
}

TEST(Clip, RefusesKeysOutsideTheDuration) {
  RawClip raw = PointLoadClip();
  raw.parts[0].channels.point_loads[0].magnitude = Keys({{0.0, 0.0}, {2.5, 1.0}});
  EXPECT_EQ(ValidateRawClip(raw),
            "parts[0].point_loads[0].magnitude.keys[1].time: must lie within the clip, [0, "
            "duration]");
}

TEST(Clip, RefusesBrokenTracksDurationsAndDuplicates) {
  RawClip raw = PointLoadClip();
  raw.parts[0].channels.point_loads[0].at = Keys({{1.0, 0.5}, {0.5, 0.5}});
  EXPECT_EQ(ValidateRawClip(raw),
            "parts[0].point_loads[0].at.keys[1].time: key times must be strictly increasing");
  raw = PointLoadClip();
  raw.duration = 0.0;
  EXPECT_EQ(ValidateRawClip(raw), "duration: must be positive and at most 1e6 (s)");
  raw.duration = 1e308;  // finite, but no file holds its keys
  EXPECT_EQ(ValidateRawClip(raw), "duration: must be positive and at most 1e6 (s)");
  raw = PointLoadClip();
  raw.parts.push_back(raw.parts[0]);
  EXPECT_EQ(ValidateRawClip(raw), "parts[1].part: this part already has tracks in the clip");
  raw = PointLoadClip();
  raw.name.clear();
  EXPECT_EQ(ValidateRawClip(raw), "name: a clip needs a name");
  raw = PointLoadClip();
  raw.parts[0].channels.boundary = {{1.0, BoundaryCondition::kClamped},
                                    {1.0, BoundaryCondition::kSimplySupported}};
  EXPECT_EQ(ValidateRawClip(raw),
            "parts[0].boundary[1].time: key times must be strictly increasing");
}

// Loads that would never act are refused, naming the field: a point load without a direction,
// a line load whose stretch is empty at every key (from above to). One that closes at some
// keys only slides off: kept (LineLoadsOfZeroWidthAreSkippedAndPositionsClamped).
TEST(Clip, RefusesLoadsThatNeverAct) {
  RawClip raw = PointLoadClip();
  RawVectorTrack direction = Constant(Vec3(1, 0, 0));
  direction.keys.push_back({1.0, Vec3::Zero(), Interpolation::kStep});
  raw.parts[0].channels.point_loads[0].direction = direction;
  EXPECT_EQ(ValidateRawClip(raw),
            "parts[0].point_loads[0].direction.keys[1].value: must have a non-zero length (the "
            "force's direction)");
  raw = PointLoadClip();
  LineLoadChannels<RawTrack> line;
  line.from = Keys({{0.0, 0.9}});
  line.to = Keys({{0.0, 0.1}, {2.0, 0.3}});
  line.force_per_length = Constant(Vec3(0, 1, 0));
  raw.parts[0].channels.line_loads.push_back(line);
  EXPECT_EQ(ValidateRawClip(raw),
            "parts[0].line_loads[0].to: must be greater than from at some key, or the load "
            "never acts (at t = 0 s: from 0.9, to 0.1)");
  raw.parts[0].channels.line_loads[0].to = Keys({{0.0, 0.1}, {2.0, 1.0}});  // acts from 1.78 s
  EXPECT_EQ(ValidateRawClip(raw), "");
  RawProfileTracks bulge;
  bulge.part = "beam";
  bulge.channels.line_loads.push_back(line);
  bulge.channels.line_loads[0].from = Keys({{0.0, 1.5}});  // clamped to 1: nothing above it
  bulge.channels.line_loads[0].to.keys.clear();            // 1
  raw.profiles.push_back(bulge);
  EXPECT_EQ(ValidateRawClip(raw),
            "profiles[0].line_loads[0].to: must be greater than from at some key, or the load "
            "never acts (at t = 0 s: from 1, to 1)");
}

TEST(Clip, RefusesTranslationsBeyondReach) {
  RawClip raw = PointLoadClip();
  raw.parts[0].channels.translation = Constant(Vec3(0, 2e6, 0));
  EXPECT_EQ(ValidateRawClip(raw), "parts[0].translation.keys[0].value: beyond 1e6 m");
  raw.parts[0].channels.translation = Constant(Vec3(0, 1e5, 0));
  EXPECT_EQ(ValidateRawClip(raw), "");
}

TEST(Clip, RefusesRigidBodyForcesOnDeformableParts) {
  RawClip raw = PointLoadClip();
  raw.parts[0].channels.rigid_torque = Constant(Vec3(0, 1, 0));
  EXPECT_EQ(BuildClip(raw, Beam().model).error(),
            "parts[0].rigid_forces: rigid-body forces and torques need a rigid part");
}

TEST(Clip, RigidDragNeedsARigidPartAndSaneCoefficientsAndRoundTrips) {
  RawClip raw = PointLoadClip();
  raw.parts[0].channels.rigid_drag.linear = 2.0;
  EXPECT_EQ(BuildClip(raw, Beam().model).error(),
            "parts[0].rigid_forces: rigid-body forces and torques need a rigid part");
  raw.parts[0].channels.rigid_drag.quadratic = -1.0;
  EXPECT_EQ(ValidateRawClip(raw), "parts[0].rigid_drag/quadratic: must be finite, in [0, 1e9]");
  raw.parts[0].channels.rigid_drag = {0.5, 0.25, 0.125};
  const nlohmann::json saved = ClipToJson(raw);
  const RawClip loaded = ReadClip(JsonObject(saved, ""));
  EXPECT_EQ(loaded.parts[0].channels.rigid_drag.linear, 0.5);
  EXPECT_EQ(loaded.parts[0].channels.rigid_drag.quadratic, 0.25);
  EXPECT_EQ(loaded.parts[0].channels.rigid_drag.angular, 0.125);
}

// A track of the wrong type is told what it may be (it said "must be an object", though a
// number or [x, y, z] is what is usually written).
TEST(Clip, ATrackOfTheWrongTypeSaysWhatItMayBe) {
  nlohmann::json saved = ClipToJson(PointLoadClip());
  ASSERT_TRUE(saved["parts"][0]["point_loads"][0].contains("at")) << saved.dump();
  const auto error = [&] {
    try {
      ReadClip(JsonObject(saved, ""));
    } catch (const FieldError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  saved["parts"][0]["point_loads"][0]["at"] = "x";
  EXPECT_EQ(error(),
            "/parts/0/point_loads/0/at: must be a number or a track {\"keys\": [[time, value], "
            "...]}");
  saved = ClipToJson(PointLoadClip());
  saved["parts"][0]["point_loads"][0]["direction"] = "x";
  EXPECT_EQ(error(),
            "/parts/0/point_loads/0/direction: must be [x, y, z] or a track {\"keys\": [[time, "
            "[x, y, z]], ...]}");
}

TEST(Clip, LoopModesMapPlaybackTime) {
  Clip clip;
  clip.duration = 2.0;
  clip.loop = LoopMode::kOnce;
  EXPECT_EQ(clip.LocalTime(-1.0), 0.0);
  EXPECT_EQ(clip.LocalTime(1.5), 1.5);
  EXPECT_EQ(clip.LocalTime(3.0), 2.0);
  clip.loop = LoopMode::kLoop;
  EXPECT_DOUBLE_EQ(clip.LocalTime(5.5), 1.5);
  // Negative times loop back as positive ones do (they held the first frame).
  EXPECT_DOUBLE_EQ(clip.LocalTime(-0.5), 1.5);
  EXPECT_DOUBLE_EQ(clip.LocalTime(-4.5), 1.5);
  EXPECT_DOUBLE_EQ(clip.LocalTime(-2.0), 0.0);
  clip.loop = LoopMode::kPingPong;
  EXPECT_DOUBLE_EQ(clip.LocalTime(2.5), 1.5);
  EXPECT_DOUBLE_EQ(clip.LocalTime(4.5), 0.5);
  EXPECT_DOUBLE_EQ(clip.LocalTime(-1.0), 1.0);  // as +1: ping-pong is symmetric about 0
  EXPECT_DOUBLE_EQ(clip.LocalTime(-0.5), 0.5);
  EXPECT_DOUBLE_EQ(clip.LocalTime(-2.5), 1.5);
  for (LoopMode m : {LoopMode::kOnce, LoopMode::kLoop, LoopMode::kPingPong}) {
    LoopMode parsed = LoopMode::kOnce;
    ASSERT_TRUE(ParseLoopMode(ToString(m), &parsed));
    EXPECT_EQ(parsed, m);
  }
}

TEST(ClipSampling, PointLoadIsMagnitudeAlongTheUnitDirection) {
  const Clip clip = BuildClip(PointLoadClip(), Beam().model).value();
  ClipSample sample = MakeClipSample(clip, Beam().model);
  SampleClip(clip, 0.5, &sample);
  const SpineLoads& loads = sample.poses[0].loads;
  ASSERT_EQ(loads.bending_point_loads.size(), 1u);
  EXPECT_EQ(loads.bending_point_loads[0].at, 1.0);
  EXPECT_TRUE(loads.bending_point_loads[0].force.isApprox(Vec3(2.5, 0, 0), 1e-15));
  EXPECT_EQ(loads.boundary, BoundaryCondition::kCantileverFree);
  // At t = 0 the magnitude is zero: no load at all.
  SampleClip(clip, 0.0, &sample);
  EXPECT_TRUE(sample.poses[0].loads.bending_point_loads.empty());
}

TEST(ClipSampling, BoundaryKeysSwitchFamiliesAndDropTipForcesOffCantilevers) {
  RawClip raw = PointLoadClip();
  raw.parts[0].channels.boundary = {{0.0, BoundaryCondition::kCantileverFree},
                                    {1.0, BoundaryCondition::kSimplySupported}};
  raw.parts[0].channels.tip_force = Constant(Vec3(0, 0, 3));
  const Clip clip = BuildClip(raw, Beam().model).value();
  ClipSample sample = MakeClipSample(clip, Beam().model);
  SampleClip(clip, 0.99, &sample);
  EXPECT_EQ(sample.poses[0].loads.boundary, BoundaryCondition::kCantileverFree);
  EXPECT_EQ(sample.poses[0].loads.tip_force, Vec3(0, 0, 3));
  SampleClip(clip, 1.0, &sample);
  EXPECT_EQ(sample.poses[0].loads.boundary, BoundaryCondition::kSimplySupported);
  EXPECT_EQ(sample.poses[0].loads.tip_force, Vec3::Zero());
}

TEST(ClipSampling, LineLoadsOfZeroWidthAreSkippedAndPositionsClamped) {
  RawClip raw = PointLoadClip();
  LineLoadChannels<RawTrack> line;
  line.from = Keys({{0.0, 0.2}, {2.0, 0.8}});
  line.to = Keys({{0.0, 0.6}});
  line.force_per_length = Constant(Vec3(0, 1, 0));
  raw.parts[0].channels.line_loads.push_back(line);
  raw.parts[0].channels.point_loads[0].at = Keys({{0.0, 0.5}, {2.0, 1.5}});
  const Clip clip = BuildClip(raw, Beam().model).value();
  ClipSample sample = MakeClipSample(clip, Beam().model);
  SampleClip(clip, 0.5, &sample);  // from 0.35 < to 0.6
  ASSERT_EQ(sample.poses[0].loads.bending_line_loads.size(), 1u);
  EXPECT_DOUBLE_EQ(sample.poses[0].loads.bending_line_loads[0].from, 0.35);
  SampleClip(clip, 2.0, &sample);  // from 0.8 > to 0.6: skipped; at 1.5 clamped to 1
  EXPECT_TRUE(sample.poses[0].loads.bending_line_loads.empty());
  EXPECT_EQ(sample.poses[0].loads.bending_point_loads[0].at, 1.0);
}

TEST(ClipSampling, ProfileGroupsExpandToEveryProfileWhenNoneAreListed) {
  RawClip raw = PointLoadClip();
  RawProfileTracks bulge;
  bulge.part = "beam";
  bulge.channels.from = 0.25;
  bulge.channels.to = 0.75;
  PointLoadChannels<RawTrack> push;
  push.at = Keys({{0.0, 0.5}});
  push.magnitude = Keys({{0.0, 4.0}});
  push.direction = Constant(Vec3(1, 0, 0));
  bulge.channels.point_loads.push_back(push);
  raw.profiles.push_back(bulge);
  const Clip clip = BuildClip(raw, Beam().model).value();
  ClipSample sample = MakeClipSample(clip, Beam().model);
  SampleClip(clip, 1.0, &sample);
  ASSERT_EQ(sample.profile_loads.size(), Beam().model.parts[0].profiles.size());
  for (std::size_t k = 0; k < sample.profile_loads.size(); ++k) {
    EXPECT_EQ(sample.profile_loads[k].profile, k);
    EXPECT_EQ(sample.profile_loads[k].from, 0.25);
    ASSERT_EQ(sample.profile_loads[k].point_loads.size(), 1u);
    EXPECT_EQ(sample.profile_loads[k].point_loads[0].force, Vec3(4, 0, 0));
  }
}

TEST(ClipSampling, WorldAxesLoadsTurnIntoTheRestFrameAtTheLoad) {
  RawClip raw = PointLoadClip();
  raw.parts[0].channels.point_loads[0].axes = LoadAxes::kWorld;
  raw.parts[0].channels.point_loads[0].direction = Constant(Vec3(1, 1, 0));
  const Clip clip = BuildClip(raw, Beam().model).value();
  ClipSample sample = MakeClipSample(clip, Beam().model);
  SampleClip(clip, 2.0, &sample);  // magnitude 10 along (1, 1, 0) / sqrt 2, at v = 1
  const Frame& end = Beam().model.parts[0].spine_frames.back();
  const Vec3 world = Vec3(1, 1, 0).normalized() * 10.0;
  const Vec3 local = sample.poses[0].loads.bending_point_loads[0].force;
  EXPECT_NEAR(local.x(), world.dot(end.normal), 1e-12);
  EXPECT_NEAR(local.y(), world.dot(end.binormal), 1e-12);
  EXPECT_NEAR(local.z(), world.dot(end.tangent), 1e-12);
  // The beam stands on +Y: the world x part is lateral, the world y part along the tangent.
  EXPECT_NEAR(local.head<2>().norm(), 10.0 / std::sqrt(2.0), 1e-9);
}

TEST(ClipSampling, PoseIsTheAxisAngleRotationAndTranslation) {
  RawClip raw = PointLoadClip();
  raw.parts[0].channels.rotation = Constant(Vec3(0, 0, 0.5));
  raw.parts[0].channels.translation = Constant(Vec3(1, 2, 3));
  const Clip clip = BuildClip(raw, Beam().model).value();
  ClipSample sample = MakeClipSample(clip, Beam().model);
  SampleClip(clip, 1.0, &sample);
  EXPECT_TRUE(sample.poses[0].rotation.isApprox(Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ()))));
  EXPECT_EQ(sample.poses[0].translation, Vec3(1, 2, 3));
}

// Found with the clip fuzzer's check (fuzz/corpus/clip/finding-huge-rotation.json): a rotation
// vector whose squared length overflows (a component past 1.3e154) sampled to a NaN quaternion,
// refused only by the evaluation, far from the clip ("poses: rotations must be finite unit
// quaternions").
TEST(ClipSampling, EveryFiniteRotationVectorGivesAUnitQuaternion) {
  for (const Vec3& v : {Vec3(1e200, 0, 0), Vec3(1e155, 1e155, 0), Vec3(-1e308, 1e308, 1e308)}) {
    SCOPED_TRACE(::testing::Message() << v.transpose());
    RawClip raw = PointLoadClip();
    raw.parts[0].channels.rotation = Constant(v);
    const Clip clip = BuildClip(raw, Beam().model).value();
    ClipSample sample = MakeClipSample(clip, Beam().model);
    SampleClip(clip, 1.0, &sample);
    const Quat& q = sample.poses[0].rotation;
    EXPECT_TRUE(q.coeffs().allFinite()) << q.coeffs().transpose();
    EXPECT_NEAR(q.norm(), 1.0, 1e-12);
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

// The jointed cylinder's "arm" hangs from "base"; a clip keying its joint angles in degrees.
RawClip JointClip(const Vec3& first, const Vec3& last) {
  RawClip raw;
  raw.name = "bend";
  raw.duration = 1.0;
  RawPartTracks arm;
  arm.part = "arm";
  arm.channels.joint_angles.keys = {{0.0, first, Interpolation::kLinear},
                                    {1.0, last, Interpolation::kLinear}};
  raw.parts.push_back(arm);
  return raw;
}

TEST(ClipSampling, JointAnglesTurnThePartAboutItsJointAxesInDegreesWithinLimits) {
  testing::TestRig rig = testing::MakeJointedCylinderRig(SpineKind::kRigid);
  JointModel& joint = rig.model.parts[1].joint;
  const Result<Clip> clip = BuildClip(JointClip(Vec3::Zero(), Vec3(90, 0, 0)), rig.model);
  ASSERT_TRUE(clip.ok()) << clip.error();
  ClipSample sample = MakeClipSample(clip.value(), rig.model);
  SampleClip(clip.value(), 0.5, &sample);
  // Halfway: 45 degrees about the joint's X axis.
  const Eigen::AngleAxisd turned(sample.poses[1].rotation);
  EXPECT_NEAR(turned.angle(), std::numbers::pi / 4, 1e-12);
  EXPECT_NEAR(std::abs(turned.axis().dot(joint.axes.col(0))), 1.0, 1e-12);
  EXPECT_TRUE(sample.poses[0].rotation.isApprox(Quat::Identity(), 1e-15));
  // A hinge limited to [0, 60]: 90 is held at 60; Y and Z keys do nothing.
  joint.type = JointType::kHinge;
  joint.min_degrees.x() = 0.0;
  joint.max_degrees.x() = 60.0;
  const Result<Clip> limited = BuildClip(JointClip(Vec3::Zero(), Vec3(90, 30, 30)), rig.model);
  ASSERT_TRUE(limited.ok()) << limited.error();
  ClipSample at_end = MakeClipSample(limited.value(), rig.model);
  SampleClip(limited.value(), 1.0, &at_end);
  const Eigen::AngleAxisd held(at_end.poses[1].rotation);
  EXPECT_NEAR(held.angle(), std::numbers::pi / 3, 1e-12);
  EXPECT_NEAR(std::abs(held.axis().dot(joint.axes.col(0))), 1.0, 1e-12);
}

TEST(Clip, RefusesJointAnglesOnTheRootAndOnJointsThatDoNotExist) {
  const testing::TestRig rig = testing::MakeJointedCylinderRig(SpineKind::kRigid);
  RawClip raw = JointClip(Vec3::Zero(), Vec3(10, 0, 0));
  raw.parts[0].part = "base";
  EXPECT_EQ(BuildClip(raw, rig.model).error(),
            "parts[0].joint_angles: part \"base\" is the root: it has no joint to turn");
  raw.parts[0].part = "elbow";
  EXPECT_EQ(BuildClip(raw, rig.model).error(),
            "parts[0].part: no part of the rig is named \"elbow\" (parts: base, arm)");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
