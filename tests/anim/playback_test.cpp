// Playback against textbook answers: a keyed tip load bends a cantilever spine by F L^3 / 3EI
// at every time (random access, any order); a rigid part under a constant force at its centre
// moves by F t^2 / 2m; scrubbing back and forth gives the same states as a fresh playback.
#include "wirerig/anim/playback.h"

#include <gtest/gtest.h>

#include <cmath>

#include "anim_test_rigs.h"
#include "wirerig/io/floating_point_hold.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using testing::Constant;
using testing::Keys;

using testing::Beam;
const testing::TestRig& Block() {
  static const testing::TestRig rig = testing::MakeCylinderRig(SpineKind::kRigid);
  return rig;
}

TEST(Playback, KeyedTipLoadBendsTheSpineByTheCantileverFormulaAtAnyTime) {
  const RigModel& model = Beam().model;
  RawClip raw;
  raw.name = "push";
  raw.duration = 2.0;
  RawPartTracks part;
  part.part = "beam";
  PointLoadChannels<RawTrack> load;
  load.at = Keys({{0.0, 1.0}});
  load.magnitude = Keys({{0.0, 0.0}, {2.0, 0.02}});  // N, small: linear theory
  load.direction = Constant(Vec3(1, 0, 0));          // along the rest normal
  part.channels.point_loads.push_back(load);
  raw.parts.push_back(part);
  const Clip clip = BuildClip(raw, model).value();
  Playback playback = Playback::Make(model, clip).value();
  std::vector<Vec3> positions(model.vertices.size()), normals(model.vertices.size());
  const PartModel& beam = model.parts[0];
  const double ei = beam.spine_stiffness.bending, length = beam.spine_length;
  for (double t : {1.5, 0.25, 2.0, 0.0, 1.0}) {
    ASSERT_TRUE(playback.Evaluate(t, positions, normals).ok());
    const double force = 0.01 * t;
    const Vec3 tip = playback.workspace().spine_points[0].back() - beam.spine_points.back();
    const double expected = force * length * length * length / (3.0 * ei);
    EXPECT_NEAR(tip.dot(beam.spine_frames.back().normal), expected, 1e-9 * length + 1e-9 * expected)
        << "t = " << t;
  }
}

TEST(Playback, ConstantForceAtTheCentreMovesARigidPartByHalfATSquaredOverM) {
  const RigModel& model = Block().model;
  const PartModel& block = model.parts[0];
  ASSERT_GT(block.mass.mass, 0.0);
  RawClip raw;
  raw.name = "shove";
  raw.duration = 1.0;
  RawPartTracks part;
  part.part = "beam";
  RigidForceChannels<RawTrack> force;
  force.at = block.mass.center;
  force.force = Constant(Vec3(3.0, 0.0, -1.0));
  part.channels.rigid_forces.push_back(force);
  raw.parts.push_back(part);
  const Clip clip = BuildClip(raw, model).value();
  ASSERT_TRUE(clip.HasDynamics());
  PlaybackOptions options;
  options.rigid_step = 1.0 / 100.0;
  options.checkpoint_interval = 7;
  Playback playback = Playback::Make(model, clip, options).value();
  std::vector<Vec3> positions(model.vertices.size());
  for (double t : {0.8, 0.333, 1.0, 0.05}) {
    ASSERT_TRUE(playback.Evaluate(t, positions, {}).ok());
    const Vec3 shift = Vec3(3.0, 0.0, -1.0) * (t * t / (2.0 * block.mass.mass));
    EXPECT_LE((playback.bodies()[0].position - block.mass.center - shift).norm(), 1e-12)
        << "t = " << t;
    // The whole mesh translates with the body, no rotation.
    double worst = 0.0;
    for (std::size_t v = 0; v < positions.size(); ++v)
      worst = std::max(worst, (positions[v] - Beam().mesh.welded_positions[v] - shift).norm());
    EXPECT_LE(worst, 1e-9) << "t = " << t;
  }
}

// A constant force against linear drag c: x(t) = (F/c) (t - tau (1 - exp(-t/tau))), tau = m/c;
// against quadratic drag k: v(t) = v_t tanh(k v_t t / m), v_t = sqrt(F/k). The drag is sampled at
// each step's start state (first order in the step), hence the tolerances.
TEST(Playback, DragSlowsARigidPartToItsTerminalSpeed) {
  const RigModel& model = Block().model;
  const PartModel& block = model.parts[0];
  const double mass = block.mass.mass, push = 2.0;
  for (const bool quadratic : {false, true}) {
    RawClip raw;
    raw.name = "drift";
    raw.duration = 8.0;
    RawPartTracks part;
    part.part = "beam";
    RigidForceChannels<RawTrack> force;
    force.at = block.mass.center;
    force.force = Constant(Vec3(0.0, push, 0.0));
    part.channels.rigid_forces.push_back(force);
    const double c = mass / 1.5;  // tau = 1.5 s
    if (quadratic)
      part.channels.rigid_drag.quadratic = c;
    else
      part.channels.rigid_drag.linear = c;
    raw.parts.push_back(part);
    const Clip clip = BuildClip(raw, model).value();
    PlaybackOptions options;
    options.rigid_step = 1.0 / 1000.0;
    Playback playback = Playback::Make(model, clip, options).value();
    std::vector<Vec3> positions(model.vertices.size());
    for (double t : {0.5, 2.0, 8.0}) {
      ASSERT_TRUE(playback.Evaluate(t, positions, {}).ok());
      const RigidBodyState& body = playback.bodies()[0];
      EXPECT_LE(std::abs(body.velocity.x()) + std::abs(body.velocity.z()), 1e-12);
      if (quadratic) {
        const double terminal = std::sqrt(push / c);  // v(t) = v_t tanh(c v_t t / m)
        EXPECT_NEAR(body.velocity.y(), terminal * std::tanh(c * terminal * t / mass),
                    1e-3 * terminal);
        continue;
      }
      const double tau = mass / c;
      const double x = push / c * (t - tau * (1.0 - std::exp(-t / tau)));
      EXPECT_NEAR(body.position.y() - block.mass.center.y(), x, 1e-3 * x) << "t = " << t;
      EXPECT_NEAR(body.velocity.y(), push / c * (1.0 - std::exp(-t / tau)), 1e-3 * push / c);
    }
  }
}

// t = 3.4 s with the default step (1/240 s) and checkpoints (every 24 steps): t / span rounds
// up to 34 while checkpoint 34 lies 4e-16 s after t. The playback must still land on t (it once
// stepped (size_t)-1 times from there).
TEST(Playback, ATimeJustBeforeACheckpointIsReachedFromTheOneBefore) {
  const RigModel& model = Block().model;
  const PartModel& block = model.parts[0];
  RawClip raw;
  raw.name = "shove";
  raw.duration = 4.0;
  RawPartTracks part;
  part.part = "beam";
  RigidForceChannels<RawTrack> force;
  force.at = block.mass.center;
  force.force = Constant(Vec3(0.0, 1.0, 0.0));
  part.channels.rigid_forces.push_back(force);
  raw.parts.push_back(part);
  const Clip clip = BuildClip(raw, model).value();
  const PlaybackOptions options;
  const double t = 17.0 / 5.0, span = options.rigid_step * double(options.checkpoint_interval);
  ASSERT_GT(std::floor(t / span) * span, t);  // the case itself
  Playback playback = Playback::Make(model, clip, options).value();
  std::vector<Vec3> positions(model.vertices.size());
  ASSERT_TRUE(playback.Evaluate(t, positions, {}).ok());
  EXPECT_NEAR(playback.bodies()[0].position.y() - block.mass.center.y(),
              t * t / (2.0 * block.mass.mass), 1e-12);
}

TEST(Playback, ScrubbingGivesTheStatesOfAFreshPlayback) {
  const RigModel& model = Block().model;
  const PartModel& block = model.parts[0];
  RawClip raw;
  raw.name = "spin";
  raw.duration = 3.0;
  RawPartTracks part;
  part.part = "beam";
  RigidForceChannels<RawTrack> force;
  force.at = block.spine_points.back();  // off the centre: a torque too
  RawVectorTrack push;
  push.keys = {{0.0, Vec3(0, 0, 0), Interpolation::kLinear},
               {1.0, Vec3(0.5, 0, 0.2), Interpolation::kCubic},
               {3.0, Vec3(0, 0, 0), Interpolation::kLinear}};
  force.force = push;
  part.channels.rigid_forces.push_back(force);
  raw.parts.push_back(part);
  const Clip clip = BuildClip(raw, model).value();
  PlaybackOptions options;
  options.checkpoint_interval = 10;
  std::vector<Vec3> positions(model.vertices.size());
  Playback scrubbed = Playback::Make(model, clip, options).value();
  for (double t : {2.9, 0.4, 1.77, 2.9, 0.0, 2.9}) {
    ASSERT_TRUE(scrubbed.Evaluate(t, positions, {}).ok());
    Playback fresh = Playback::Make(model, clip, options).value();
    ASSERT_TRUE(fresh.Evaluate(t, positions, {}).ok());
    EXPECT_EQ(scrubbed.bodies()[0].position, fresh.bodies()[0].position) << t;
    EXPECT_EQ(scrubbed.bodies()[0].orientation.coeffs(), fresh.bodies()[0].orientation.coeffs())
        << t;
  }
  // The body did turn: the force off its centre has a torque.
  ASSERT_TRUE(scrubbed.Evaluate(2.9, positions, {}).ok());
  const Quat rest(block.mass.principal_axes);
  EXPECT_GT(scrubbed.bodies()[0].orientation.angularDistance(rest), 1e-3);
}

TEST(Playback, ATorqueTurnsAChildAboutItsJointWithTheParallelAxisInertia) {
  static const testing::TestRig rig = testing::MakeJointedCylinderRig(SpineKind::kRigid);
  const RigModel& model = rig.model;
  ASSERT_EQ(model.parts.size(), 2u);
  const PartModel& arm = model.parts[1];
  RawClip raw;
  raw.name = "swing";
  raw.duration = 1.0;
  RawPartTracks part;
  part.part = "arm";
  const double torque = 0.02;  // N m about +z
  part.channels.rigid_torque = Constant(Vec3(0, 0, torque));
  raw.parts.push_back(part);
  const Clip clip = BuildClip(raw, model).value();
  Playback playback = Playback::Make(model, clip).value();
  std::vector<Vec3> positions(model.vertices.size());
  // Parallel axis about the joint (the arm's first spine point), for the z axis: the centre's
  // offset d from the joint lies along y, so I_zz grows by m (d_x^2 + d_y^2).
  const Vec3 joint = arm.spine_points.front();
  const Vec3 d = arm.mass.center - joint;
  const double izz = arm.mass.inertia(2, 2) + arm.mass.mass * (d.x() * d.x() + d.y() * d.y());
  for (double t : {0.5, 1.0}) {
    ASSERT_TRUE(playback.Evaluate(t, positions, {}).ok());
    const double angle = torque * t * t / (2.0 * izz);  // constant torque from rest
    const std::vector<Vec3>& spine = playback.workspace().spine_points[1];
    // The joint stays; the tip turns about it by `angle`.
    EXPECT_LE((spine.front() - joint).norm(), 1e-9) << t;
    const Vec3 rest = arm.spine_points.back() - joint, now = spine.back() - joint;
    const double turned = std::atan2(rest.cross(now).z(), rest.dot(now));
    EXPECT_NEAR(turned, angle, 1e-6 * angle) << t;
    // The parent does not move.
    EXPECT_LE(
        (playback.workspace().spine_points[0].back() - model.parts[0].spine_points.back()).norm(),
        1e-12);
  }
}

TEST(Playback, AnInteractiveLoadBendsLikeAKeyedOneAndClears) {
  const RigModel& model = Beam().model;
  RawClip raw;
  raw.name = "idle";
  const Clip clip = BuildClip(raw, model).value();
  Playback playback = Playback::Make(model, clip).value();
  std::vector<Vec3> positions(model.vertices.size());
  const PartModel& beam = model.parts[0];
  const Frame& end = beam.spine_frames.back();
  const double force = 0.01;
  InteractiveLoad load;
  load.part = 0;
  load.at = 1.0;
  load.force = force * end.normal;  // world axes
  ASSERT_TRUE(playback.SetInteractiveLoad(load).ok());
  ASSERT_TRUE(playback.Evaluate(0.0, positions, {}).ok());
  const double l = beam.spine_length, ei = beam.spine_stiffness.bending;
  const Vec3 tip = playback.workspace().spine_points[0].back() - beam.spine_points.back();
  EXPECT_NEAR(tip.dot(end.normal), force * l * l * l / (3.0 * ei), 1e-9);
  // On a profile wire: the loop moves, the spine does not.
  load.profile = 3;
  load.at = 0.25;
  ASSERT_TRUE(playback.SetInteractiveLoad(load).ok());
  ASSERT_TRUE(playback.Evaluate(0.0, positions, {}).ok());
  EXPECT_LE((playback.workspace().spine_points[0].back() - beam.spine_points.back()).norm(), 1e-12);
  double moved = 0.0;
  for (std::size_t v = 0; v < positions.size(); ++v)
    moved = std::max(moved, (positions[v] - Beam().mesh.welded_positions[v]).norm());
  EXPECT_GT(moved, 1e-4);
  ASSERT_TRUE(playback.SetInteractiveLoad(std::nullopt).ok());
  ASSERT_TRUE(playback.Evaluate(0.0, positions, {}).ok());
  for (std::size_t v = 0; v < positions.size(); ++v)
    ASSERT_LE((positions[v] - Beam().mesh.welded_positions[v]).norm(), 1e-9);
  load.part = 7;
  EXPECT_EQ(playback.SetInteractiveLoad(load).field, "part");
  load.part = 0;
  load.at = 2.0;
  EXPECT_EQ(playback.SetInteractiveLoad(load).field, "at");
}

TEST(Playback, RefusesBadOptionsByName) {
  const RigModel& model = Beam().model;
  RawClip raw;
  raw.name = "idle";
  const Clip clip = BuildClip(raw, model).value();
  PlaybackOptions options;
  options.rigid_step = 0.0;
  EXPECT_EQ(Playback::Make(model, clip, options).error(),
            "rigid_step: must be finite and positive (s)");
  options = {};
  options.checkpoint_interval = 0;
  EXPECT_EQ(Playback::Make(model, clip, options).error(),
            "checkpoint_interval: must be at least 1");
  Playback playback = Playback::Make(model, clip).value();
  std::vector<Vec3> positions(model.vertices.size());
  EXPECT_FALSE(playback.Evaluate(std::nan(""), positions, {}).ok());
  std::vector<Vec3> wrong(3);
  EXPECT_FALSE(playback.Evaluate(0.0, wrong, {}).ok());
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

// The viewer's joint sliders: angles set on a part turn it about its joint, exactly as its
// joint's rotation, on top of the clip, until set back to zero; the root and bad angles are
// refused by name.
TEST(Playback, InteractiveJointAnglesTurnAPartAboutItsJointAndClear) {
  const testing::TestRig rig = testing::MakeJointedCylinderRig(SpineKind::kRigid);
  RawClip raw;
  raw.name = "still";
  raw.duration = 1.0;
  const Clip clip = BuildClip(raw, rig.model).value();
  Result<Playback> made = Playback::Make(rig.model, clip);
  ASSERT_TRUE(made.ok()) << made.error();
  Playback& playback = made.value();
  std::vector<Vec3> positions(rig.model.vertices.size());
  const Vec3 angles(50, 0, 0);
  ASSERT_TRUE(playback.SetInteractiveJointAngles(1, angles).ok());
  EXPECT_EQ(playback.InteractiveJointAngles(1), angles);
  ASSERT_TRUE(playback.Evaluate(0.5, positions, {}).ok());
  const Quat expected = JointRotation(rig.model.parts[1].joint, angles);
  EXPECT_TRUE(playback.sample().poses[1].rotation.isApprox(expected, 1e-12));
  // The arm's far end (the bottom cap, beyond its skin bridge) turned about the joint.
  const Vec3 root = rig.model.parts[1].spine_points.front();
  std::size_t checked = 0;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    if (rig.mesh.welded_positions[v].y() > 0.05) continue;
    const Vec3 turned = root + expected * (rig.mesh.welded_positions[v] - root);
    EXPECT_LT((positions[v] - turned).norm(), 1e-9);
    ++checked;
  }
  EXPECT_GT(checked, 10u);
  ASSERT_TRUE(playback.SetInteractiveJointAngles(1, Vec3::Zero()).ok());
  ASSERT_TRUE(playback.Evaluate(0.5, positions, {}).ok());
  EXPECT_TRUE(playback.sample().poses[1].rotation.isApprox(Quat::Identity(), 1e-15));
  EXPECT_EQ(playback.SetInteractiveJointAngles(0, angles).field, "part");  // the root
  EXPECT_EQ(playback.SetInteractiveJointAngles(7, angles).field, "part");
  EXPECT_EQ(playback.SetInteractiveJointAngles(1, Vec3(NAN, 0, 0)).field, "degrees");
}

// A tip deflection of 1e45 m (finite in double, beyond float) was drawn by `render` while the
// export refused it; at 1e33 m the float evaluation's normals overflowed (bake refused) while
// the double one's did not (render drew it). Over tip deflections from 1 mm to 1e45 m both
// evaluations agree: they pass up to the geometry bound (1e7 m) and fail beyond it, naming the
// vertex, with the same reason.
TEST(Playback, BothEvaluationsRefuseTheSameOverflowedGeometry) {
  const RigModel& model = Beam().model;
  const PartModel& beam = model.parts[0];
  const double l = beam.spine_length, ei = beam.spine_stiffness.bending;
  const ScopedFloatingPointHold hold;  // float rounding of huge values overflows, by design here
  for (const double tip : {1e-3, 1.0, 1e3, 1e6, 5e6, 2e7, 1e9, 1e12, 1e20, 1e33, 1e45}) {
    SCOPED_TRACE("tip deflection " + std::to_string(tip) + " m");
    RawClip raw;
    raw.name = "crush";
    raw.duration = 1.0;
    RawPartTracks part;
    part.part = "beam";
    PointLoadChannels<RawTrack> load;
    load.at = Keys({{0.0, 1.0}});
    load.magnitude = Keys({{0.0, tip * 3.0 * ei / (l * l * l)}});  // N: F L^3 / 3EI = tip
    load.direction = Constant(Vec3(1, 0, 0));
    part.channels.point_loads.push_back(load);
    raw.parts.push_back(part);
    const Clip clip = BuildClip(raw, model).value();
    Playback playback = Playback::Make(model, clip).value();
    std::vector<Vec3> positions(model.vertices.size()), normals(model.vertices.size());
    const Status doubles = playback.Evaluate(0.5, positions, normals);
    std::vector<float> buffer(6 * model.vertices.size());
    Playback::FloatOutput output;
    output.positions = buffer;
    output.position_stride = 6;
    output.normals = std::span<float>(buffer).subspan(3);
    output.normal_stride = 6;
    const Status floats = playback.Evaluate(0.5, output);
    const bool drawable = tip < 1e7;  // the tip moves by `tip`; the rest of the beam by less
    EXPECT_EQ(doubles.ok(), drawable) << ToString(doubles);
    EXPECT_EQ(floats.ok(), drawable) << ToString(floats);
    if (drawable) continue;
    EXPECT_EQ(doubles.field, "positions");
    EXPECT_GE(doubles.index, 0);
    EXPECT_EQ(doubles.reason, "not finite, or beyond 1e7 m (the deformation overflowed)");
    EXPECT_EQ(floats.field, "positions");
    EXPECT_EQ(floats.reason, doubles.reason);
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
