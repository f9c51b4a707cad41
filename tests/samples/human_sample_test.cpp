// The human samples (paper Figs. 11-12) and the dancer on the human bone chain (pelvis, spine_1,
// spine_2, chest, neck, head; upper arm, forearm, hand; thigh, shin, foot per side): played
// headless, their key numbers against closed forms written here.
//  * age: a thigh's spine, held at its root and pushed by -30 N at its tip, shortens by
//    F L / EA; the shin rides on the thigh's shortened end and shortens by its own F L / EA.
//  * shape: the chest's loaded stretches bulge by q L^4 / 384 EI at their middles, along the
//    world load; the rest of each loop stays.
//  * sex: the pectorals' loaded stretches (chest profile 2) bulge forward by q L^4 / 384 EI at
//    their middles; the pelvis's sides move in by their closed forms (the right side, mid-stretch
//    of a clamped stretch: q L^4 / 384 EI; the left side, the loop's seam, the guided end of a
//    cantilever stretch: q L^4 / 24 EI), so the hips' width along x shrinks by both.
//  * pose and dancer: a keyed part's spine is its rest spine carried by the product of the
//    joint rotations down its chain, R = A Rx(x) Ry(y) Rz(z) A^T about each root (joint.h),
//    computed here from the joint axes; the limbs swing visibly and the dance loops.
//  * every keyed joint angle of every human scene stays inside its joint's limits (the runtime
//    would clamp it silently).
//  * the skin holds on every frame (30 per second) of the posing scenes: no folded edge, no edge
//    stretched beyond 2x (skin_quality.h; what ../shared/tools/meshquality.py measures on a
//    morph-mode bake).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "sample_test_support.h"
#include "wirerig/rig/skin_quality.h"

namespace wirerig::samples {
namespace {
namespace WIRERIG_TEST_FILE {

// A rigid motion x -> rotation x + offset.
struct Motion {
  Mat3 rotation = Mat3::Identity();
  Vec3 offset = Vec3::Zero();
  Vec3 operator()(const Vec3& x) const { return rotation * x + offset; }
};

// The joint's rotation for angles in degrees, from its definition (joint.h): intrinsic X, then
// Y, then Z about the joint's rest axes (the columns of joint.axes).
Mat3 JointMatrix(const JointModel& joint, const Vec3& degrees) {
  const Vec3 a = degrees * (std::numbers::pi / 180.0);
  const Mat3 local =
      (Eigen::AngleAxisd(a.x(), Vec3::UnitX()) * Eigen::AngleAxisd(a.y(), Vec3::UnitY()) *
       Eigen::AngleAxisd(a.z(), Vec3::UnitZ()))
          .toRotationMatrix();
  return joint.axes * local * joint.axes.transpose();
}

// Where the clip puts part `p` at time t when no part carries loads: its own turn (the
// rotation track, then its joint angles) about its spine's root, then its parent's motion.
Motion ChainMotion(const RigModel& model, const Clip& clip, std::size_t p, double t) {
  const PartModel& part = model.parts[p];
  const PartChannels<Track>& c = clip.parts[p];
  Mat3 turn = Mat3::Identity();
  if (!c.rotation.IsEmpty()) {
    const Vec3 v = c.rotation.Sample(t);
    if (v.norm() > 0.0) turn = Eigen::AngleAxisd(v.norm(), v.normalized()).toRotationMatrix();
  }
  if (!c.joint_angles.IsEmpty()) turn = turn * JointMatrix(part.joint, c.joint_angles.Sample(t));
  const Vec3 root = part.spine_points.front();
  const Vec3 shift = c.translation.IsEmpty() ? Vec3::Zero() : c.translation.Sample(t);
  Motion own{turn, root - turn * root + shift};
  if (part.parent < 0) return own;
  const Motion parent = ChainMotion(model, clip, std::size_t(part.parent), t);
  return {parent.rotation * own.rotation, parent.rotation * own.offset + parent.offset};
}

// The part's deformed spine (in the playback's workspace) against its rest spine carried by
// the chain's motion.
void ExpectSpineFollowsItsChain(const PlayedScene& played, std::size_t p, double t) {
  const PartModel& part = played.scene.model.parts[p];
  const Motion motion = ChainMotion(played.scene.model, played.playback->clip(), p, t);
  const std::vector<Vec3>& spine = played.playback->workspace().spine_points[p];
  ASSERT_EQ(spine.size(), part.spine_points.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < spine.size(); ++k)
    worst = std::max(worst, (spine[k] - motion(part.spine_points[k])).norm());
  EXPECT_LT(worst, 1e-9) << part.name << " at t = " << t;
}

TEST(HumanSamples, AgeShortensTheThighAndShinByTheAxialClosedForm) {
  std::unique_ptr<PlayedScene> played = PlaySample("human/human_age.scene.json");
  ASSERT_NE(played, nullptr);
  const std::size_t thigh = played->Part("thigh_l"), shin = played->Part("shin_l");
  const PartModel& thigh_part = played->scene.model.parts[thigh];
  const PartModel& shin_part = played->scene.model.parts[shin];
  ASSERT_EQ(shin_part.parent, int(thigh));
  played->Evaluate(2.0);  // the full loads: -30 N on the thigh, -20 N on the shin
  const auto& spines = played->playback->workspace().spine_points;
  const double expected = -30.0 * thigh_part.spine_length / thigh_part.spine_stiffness.axial;
  const Vec3 moved = spines[thigh].back() - thigh_part.spine_points.back();
  EXPECT_NEAR(moved.dot(thigh_part.spine_frames.back().tangent), expected,
              1e-9 * std::abs(expected));
  EXPECT_LE((spines[thigh].front() - thigh_part.spine_points.front()).norm(), 1e-12);  // held
  EXPECT_GT(std::abs(expected), 0.05 * thigh_part.spine_length);  // visibly: over 5% shorter
  // The shin hangs from the thigh's shortened end (its root, a little below the thigh's spine,
  // moves with it) and shortens by its own closed form.
  const Vec3 carried = spines[shin].front() - shin_part.spine_points.front();
  EXPECT_LT((carried - moved).norm(), 1e-9 * moved.norm());
  const double own = -20.0 * shin_part.spine_length / shin_part.spine_stiffness.axial;
  const Vec3 shin_moved = spines[shin].back() - shin_part.spine_points.back() - carried;
  EXPECT_NEAR(shin_moved.dot(shin_part.spine_frames.back().tangent), own, 1e-9 * std::abs(own));
  EXPECT_GT(std::abs(own), 0.05 * shin_part.spine_length);
}

TEST(HumanSamples, ShapeBulgesTheChestByTheClampedWireFormula) {
  std::unique_ptr<PlayedScene> played = PlaySample("human/human_shape.scene.json");
  ASSERT_NE(played, nullptr);
  const std::size_t chest = played->Part("chest");
  const PartModel& part = played->scene.model.parts[chest];
  played->Evaluate(0.0);
  const auto rest = played->playback->workspace().profile_points[chest];
  played->Evaluate(2.0);
  const auto& points = played->playback->workspace().profile_points[chest];
  const Vec3 load(0.0, 0.0, 0.027);  // N/m, world: the front of the ribs forward
  for (std::uint32_t p : {1u, 2u, 3u}) {
    const ProfileModel& profile = part.profiles[p];
    ASSERT_EQ(profile.local_points.size(), 24u);
    const double length = StretchLength(profile, 0.55, 0.95);
    const double peak = std::pow(length, 4) / (384.0 * profile.stiffness.bending);
    const Vec3 moved = points[p][18] - rest[p][18];  // u = 0.75, the stretch's middle
    const Vec3 expected = peak * load;  // the chest is not posed: world = its rest frame
    EXPECT_LT((moved - expected).norm(), 1e-6 * expected.norm()) << "profile " << p;
    EXPECT_GT(expected.z(), 0.02) << "profile " << p;  // a visible bulge: over 2 cm forward
    EXPECT_LT((points[p][6] - rest[p][6]).norm(), 1e-12) << "profile " << p;  // the back stays
  }
}

TEST(HumanSamples, SexFlattensTheChestByTheClampedWireFormulaAndNarrowsTheHips) {
  std::unique_ptr<PlayedScene> played = PlaySample("human/human_sex.scene.json");
  ASSERT_NE(played, nullptr);
  const std::size_t chest = played->Part("chest"), pelvis = played->Part("pelvis");
  played->Evaluate(0.0);
  const auto rest = played->playback->workspace().profile_points;  // every part's, at rest
  played->Evaluate(2.0);
  const auto& points = played->playback->workspace().profile_points;

  // Chest profile 2: a clamped stretch over each pectoral, [0.52, 0.73] (right) and [0.77, 0.98]
  // (left), 0.05 N/m forward in world axes. Their middles, u = 0.625 and 0.875, are the loop's
  // points 15 and 21 of 24; no other load reaches them and the chest is not posed (world = its
  // rest frame).
  const ProfileModel& pectorals = played->scene.model.parts[chest].profiles[2];
  ASSERT_EQ(pectorals.local_points.size(), 24u);
  const Vec3 forward(0.0, 0.0, 0.05);  // N/m, world
  struct Stretch {
    double from, to;
    std::size_t middle;
  };
  for (const Stretch& s : {Stretch{0.52, 0.73, 15}, Stretch{0.77, 0.98, 21}}) {
    const double length = StretchLength(pectorals, s.from, s.to);
    const double peak = std::pow(length, 4) / (384.0 * pectorals.stiffness.bending);
    const Vec3 expected = peak * forward;
    const Vec3 moved = points[chest][2][s.middle] - rest[chest][2][s.middle];
    EXPECT_LT((moved - expected).norm(), 1e-6 * expected.norm()) << "point " << s.middle;
    EXPECT_GT(expected.z(), 0.008) << "point " << s.middle;  // visibly: over 8 mm forward
  }
  EXPECT_LT((points[chest][2][6] - rest[chest][2][6]).norm(), 1e-12);  // the back stays

  // Hips: pelvis profile 2, its sides pushed in by 0.0016 N/m along world x. The right side
  // (point 12, u = 0.5) is the middle of the clamped stretch [0.25, 0.75]: q L^4 / 384 EI. The
  // left side is the loop's seam (point 0, u = 0 = 1), the guided end of the cantilever stretch
  // [0.75, 1]: q L^4 / 24 EI (the clamped stretches that start at the seam hold it still).
  const ProfileModel& hips = played->scene.model.parts[pelvis].profiles[2];
  ASSERT_EQ(hips.local_points.size(), 24u);
  const double q = 0.0016;
  const double right =
      q * std::pow(StretchLength(hips, 0.25, 0.75), 4) / (384.0 * hips.stiffness.bending);
  const double left =
      q * std::pow(StretchLength(hips, 0.75, 1.0), 4) / (24.0 * hips.stiffness.bending);
  const Vec3 right_moved = points[pelvis][2][12] - rest[pelvis][2][12];
  const Vec3 left_moved = points[pelvis][2][0] - rest[pelvis][2][0];
  EXPECT_LT((right_moved - Vec3(right, 0.0, 0.0)).norm(), 1e-6 * right);
  EXPECT_LT((left_moved - Vec3(-left, 0.0, 0.0)).norm(), 1e-6 * left);
  // The sides stay the loop's extremes along x, so its width shrinks by both pushes.
  const auto width = [](const std::vector<Vec3>& loop) {
    double lo = loop.front().x(), hi = lo;
    for (const Vec3& p : loop) {
      lo = std::min(lo, p.x());
      hi = std::max(hi, p.x());
    }
    return hi - lo;
  };
  EXPECT_NEAR(width(points[pelvis][2]), width(rest[pelvis][2]) - left - right, 1e-9);
  EXPECT_GT(left + right, 0.008);  // visibly: the hips over 8 mm narrower
}

TEST(HumanSamples, PoseTurnsEveryLimbByItsJointChain) {
  std::unique_ptr<PlayedScene> played = PlaySample("human/human_pose.scene.json");
  ASSERT_NE(played, nullptr);
  for (double t : {0.5, 1.0, 2.0}) {
    played->Evaluate(t);
    for (const Vec3& p : played->positions)
      ASSERT_TRUE(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()));
    for (const char* name : {"head", "hand_l", "hand_r", "foot_l", "foot_r"})
      ExpectSpineFollowsItsChain(*played, played->Part(name), t);
  }
  // A clear pose: the hands, the left foot and the head moved well away from rest.
  const auto& spines = played->playback->workspace().spine_points;
  for (const char* name : {"hand_l", "hand_r", "foot_l"}) {
    const std::size_t p = played->Part(name);
    EXPECT_GT((spines[p].back() - played->scene.model.parts[p].spine_points.back()).norm(), 0.1)
        << name;
  }
  const std::size_t head = played->Part("head");
  EXPECT_GT((spines[head].back() - played->scene.model.parts[head].spine_points.back()).norm(),
            0.02);
}

TEST(DancerSample, LimbsFollowTheirJointChainsSwingWideAndTheDanceLoops) {
  std::unique_ptr<PlayedScene> played = PlaySample("dancer/dancer.scene.json");
  ASSERT_NE(played, nullptr);
  const RigModel& model = played->scene.model;
  const std::vector<std::string> limbs = {"upper_arm_l", "forearm_r", "hand_l", "thigh_r",
                                          "shin_l",      "foot_r",    "head"};
  std::vector<double> widest(limbs.size(), 0.0);
  for (double t = 0.0; t < 8.0; t += 0.35) {
    played->Evaluate(t);
    for (std::size_t i = 0; i < limbs.size(); ++i) {
      const std::size_t p = played->Part(limbs[i]);
      ExpectSpineFollowsItsChain(*played, p, t);
      // The swing about the limb's own joint: the tip against the root's rest offset.
      const std::vector<Vec3>& spine = played->playback->workspace().spine_points[p];
      const Vec3 rest = model.parts[p].spine_points.back() - model.parts[p].spine_points.front();
      widest[i] = std::max(widest[i], (spine.back() - spine.front() - rest).norm());
    }
  }
  for (std::size_t i = 0; i < limbs.size(); ++i)  // every limb swings over a third of its length
    EXPECT_GT(widest[i], model.parts[played->Part(limbs[i])].spine_length / 3.0) << limbs[i];
  // The loop closes: just before the end and just after the start the mesh is in one place.
  played->Evaluate(8.0 - 1e-4);
  const std::vector<Vec3> end = played->positions;
  played->Evaluate(1e-4);
  double jump = 0.0;
  for (std::size_t v = 0; v < end.size(); ++v)
    jump = std::max(jump, (end[v] - played->positions[v]).norm());
  EXPECT_LT(jump, 1e-3);
}

// The angle (degrees) between two parts' bone chords (spine start to end) now, less at rest.
double ChordAngleChange(const PlayedScene& played, std::size_t a, std::size_t b) {
  auto chord = [](const std::vector<Vec3>& spine) {
    return Vec3(spine.back() - spine.front()).normalized();
  };
  auto angle = [](const Vec3& u, const Vec3& v) {
    return std::acos(std::clamp(u.dot(v), -1.0, 1.0)) * 180.0 / std::numbers::pi;
  };
  const auto& now = played.playback->workspace().spine_points;
  const RigModel& model = played.scene.model;
  return angle(chord(now[a]), chord(now[b])) -
         angle(chord(model.parts[a].spine_points), chord(model.parts[b].spine_points));
}

// The dance reaches its keyed extremes as played: the knees bend 85 degrees (hinges: the
// shin's chord turns that far against the thigh's), the arms rise overhead (the upper arm's
// chord turns over 100 degrees toward the chest's).
TEST(DancerSample, ReachesItsKeyedJointAngles) {
  std::unique_ptr<PlayedScene> played = PlaySample("dancer/dancer.scene.json");
  ASSERT_NE(played, nullptr);
  double knee_l = 0.0, knee_r = 0.0, arm_l = 0.0, arm_r = 0.0;
  for (double t = 0.0; t < 8.0; t += 1.0 / 30.0) {
    played->Evaluate(t);
    const PlayedScene& p = *played;
    knee_l = std::max(knee_l, ChordAngleChange(p, p.Part("thigh_l"), p.Part("shin_l")));
    knee_r = std::max(knee_r, ChordAngleChange(p, p.Part("thigh_r"), p.Part("shin_r")));
    arm_l = std::max(arm_l, -ChordAngleChange(p, p.Part("chest"), p.Part("upper_arm_l")));
    arm_r = std::max(arm_r, -ChordAngleChange(p, p.Part("chest"), p.Part("upper_arm_r")));
  }
  std::printf("[ measured ] knees %.1f %.1f, arms %.1f %.1f degrees\n", knee_l, knee_r, arm_l,
              arm_r);
  EXPECT_GT(std::min(knee_l, knee_r), 80.0);  // keyed 85
  EXPECT_GT(std::min(arm_l, arm_r), 100.0);   // keyed 110: from 45 degrees below level to
                                              // within 30 of vertical
}

TEST(HumanSamples, EveryKeyedJointAngleStaysInsideItsLimits) {
  for (const char* scene : {"human/human_wave.scene.json", "human/human_pose.scene.json",
                            "human/human_shape.scene.json", "human/human_sex.scene.json",
                            "human/human_age.scene.json", "dancer/dancer.scene.json"}) {
    SCOPED_TRACE(scene);
    std::unique_ptr<PlayedScene> played = PlaySample(scene);
    ASSERT_NE(played, nullptr);
    const Clip& clip = played->playback->clip();
    for (std::size_t p = 0; p < clip.parts.size(); ++p) {
      const Track<Vec3>& angles = clip.parts[p].joint_angles;
      if (angles.IsEmpty()) continue;
      const JointModel& joint = played->scene.model.parts[p].joint;
      // Dense sampling: cubic keys overshoot between keys.
      for (double t = 0.0; t <= clip.duration; t += 1.0 / 120.0) {
        const Vec3 a = angles.Sample(t);
        ASSERT_LT((ClampJointAngles(joint, a) - a).norm(), 1e-9)
            << played->scene.model.parts[p].name << " at t = " << t << ": " << a.transpose();
      }
    }
  }
}

TEST(HumanSamples, SkinHoldsOnEveryFrame) {
  for (const char* scene :
       {"human/human_wave.scene.json", "human/human_pose.scene.json",
        "human/human_shape.scene.json", "human/human_sex.scene.json", "human/human_age.scene.json",
        "dancer/dancer.scene.json", "mocap/human_mocap.scene.json"}) {
    SCOPED_TRACE(scene);
    std::unique_ptr<PlayedScene> played = PlaySample(scene);
    ASSERT_NE(played, nullptr);
    const SkinQualityReference reference = MakeSkinQualityReference(
        played->scene.mesh.welded_positions, played->scene.model.triangles);
    const double duration = played->playback->clip().duration;
    std::size_t frames = 0;
    for (double t = 0.0; t <= duration + 1e-9; t += 1.0 / 30.0, ++frames) {
      played->Evaluate(t);
      const SkinQuality quality = MeasureSkin(reference, played->positions);
      ASSERT_EQ(quality.folded_edges, 0u) << "t = " << t;
      ASSERT_LT(quality.worst_stretch, 2.0) << "t = " << t;
    }
    EXPECT_GT(frames, 30u);
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::samples
