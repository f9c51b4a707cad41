// Real motion as clips (motion_import.h): BVH motion capture parsed and retargeted, skinned
// assets' animations played through their own skeleton rigs, and scene clips naming a motion.
//  * a hand-written 3-joint BVH: the parser reads it exactly; retargeted onto a 3-part chain
//    hanging down (the capture's chain lies along +X, a T-pose against the rig's rest), each
//    part's rotation is the product of elementary rotations derived here by hand from the
//    definition (rest alignment, then the capture's world rotation), the played bones point
//    along the capture's bones and the root moves by the capture's translation times the leg
//    length ratio; the joint-angle form plays the same pose. With limits, a twist beyond the
//    end's limit: the end's and its parent's turns as derived by hand from the rule
//    (docs/motion-import.md#joint-limits), the end's world rotation off by exactly what the
//    limits cannot take.
//  * 01_01.bvh (CMU): 31 joints, its frame count and rate; retargeted onto human.zae (the
//    sample scene samples/mocap/human_mocap.scene.json, limits ignored) it plays without a
//    non-finite value, every mapped bone points along the capture's bone (forward kinematics
//    written here), the pelvis follows the capture's hips scaled by the leg length ratio, and the
//    knees bend as the capture's do (past 75 degrees in the jumps); as checked in (limits passed to
//    parents) no joint angle passes its limits at any key and the head stays nearer the capture's
//    rotation than a plain clamp leaves it.
//  * anim_test.x and Testwuson.X: their animations played through their skeleton rigs carry
//    every bone's root and tip where Assimp's animated node transforms put the joints.
//  * bad input is refused with the file and field named: a mapping naming a joint or part that
//    does not exist, BVH text whose hierarchy and motion data disagree, non-finite values, an
//    animation index out of range, a scene clip with a motion and a duration.
#include "wirerig/anim/motion_import.h"

#include <gtest/gtest.h>

#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>

#include <nlohmann/json.hpp>

#include "samples/sample_test_support.h"
#include "wirerig/anim/clip_json.h"
#include "wirerig/anim/scene.h"

#ifndef WIRERIG_ASSET_DIR
#error "the tests need WIRERIG_ASSET_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;
using nlohmann::json;
using samples::PlayedScene;

constexpr double kPi = std::numbers::pi;
constexpr double kDegrees = 180.0 / kPi;

fs::path Asset(const std::string& relative) { return fs::path(WIRERIG_ASSET_DIR) / relative; }

// A fresh folder for the files a test writes.
fs::path TempFolder() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path folder = fs::temp_directory_path() /
                          ("wirerig_motion_" + std::to_string(getpid()) + "_" + info->name());
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

fs::path WriteFile(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

Mat3 Rx(double degrees) { return Eigen::AngleAxisd(degrees / kDegrees, Vec3::UnitX()).matrix(); }
Mat3 Ry(double degrees) { return Eigen::AngleAxisd(degrees / kDegrees, Vec3::UnitY()).matrix(); }
Mat3 Rz(double degrees) { return Eigen::AngleAxisd(degrees / kDegrees, Vec3::UnitZ()).matrix(); }

Mat3 FromVector(const Vec3& v) {
  return v.norm() > 0.0 ? Mat3(Eigen::AngleAxisd(v.norm(), v.normalized()).matrix())
                        : Mat3::Identity();
}

// A rigid motion x -> rotation x + offset.
struct Motion {
  Mat3 rotation = Mat3::Identity();
  Vec3 offset = Vec3::Zero();
  Vec3 operator()(const Vec3& x) const { return rotation * x + offset; }
};

// The joint's rotation for angles in degrees (joint.h): intrinsic X, Y, Z about its rest axes.
Mat3 JointMatrix(const JointModel& joint, const Vec3& degrees) {
  return joint.axes * Rx(degrees.x()) * Ry(degrees.y()) * Rz(degrees.z()) * joint.axes.transpose();
}

// Where the clip puts part p at time t (clip.h): its own turn (rotation track, then joint
// angles) about its spine's root plus its translation, then its parent's motion.
Motion ChainMotion(const RigModel& model, const Clip& clip, std::size_t p, double t) {
  const PartModel& part = model.parts[p];
  const PartChannels<Track>& c = clip.parts[p];
  Mat3 turn = c.rotation.IsEmpty() ? Mat3::Identity() : FromVector(c.rotation.Sample(t));
  if (!c.joint_angles.IsEmpty()) turn = turn * JointMatrix(part.joint, c.joint_angles.Sample(t));
  const Vec3 root = part.spine_points.front();
  const Vec3 shift = c.translation.IsEmpty() ? Vec3::Zero() : c.translation.Sample(t);
  const Motion own{turn, root - turn * root + shift};
  if (part.parent < 0) return own;
  const Motion parent = ChainMotion(model, clip, std::size_t(part.parent), t);
  return {parent.rotation * own.rotation, parent.rotation * own.offset + parent.offset};
}

// The deformed spine of part p against its rest spine carried by its chain's motion.
double SpineOffChain(const PlayedScene& played, std::size_t p, double t) {
  const PartModel& part = played.scene.model.parts[p];
  const Motion motion = ChainMotion(played.scene.model, played.playback->clip(), p, t);
  const std::vector<Vec3>& spine = played.playback->workspace().spine_points[p];
  double worst = 0.0;
  for (std::size_t k = 0; k < spine.size(); ++k)
    worst = std::max(worst, (spine[k] - motion(part.spine_points[k])).norm());
  return worst;
}

// The played part's bone (its spine's chord), unit.
Vec3 PlayedBone(const PlayedScene& played, std::size_t p) {
  const std::vector<Vec3>& spine = played.playback->workspace().spine_points[p];
  return (spine.back() - spine.front()).normalized();
}

double Angle(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * kDegrees;
}

// ---------------------------------------------------------------------------------------------
// Forward kinematics of a BVH frame, written here from the format's definition: a joint's
// rotation channels compose in the order listed (intrinsic), position channels replace its
// OFFSET; world rotation W = W_parent R, position p = p_parent + W_parent t.
struct TestPose {
  std::vector<Mat3> rotation;
  std::vector<Vec3> position;
};

TestPose PoseFrame(const MotionCapture& m, std::size_t frame) {
  TestPose out;
  const double* values = m.values.data() + frame * m.channel_count;
  for (const BvhJoint& joint : m.joints) {
    Vec3 t = joint.offset;
    Mat3 r = Mat3::Identity();
    for (std::size_t c = 0; c < joint.channels.size(); ++c) {
      const double v = values[joint.first_channel + c];
      switch (joint.channels[c]) {
        case BvhChannel::kXPosition:
          t.x() = v;
          break;
        case BvhChannel::kYPosition:
          t.y() = v;
          break;
        case BvhChannel::kZPosition:
          t.z() = v;
          break;
        case BvhChannel::kXRotation:
          r = r * Rx(v);
          break;
        case BvhChannel::kYRotation:
          r = r * Ry(v);
          break;
        case BvhChannel::kZRotation:
          r = r * Rz(v);
          break;
      }
    }
    if (joint.parent < 0) {
      out.rotation.push_back(r);
      out.position.push_back(t);
    } else {
      const Mat3 parent = out.rotation[std::size_t(joint.parent)];
      out.position.push_back(out.position[std::size_t(joint.parent)] + parent * t);
      out.rotation.push_back(parent * r);
    }
  }
  return out;
}

int Joint(const MotionCapture& m, const std::string& name) {
  const int j = m.FindJoint(name);
  EXPECT_GE(j, 0) << name;
  return std::max(j, 0);
}

// ---------------------------------------------------------------------------------------------
// The 3-joint capture: A (root, 6 channels) -> B at +10 x -> C at +10 x -> End Site at +5 x.
// B lists its rotations Z, X, Y; C lists Z, Y, X. Frame 0 is the rest pose; frame 1 turns A
// by 30 degrees about z and lifts it 4 units, twists B by 90 degrees about x and bends C by 45
// degrees about z.
constexpr const char* kThreeJoints = R"(HIERARCHY
ROOT A
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation
  JOINT B
  {
    OFFSET 10 0 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    JOINT C
    {
      OFFSET 10 0 0
      CHANNELS 3 Zrotation Yrotation Xrotation
      End Site
      {
        OFFSET 5 0 0
      }
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.5
0 0 0 0 0 0 0 0 0 0 0 0
0 4 0 30 0 0 0 90 0 45 0 0
)";

constexpr const char* kThreeJointMapping = R"({
  "format": "wirerig.motion_mapping", "version": 1,
  "source": {"up_axis": "y", "unit_scale": 0.01},
  "joints": {"A": "top", "B": "middle", "C": "bottom"}
})";

// A cylinder 1.5 m tall along +Y rigged as a chain hanging down: top (1.5 -> 1.0), middle
// (1.0 -> 0.5), bottom (0.5 -> 0).
json ChainScene(const fs::path& bvh, const fs::path& mapping) {
  json scene = json::parse(R"({
    "format": "wirerig.scene", "version": 1, "name": "chain",
    "mesh": {"procedural": "cylinder", "parameters": {"radius": 0.1, "height": 1.5,
             "height_segments": 30}},
    "rig": {"description": {"parts": [
      {"name": "top", "central_curve": [[0, 1.5, 0], [0, 1.0, 0]], "profile_count": 6,
       "points_per_profile": 16},
      {"name": "middle", "parent": "top", "central_curve": [[0, 1.0, 0], [0, 0.5, 0]],
       "profile_count": 6, "points_per_profile": 16},
      {"name": "bottom", "parent": "middle", "central_curve": [[0, 0.5, 0], [0, 0, 0]],
       "profile_count": 6, "points_per_profile": 16}]}},
    "default_kind": "rigid",
    "clips": [{"name": "capture", "motion": {}}]
  })");
  scene["clips"][0]["motion"] = {{"file", bvh.string()}, {"mapping", mapping.string()}};
  return scene;
}

TEST(MotionCapture, ParsesAHandWrittenThreeJointFile) {
  Result<MotionCapture> parsed = ParseBvh(kThreeJoints, "three.bvh");
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  const MotionCapture& m = parsed.value();
  ASSERT_EQ(m.joints.size(), 3u);
  EXPECT_EQ(m.joints[0].name, "A");
  EXPECT_EQ(m.joints[1].parent, 0);
  EXPECT_EQ(m.joints[2].parent, 1);
  EXPECT_EQ(m.joints[2].offset, Vec3(10, 0, 0));
  EXPECT_EQ(m.joints[1].channels,
            (std::vector<BvhChannel>{BvhChannel::kZRotation, BvhChannel::kXRotation,
                                     BvhChannel::kYRotation}));
  EXPECT_EQ(m.joints[1].first_channel, 6u);
  EXPECT_EQ(m.joints[2].first_channel, 9u);
  ASSERT_TRUE(m.joints[2].end_site.has_value());
  EXPECT_EQ(*m.joints[2].end_site, Vec3(5, 0, 0));
  EXPECT_FALSE(m.joints[1].end_site.has_value());
  EXPECT_EQ(m.channel_count, 12u);
  EXPECT_EQ(m.frame_count, 2u);
  EXPECT_EQ(m.frame_time, 0.5);
  EXPECT_EQ(m.Frame(1)[7], 90.0);
  EXPECT_EQ(m.Duration(), 0.5);

  // The library's forward kinematics against the definition: C sits at A + W_A (10, 0, 0) +
  // W_B (10, 0, 0) with W_A = Rz(30), W_B = Rz(30) Rx(90).
  std::vector<BvhPose> poses;
  PoseBvhFrame(m, 1, poses);
  const Vec3 c = Vec3(0, 4, 0) + Rz(30) * Vec3(10, 0, 0) + Rz(30) * Rx(90) * Vec3(10, 0, 0);
  EXPECT_LT((poses[2].position - c).norm(), 1e-12);
  EXPECT_LT((poses[2].rotation - Rz(30) * Rx(90) * Rz(45)).norm(), 1e-12);
  EXPECT_EQ(BvhRestPositions(m)[2], Vec3(20, 0, 0));
}

TEST(MotionCapture, ReadsLinesEndedByCrLfOrALoneCr) {
  const std::string lf = kThreeJoints;
  for (const char* ending : {"\r\n", "\r"}) {
    std::string text;
    for (char c : lf) {
      if (c == '\n')
        text.append(ending);
      else
        text.push_back(c);
    }
    Result<MotionCapture> parsed = ParseBvh(text, "three.bvh");
    ASSERT_TRUE(parsed.ok()) << parsed.error();
    EXPECT_EQ(parsed.value().frame_count, 2u);
    EXPECT_EQ(parsed.value().Frame(1)[7], 90.0);
    EXPECT_EQ(parsed.value().channel_count, 12u);
  }
  // A line number in an error counts lone CRs as line ends too.
  std::string broken = lf;
  broken.replace(broken.find("OFFSET"), 6, "OFFSTE");
  const std::size_t line =
      1 + std::count(broken.begin(), broken.begin() + broken.find("OFFSTE"), '\n');
  std::replace(broken.begin(), broken.end(), '\n', '\r');
  Result<MotionCapture> parsed = ParseBvh(broken, "three.bvh");
  ASSERT_FALSE(parsed.ok());
  EXPECT_NE(parsed.error().find("line " + std::to_string(line) + ":"), std::string::npos)
      << parsed.error();
}

TEST(MotionRetarget, ThreeJointChainTurnsAsTheDefinitionSays) {
  const fs::path folder = TempFolder();
  const fs::path bvh = WriteFile(folder / "three.bvh", kThreeJoints);
  const fs::path mapping = WriteFile(folder / "three.mapping.json", kThreeJointMapping);
  std::unique_ptr<PlayedScene> played = samples::PlayDocument(ChainScene(bvh, mapping));
  ASSERT_NE(played, nullptr);
  const RigModel& model = played->scene.model;
  const Clip& clip = played->playback->clip();
  EXPECT_DOUBLE_EQ(clip.duration, 0.5);
  const std::size_t top = played->Part("top"), middle = played->Part("middle"),
                    bottom = played->Part("bottom");

  // Rest alignments: the root's is the identity; the middle bone (-Y in the rig, +X in the
  // capture) turns by the least rotation Rz(90); the bottom continues the middle in both, so
  // it keeps the middle's alignment. Part rotation P = W_joint C, own turn T = P_parent^T P.
  const Mat3 c_middle = Rz(90), c_bottom = Rz(90);
  struct Expected {
    double t;
    Mat3 top, middle, bottom;  // own turns
    Vec3 middle_bone, bottom_bone, root_shift;
  };
  const double s = 0.5 / 10.0;  // leg length: the rig's middle -> bottom over the capture's B -> C
  const std::vector<Expected> expected = {
      // Frame 0, the capture's rest: the rig's chain lifts to +X below its unturned root.
      {0.0, Mat3::Identity(), c_middle, c_middle.transpose() * c_bottom, Vec3::UnitX(),
       Vec3::UnitX(), Vec3::Zero()},
      // Frame 1: W_A = Rz(30), W_B = Rz(30) Rx(90), W_C = Rz(30) Rx(90) Rz(45).
      {0.5, Rz(30), Rx(90) * c_middle, c_middle.transpose() * Rz(45) * c_bottom,
       Rz(30) * Vec3::UnitX(), Rz(30) * Rx(90) * Rz(45) * Vec3::UnitX(), Vec3(0, 4 * s, 0)}};
  for (const Expected& e : expected) {
    SCOPED_TRACE("t = " + std::to_string(e.t));
    played->Evaluate(e.t);
    EXPECT_LT((FromVector(clip.parts[top].rotation.Sample(e.t)) - e.top).norm(), 1e-9);
    EXPECT_LT((FromVector(clip.parts[middle].rotation.Sample(e.t)) - e.middle).norm(), 1e-9);
    EXPECT_LT((FromVector(clip.parts[bottom].rotation.Sample(e.t)) - e.bottom).norm(), 1e-9);
    EXPECT_LT((clip.parts[top].translation.Sample(e.t) - e.root_shift).norm(), 1e-12);
    EXPECT_LT(Angle(PlayedBone(*played, middle), e.middle_bone), 1e-6);
    EXPECT_LT(Angle(PlayedBone(*played, bottom), e.bottom_bone), 1e-6);
    for (std::size_t p : {top, middle, bottom}) EXPECT_LT(SpineOffChain(*played, p, e.t), 1e-9);
    // The root turns about its spine's root point, which rises by the scaled lift.
    const Vec3 root = played->playback->workspace().spine_points[top].front();
    EXPECT_LT((root - model.parts[top].spine_points.front() - e.root_shift).norm(), 1e-9);
  }

  // The joint-angle form: the same pose where no limit binds (the chain's joints are free).
  json angles = json::parse(kThreeJointMapping);
  angles["channels"] = "joint_angles";
  const fs::path angle_mapping = WriteFile(folder / "angles.mapping.json", angles.dump());
  std::unique_ptr<PlayedScene> by_angles = samples::PlayDocument(ChainScene(bvh, angle_mapping));
  ASSERT_NE(by_angles, nullptr);
  EXPECT_FALSE(by_angles->playback->clip().parts[middle].joint_angles.IsEmpty());
  EXPECT_TRUE(by_angles->playback->clip().parts[middle].rotation.IsEmpty());
  for (const Expected& e : expected) {
    by_angles->Evaluate(e.t);
    played->Evaluate(e.t);
    for (std::size_t p : {top, middle, bottom}) {
      const auto& a = by_angles->playback->workspace().spine_points[p];
      const auto& b = played->playback->workspace().spine_points[p];
      for (std::size_t k = 0; k < a.size(); ++k) EXPECT_LT((a[k] - b[k]).norm(), 1e-9);
    }
  }
  fs::remove_all(folder);
}

// Joint limits. A capture hanging down like the chain (no rest alignment) twists C by 80
// degrees about its bone (Yrotation -80: about -Y, the bottom joint's Z axis, so the bottom's
// turn is +80 about Z). The bottom may twist 45, comfortably 0.75 of that (33.75). The middle
// first takes what lies beyond that within its own comfortable range, the bottom takes back the
// rest up to its limit, the middle the rest up to its own; the root takes nothing.
constexpr const char* kHangingTwist = R"(HIERARCHY
ROOT A
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation
  JOINT B
  {
    OFFSET 0 -10 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    JOINT C
    {
      OFFSET 0 -10 0
      CHANNELS 3 Zrotation Yrotation Xrotation
      End Site
      {
        OFFSET 0 -5 0
      }
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.5
0 0 0 0 0 0 0 0 0 0 0 0
0 0 0 0 0 0 0 0 0 0 -80 0
)";

TEST(MotionRetarget, LimitsHandTheExcessToTheParent) {
  const fs::path folder = TempFolder();
  const fs::path bvh = WriteFile(folder / "twist.bvh", kHangingTwist);
  auto play = [&](const std::string& limits, double middle_twist) {
    json mapping = json::parse(kThreeJointMapping);
    mapping["limits"] = limits;
    json scene = ChainScene(bvh, WriteFile(folder / (limits + ".mapping.json"), mapping.dump()));
    json& parts = scene["rig"]["description"]["parts"];
    parts[1]["joint"] = {
        {"type", "ball"}, {"axis", {1, 0, 0}}, {"limits", {{"z", {-middle_twist, middle_twist}}}}};
    parts[2]["joint"] = {{"type", "ball"}, {"axis", {1, 0, 0}}, {"limits", {{"z", {-45, 45}}}}};
    return samples::PlayDocument(scene);
  };
  struct Case {
    std::string limits;
    double middle_limit;
    double middle, bottom;  // expected twists, degrees
  };
  const std::vector<Case> cases = {
      // 80 - 33.75 = 46.25 > the middle's comfortable 37.5: it takes 37.5, the bottom 42.5.
      {"pass_to_parents", 50.0, 37.5, 42.5},
      // The middle's comfortable 15, the bottom back up to 45, the middle to its limit 20: 15
      // degrees of the capture's twist are lost.
      {"pass_to_parents", 20.0, 20.0, 45.0},
      {"clamp", 50.0, 0.0, 45.0},
      {"ignore", 50.0, 0.0, 80.0}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.limits + ", middle limit " + std::to_string(c.middle_limit));
    std::unique_ptr<PlayedScene> played = play(c.limits, c.middle_limit);
    ASSERT_NE(played, nullptr);
    const Clip& clip = played->playback->clip();
    const RigModel& model = played->scene.model;
    const std::size_t middle = played->Part("middle"), bottom = played->Part("bottom");
    const double t = 0.5;
    EXPECT_LT((FromVector(clip.parts[middle].rotation.Sample(t)) -
               JointMatrix(model.parts[middle].joint, Vec3(0, 0, c.middle)))
                  .norm(),
              1e-9);
    EXPECT_LT((FromVector(clip.parts[bottom].rotation.Sample(t)) -
               JointMatrix(model.parts[bottom].joint, Vec3(0, 0, c.bottom)))
                  .norm(),
              1e-9);
    // The bottom's world rotation against the capture's (Ry(-80)): off by the twist the chain
    // could not take, about the bone, which still points along the capture's (-Y).
    const Mat3 world = ChainMotion(model, clip, bottom, t).rotation;
    const double lost = Eigen::AngleAxisd(world.transpose() * Ry(-80)).angle();
    EXPECT_NEAR(lost * kDegrees, 80.0 - c.middle - c.bottom, 1e-6);
    played->Evaluate(t);
    EXPECT_LT(Angle(PlayedBone(*played, bottom), -Vec3::UnitY()), 1e-6);
  }
  fs::remove_all(folder);
}

// ---------------------------------------------------------------------------------------------
// CMU 01_01 on the human.

TEST(MotionCapture, LoadsCmu0101) {
  Result<MotionCapture> loaded = LoadBvh(Asset("assimp/BVH/01_01.bvh"));
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  const MotionCapture& m = loaded.value();
  EXPECT_EQ(m.joints.size(), 31u);
  EXPECT_EQ(m.joints.front().name, "Hips");
  EXPECT_EQ(m.joints.back().name, "RThumb");
  EXPECT_EQ(m.channel_count, 6u + 30u * 3u);
  EXPECT_EQ(m.frame_count, 2752u);             // "Frames: 2752"
  EXPECT_DOUBLE_EQ(m.frame_time, 0.0083333);   // "Frame Time: .0083333", 120 per second
  EXPECT_DOUBLE_EQ(m.Frame(1)[1], 17.8693);    // the hips' height on the second line
  EXPECT_DOUBLE_EQ(m.values.back(), -0.9244);  // the last value of the last line
}

// The mocap sample's scene with its paths made absolute and its mapping's "limits" and "floor"
// set to `limits` and `floor` (a copy of the mapping in `folder`).
json HumanMocapScene(const fs::path& folder, const std::string& limits,
                     const std::string& floor = "free") {
  const fs::path here = fs::path(WIRERIG_SAMPLES_DIR) / "mocap";
  json scene = json::parse(std::ifstream(here / "human_mocap.scene.json"));
  json mapping = json::parse(std::ifstream(here / "human_from_cmu.mapping.json"));
  mapping["limits"] = limits;
  mapping["floor"] = floor;
  scene["mesh"]["file"] = (here / scene["mesh"]["file"].get<std::string>()).string();
  scene["rig"]["description"] = (here / scene["rig"]["description"].get<std::string>()).string();
  json& motion = scene["clips"][0]["motion"];
  motion["file"] = (here / motion["file"].get<std::string>()).string();
  motion["mapping"] = WriteFile(folder / "mapping.json", mapping.dump()).string();
  return scene;
}

// With "limits": "ignore" and "floor": "free" the capture is reproduced exactly, beyond the
// rig's limits and whatever the rig's proportions do to its feet.
TEST(HumanMocap, PlaysTheCaptureOnTheHuman) {
  const fs::path folder = TempFolder();
  std::unique_ptr<PlayedScene> played = samples::PlayDocument(HumanMocapScene(folder, "ignore"));
  ASSERT_NE(played, nullptr);
  Result<MotionCapture> loaded = LoadBvh(Asset("assimp/BVH/01_01.bvh"));
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  const MotionCapture& m = loaded.value();
  const RigModel& model = played->scene.model;
  const Clip& clip = played->playback->clip();
  const std::size_t first = 1;  // the scene plays frames 1..2751 (frame 0 is CMU's T-pose)
  EXPECT_NEAR(clip.duration, 2750 * m.frame_time, 1e-9);

  // Bones: part -> (joint, tip joint); the foot's tip is its toe's End Site.
  struct Bone {
    const char* part;
    const char* joint;
    const char* tip;
  };
  const std::vector<Bone> bones = {{"spine_1", "LowerBack", "Spine"},
                                   {"spine_2", "Spine", "Spine1"},
                                   {"chest", "Spine1", "Neck1"},
                                   {"neck", "Neck1", "Head"},
                                   {"upper_arm_l", "LeftArm", "LeftForeArm"},
                                   {"forearm_l", "LeftForeArm", "LeftHand"},
                                   {"upper_arm_r", "RightArm", "RightForeArm"},
                                   {"forearm_r", "RightForeArm", "RightHand"},
                                   {"thigh_l", "LeftUpLeg", "LeftLeg"},
                                   {"shin_l", "LeftLeg", "LeftFoot"},
                                   {"thigh_r", "RightUpLeg", "RightLeg"},
                                   {"shin_r", "RightLeg", "RightFoot"}};

  // The root's scale: the rig's leg (the lower foot's chain: thigh and shin root points) over
  // the capture's (hip -> knee -> ankle at rest).
  const bool left = model.parts[played->Part("foot_l")].spine_points.front().y() <=
                    model.parts[played->Part("foot_r")].spine_points.front().y();
  const auto front = [&](const char* part) {
    return model.parts[played->Part(part)].spine_points.front();
  };
  const double rig_leg = left ? (front("shin_l") - front("thigh_l")).norm() +
                                    (front("foot_l") - front("shin_l")).norm()
                              : (front("shin_r") - front("thigh_r")).norm() +
                                    (front("foot_r") - front("shin_r")).norm();
  const TestPose rest = PoseFrame(m, 0);  // frame 0 has rotations; rest = offsets summed
  auto rest_position = [&](const char* name) {
    Vec3 p = Vec3::Zero();
    for (int j = Joint(m, name); j >= 0; j = m.joints[std::size_t(j)].parent)
      p += m.joints[std::size_t(j)].offset;
    return p;
  };
  const char* side[3] = {left ? "LeftUpLeg" : "RightUpLeg", left ? "LeftLeg" : "RightLeg",
                         left ? "LeftFoot" : "RightFoot"};
  const double source_leg = (rest_position(side[1]) - rest_position(side[0])).norm() +
                            (rest_position(side[2]) - rest_position(side[1])).norm();
  const double s = rig_leg / source_leg;
  EXPECT_NEAR(s, 0.0564, 0.006);  // close to CMU's own 0.056444 m per unit
  (void)rest;

  const std::size_t pelvis = played->Part("pelvis");
  const Vec3 hips_start = PoseFrame(m, first).position[std::size_t(Joint(m, "Hips"))];
  double widest_knee = 0.0, widest_capture_knee = 0.0, highest = -1.0, lowest = 1.0;
  double worst_bone = 0.0, worst_chain = 0.0, worst_root = 0.0;
  for (std::size_t f = first; f < m.frame_count; f += 25) {
    const double t = double(f - first) * m.frame_time;
    played->Evaluate(t);
    for (const Vec3& p : played->positions)
      ASSERT_TRUE(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()))
          << "t = " << t;
    const TestPose pose = PoseFrame(m, f);
    for (const Bone& bone : bones) {
      const Vec3 capture = pose.position[std::size_t(Joint(m, bone.tip))] -
                           pose.position[std::size_t(Joint(m, bone.joint))];
      worst_bone =
          std::max(worst_bone, Angle(PlayedBone(*played, played->Part(bone.part)), capture));
    }
    for (const char* part : {"head", "hand_l", "foot_r", "chest"})
      worst_chain = std::max(worst_chain, SpineOffChain(*played, played->Part(part), t));
    // The pelvis's root point: its rest place plus the hips' travel scaled.
    const Vec3 hips = pose.position[std::size_t(Joint(m, "Hips"))];
    const Vec3 root = played->playback->workspace().spine_points[pelvis].front();
    const Vec3 expected_root = model.parts[pelvis].spine_points.front() + s * (hips - hips_start);
    worst_root = std::max(worst_root, (root - expected_root).norm());
    highest = std::max(highest, root.y() - model.parts[pelvis].spine_points.front().y());
    lowest = std::min(lowest, root.y() - model.parts[pelvis].spine_points.front().y());
    // Knee flexion: the angle between thigh and shin, in the rig and in the capture.
    const Vec3 thigh = pose.position[std::size_t(Joint(m, "LeftLeg"))] -
                       pose.position[std::size_t(Joint(m, "LeftUpLeg"))];
    const Vec3 shin = pose.position[std::size_t(Joint(m, "LeftFoot"))] -
                      pose.position[std::size_t(Joint(m, "LeftLeg"))];
    const double capture_knee = Angle(thigh, shin);
    const double knee = Angle(PlayedBone(*played, played->Part("thigh_l")),
                              PlayedBone(*played, played->Part("shin_l")));
    EXPECT_NEAR(knee, capture_knee, 0.01) << "t = " << t;
    widest_knee = std::max(widest_knee, knee);
    widest_capture_knee = std::max(widest_capture_knee, capture_knee);
  }
  EXPECT_LT(worst_bone, 1e-5);   // degrees: every mapped bone along the capture's
  EXPECT_LT(worst_chain, 1e-9);  // m: the spines follow the clip's chain of turns
  EXPECT_LT(worst_root, 1e-9);   // m
  EXPECT_NEAR(widest_knee, widest_capture_knee, 0.01);
  EXPECT_GT(widest_knee, 75.0);  // the jumps crouch deep
  EXPECT_GT(highest, 0.15);      // and leave the ground
  EXPECT_LT(lowest, -0.10);
  // The jumps travel forward about 3.6 m (scaled) before turning around.
  double farthest = 0.0;
  for (double t = 0.0; t < clip.duration; t += 0.5) {
    played->Evaluate(t);
    farthest = std::max(farthest, played->playback->workspace().spine_points[pelvis].front().z() -
                                      model.parts[pelvis].spine_points.front().z());
  }
  EXPECT_GT(farthest, 3.0);
  fs::remove_all(folder);
}

// The height of the lowest skin point above the rest skin's lowest point (the floor), m, at
// each 1/30 s of the played clip.
std::vector<double> LowestSkinHeights(PlayedScene& played) {
  std::vector<double> heights;
  double floor = std::numeric_limits<double>::infinity();
  for (const Vec3& p : played.scene.mesh.welded_positions) floor = std::min(floor, p.y());
  const double duration = played.playback->clip().duration;
  for (int k = 0; k / 30.0 <= duration; ++k) {
    played.Evaluate(k / 30.0);
    double lowest = std::numeric_limits<double>::infinity();
    for (const Vec3& p : played.positions) lowest = std::min(lowest, p.y());
    heights.push_back(lowest - floor);
  }
  return heights;
}

// "floor": "above" (the sample's): where the rig's proportions would sink a sole into the floor
// the root is lifted, so no skin point goes below it, and the feet still come down to it (the
// lowest point within 2 cm of the floor on most frames); "free" sinks them by 5 cm and more.
TEST(HumanMocap, KeepsTheSkinAboveTheFloorAndTheFeetOnIt) {
  const fs::path folder = TempFolder();
  for (const std::string floor : {"above", "free"}) {
    SCOPED_TRACE(floor);
    std::unique_ptr<PlayedScene> played =
        samples::PlayDocument(HumanMocapScene(folder, "pass_to_parents", floor));
    ASSERT_NE(played, nullptr);
    std::vector<double> heights = LowestSkinHeights(*played);
    ASSERT_GT(heights.size(), 600u);
    const double deepest = *std::min_element(heights.begin(), heights.end());
    std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
    const double median = heights[heights.size() / 2];
    if (floor == "above") {
      EXPECT_GT(deepest, -1e-3);
      EXPECT_LT(median, 0.02);
    } else {
      EXPECT_LT(deepest, -0.05);
    }
  }
  fs::remove_all(folder);
}

// The sample as checked in ("limits": "pass_to_parents"): at every key no joint leaves its
// limits; where the capture turns the neck past them (78 degrees of twist against the chest,
// 55 bent back) the spine takes the rest, so the head's world rotation stays nearer the
// capture's than a plain clamp puts it.
TEST(HumanMocap, StaysWithinTheJointLimits) {
  const fs::path folder = TempFolder();
  std::unique_ptr<PlayedScene> sample = samples::PlaySample("mocap/human_mocap.scene.json");
  std::unique_ptr<PlayedScene> exact = samples::PlayDocument(HumanMocapScene(folder, "ignore"));
  std::unique_ptr<PlayedScene> clamped = samples::PlayDocument(HumanMocapScene(folder, "clamp"));
  ASSERT_NE(sample, nullptr);
  ASSERT_NE(exact, nullptr);
  ASSERT_NE(clamped, nullptr);
  const RigModel& model = sample->scene.model;
  const Clip& clip = sample->playback->clip();
  const std::size_t head = sample->Part("head");
  const double frame = 0.0083333;  // the capture's frame time: every key
  double worst_excess = 0.0, head_error = 0.0, clamped_head_error = 0.0;
  for (std::size_t k = 0; double(k) * frame <= clip.duration + 1e-9; ++k) {
    const double t = double(k) * frame;
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
      const PartModel& part = model.parts[p];
      if (part.parent < 0 || clip.parts[p].rotation.IsEmpty()) continue;
      // The joint angles of the part's turn (X, Y, Z intrinsic about its joint axes, joint.h).
      const Mat3 local = part.joint.axes.transpose() *
                         FromVector(clip.parts[p].rotation.Sample(t)) * part.joint.axes;
      const double b = std::asin(std::clamp(local(0, 2), -1.0, 1.0));
      const Vec3 angles =
          Vec3(std::atan2(-local(1, 2), local(2, 2)), b, std::atan2(-local(0, 1), local(0, 0))) *
          kDegrees;
      Vec3 excess = (angles - part.joint.max_degrees).cwiseMax(part.joint.min_degrees - angles);
      if (part.joint.type == JointType::kHinge) excess.tail<2>() = angles.tail<2>().cwiseAbs();
      worst_excess = std::max(worst_excess, excess.maxCoeff());
    }
    const Mat3 wanted = ChainMotion(model, exact->playback->clip(), head, t).rotation;
    const auto error = [&](const PlayedScene& played) {
      const Mat3 off =
          ChainMotion(model, played.playback->clip(), head, t).rotation.transpose() * wanted;
      return Eigen::AngleAxisd(off).angle() * kDegrees;
    };
    head_error = std::max(head_error, error(*sample));
    clamped_head_error = std::max(clamped_head_error, error(*clamped));
  }
  EXPECT_LT(worst_excess, 1e-6);  // degrees beyond a limit, over every joint and key
  EXPECT_LT(head_error, clamped_head_error);
  fs::remove_all(folder);
}

// ---------------------------------------------------------------------------------------------
// Skinned assets' own animations.

// Assimp's node transforms at `tick`: keys interpolated (positions and scales linear, rotations
// slerp), the node's own transform where the channel keys nothing.
struct AssimpPoser {
  explicit AssimpPoser(const fs::path& path) { scene = importer.ReadFile(path.string(), 0); }
  static Eigen::Matrix4d ToMat(const aiMatrix4x4& m) {
    Eigen::Matrix4d out;
    out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
        m.d4;
    return out;
  }
  template <typename Key, typename Value>
  static Value Sample(const Key* keys, unsigned n, double tick, Value fallback, bool slerp) {
    if (n == 0) return fallback;
    if (tick <= keys[0].mTime) return keys[0].mValue;
    for (unsigned k = 0; k + 1 < n; ++k) {
      if (tick > keys[k + 1].mTime) continue;
      const ai_real u = ai_real((tick - keys[k].mTime) / (keys[k + 1].mTime - keys[k].mTime));
      if constexpr (std::is_same_v<Value, aiQuaternion>) {
        (void)slerp;
        aiQuaternion q;
        aiQuaternion::Interpolate(q, keys[k].mValue, keys[k + 1].mValue, u);
        return q.Normalize();
      } else {
        return keys[k].mValue + (keys[k + 1].mValue - keys[k].mValue) * u;
      }
    }
    return keys[n - 1].mValue;
  }
  // World transform of the node named `name` at `tick` of animation `a`.
  Eigen::Matrix4d Global(const std::string& name, unsigned a, double tick) const {
    const aiNode* node = scene->mRootNode->FindNode(name.c_str());
    Eigen::Matrix4d out = Eigen::Matrix4d::Identity();
    for (; node != nullptr; node = node->mParent) out = Local(node, a, tick) * out;
    return out;
  }
  Eigen::Matrix4d Local(const aiNode* node, unsigned a, double tick) const {
    const aiAnimation* animation = scene->mAnimations[a];
    for (unsigned c = 0; c < animation->mNumChannels; ++c) {
      const aiNodeAnim* ch = animation->mChannels[c];
      if (ch->mNodeName != node->mName) continue;
      aiVector3D scaling, position;
      aiQuaternion rotation;
      node->mTransformation.Decompose(scaling, rotation, position);
      position = Sample(ch->mPositionKeys, ch->mNumPositionKeys, tick, position, false);
      rotation = Sample(ch->mRotationKeys, ch->mNumRotationKeys, tick, rotation, true);
      scaling = Sample(ch->mScalingKeys, ch->mNumScalingKeys, tick, scaling, false);
      return ToMat(aiMatrix4x4(scaling, rotation, position));
    }
    return ToMat(node->mTransformation);
  }
  std::vector<double> KeyTicks(unsigned a) const {
    std::vector<double> ticks;
    const aiAnimation* animation = scene->mAnimations[a];
    for (unsigned c = 0; c < animation->mNumChannels; ++c) {
      const aiNodeAnim* ch = animation->mChannels[c];
      for (unsigned k = 0; k < ch->mNumRotationKeys; ++k)
        ticks.push_back(ch->mRotationKeys[k].mTime);
      for (unsigned k = 0; k < ch->mNumPositionKeys; ++k)
        ticks.push_back(ch->mPositionKeys[k].mTime);
    }
    std::sort(ticks.begin(), ticks.end());
    ticks.erase(std::unique(ticks.begin(), ticks.end()), ticks.end());
    return ticks;
  }
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
};

json AssetScene(const std::string& file, const json& animation) {
  json scene = json::parse(R"({"format": "wirerig.scene", "version": 1, "name": "asset",
    "mesh": {}, "rig": {"from": "automatic"}, "default_kind": "rigid",
    "clips": [{"name": "animation", "motion": {}}]})");
  scene["mesh"]["file"] = Asset(file).string();
  scene["clips"][0]["motion"] = {{"file", Asset(file).string()}, {"animation", animation}};
  return scene;
}

// Plays an asset's animation and checks, at the animation's key times and halfway between
// them, every part whose joint has a node: its joint, the joints of its children and its bone's
// tip (the far end of its spine) against where Assimp's animated node transforms put them
// (a point x of the bind pose goes to G(t) bind^-1 x). Returns the farthest a tip travels, over
// the mesh's size.
double ExpectBonesFollowTheAsset(const std::string& file, const json& animation,
                                 unsigned animation_index) {
  std::unique_ptr<PlayedScene> played = samples::PlayDocument(AssetScene(file, animation));
  if (played == nullptr) {
    ADD_FAILURE() << "the scene did not play";
    return 0.0;
  }
  const AssimpPoser poser(Asset(file));
  EXPECT_NE(poser.scene, nullptr);
  if (poser.scene == nullptr) return 0.0;
  const Mesh& mesh = played->scene.mesh;
  const RigModel& model = played->scene.model;
  const Clip& clip = played->playback->clip();
  const std::vector<double> ticks = poser.KeyTicks(animation_index);
  const double tps = poser.scene->mAnimations[animation_index]->mTicksPerSecond > 0
                         ? poser.scene->mAnimations[animation_index]->mTicksPerSecond
                         : 25.0;
  EXPECT_NEAR(clip.duration, (ticks.back() - ticks.front()) / tps, 1e-9);
  const double size = ComputeBounds(mesh).Diagonal();
  const auto joint_named = [&](const std::string& name) {
    for (std::size_t j = 0; j < mesh.joints.size(); ++j)
      if (mesh.joints[j].name == name) return int(j);
    return -1;
  };
  double travel = 0.0;
  std::size_t checked = 0;
  const std::size_t stride = std::max<std::size_t>(1, ticks.size() / 12);
  for (std::size_t i = 0; i < ticks.size(); i += stride) {
    // At the key (float keys: 1e-5 of the size) and halfway to the next (Assimp slerps each
    // node's local rotation, the clip interpolates each part's turn vector: 1%).
    for (double fraction : {0.0, 0.5}) {
      if (fraction > 0.0 && i + 1 >= ticks.size()) continue;
      const double tick =
          ticks[i] + fraction * (ticks[std::min(i + 1, ticks.size() - 1)] - ticks[i]);
      const double t = (tick - ticks.front()) / tps;
      const double tolerance = (fraction == 0.0 ? 1e-5 : 1e-2) * size;
      played->Evaluate(t);
      for (std::size_t p = 0; p < model.parts.size(); ++p) {
        const std::string& name = model.parts[p].name;
        EXPECT_LT(SpineOffChain(*played, p, t), 1e-9 * size) << name;
        const int joint = joint_named(name);
        if (joint < 0 || poser.scene->mRootNode->FindNode(name.c_str()) == nullptr) continue;
        const Eigen::Matrix4d g = poser.Global(name, animation_index, tick);
        const Eigen::Matrix4d bind = mesh.joints[std::size_t(joint)].bind_global;
        const auto carried = [&](const Vec3& x) -> Vec3 {
          const Vec3 local = bind.block<3, 3>(0, 0).transpose() * (x - bind.block<3, 1>(0, 3));
          return g.block<3, 3>(0, 0) * local + g.block<3, 1>(0, 3);
        };
        // The bone's tip: the played spine's far end.
        const Vec3 tip = played->playback->workspace().spine_points[p].back();
        const Vec3 rest_tip = model.parts[p].spine_points.back();
        EXPECT_LT((tip - carried(rest_tip)).norm(), tolerance)
            << file << ": the tip of " << name << " at tick " << tick;
        travel = std::max(travel, (tip - rest_tip).norm());
        ++checked;
        // The joint and its child joints that have nodes, carried by the part's motion.
        const Motion motion = ChainMotion(model, clip, p, t);
        for (std::size_t j = 0; j < mesh.joints.size(); ++j) {
          const bool own = int(j) == joint, child = mesh.joints[j].parent == joint;
          if (!own && !child) continue;
          if (poser.scene->mRootNode->FindNode(mesh.joints[j].name.c_str()) == nullptr) continue;
          const Vec3 animated =
              poser.Global(mesh.joints[j].name, animation_index, tick).block<3, 1>(0, 3);
          EXPECT_LT((motion(mesh.joints[j].bind_global.block<3, 1>(0, 3)) - animated).norm(),
                    tolerance)
              << file << ": part " << name << ", joint " << mesh.joints[j].name << " at tick "
              << tick;
        }
      }
    }
  }
  EXPECT_GT(checked, 10u);
  return travel / size;
}

TEST(AssetAnimation, AnimTestPlaysThroughItsSkeleton) {
  // joint1 -> joint2 are animated (joint3 has no node: it rides on joint2).
  const double travel = ExpectBonesFollowTheAsset("assimp/X/anim_test.x", 0, 0);
  EXPECT_GT(travel, 0.1);  // the tip moves by over a tenth of the cylinder's size
}

TEST(AssetAnimation, TestwusonRunsThroughItsSkeleton) {
  const double travel = ExpectBonesFollowTheAsset("assimp/X/Testwuson.X", "Wuson_Run", 0);
  EXPECT_GT(travel, 0.05);
}

// ---------------------------------------------------------------------------------------------
// Scenes: the motion object round-trips; clip tracks merge on top.

TEST(MotionScene, SaveThenLoadKeepsTheMotion) {
  Result<SceneDescription> loaded =
      LoadScene(samples::SampleScenePath("mocap/human_mocap.scene.json"));
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  ASSERT_EQ(loaded.value().motions.size(), 1u);
  const MotionSource& motion = loaded.value().motions.at("playground");
  EXPECT_EQ(motion.file, fs::path("../../.cache/assets/assimp/BVH/01_01.bvh"));
  EXPECT_EQ(motion.mapping, fs::path("human_from_cmu.mapping.json"));
  EXPECT_EQ(motion.first_frame, std::optional<std::size_t>(1));
  EXPECT_EQ(motion.last_frame, std::optional<std::size_t>(2751));
  const json saved = SceneToJson(loaded.value());
  EXPECT_FALSE(saved["clips"][0].contains("duration"));
  EXPECT_EQ(saved["clips"][0]["motion"]["frames"], json::array({1, 2751}));
  Result<SceneDescription> again = ParseScene(saved, loaded.value().folder);
  ASSERT_TRUE(again.ok()) << again.error();
  EXPECT_EQ(SceneToJson(again.value()), saved);
}

TEST(MotionScene, TheWusonSamplePlaysBothAnimations) {
  Result<BuiltScene> built =
      LoadAndBuildScene(samples::SampleScenePath("mocap/wuson_run.scene.json"));
  ASSERT_TRUE(built.ok()) << built.error();
  ASSERT_EQ(built.value().clips.size(), 2u);
  for (const char* name : {"run", "walk"}) {
    const Clip* clip = built.value().FindClip(name);
    ASSERT_NE(clip, nullptr) << name;
    EXPECT_GT(clip->duration, 0.5) << name;
    EXPECT_EQ(clip->loop, LoopMode::kLoop);
    std::size_t driven = 0;
    for (const PartChannels<Track>& part : clip->parts) driven += !part.rotation.IsEmpty();
    EXPECT_EQ(driven, built.value().model.parts.size()) << name;  // every bone has a node
  }
}

TEST(MotionScene, ClipTracksMergeWithTheMotion) {
  const fs::path folder = TempFolder();
  const fs::path bvh = WriteFile(folder / "three.bvh", kThreeJoints);
  const fs::path mapping = WriteFile(folder / "three.mapping.json", kThreeJointMapping);
  json scene = ChainScene(bvh, mapping);
  scene["clips"][0]["loop"] = "loop";
  scene["clips"][0]["parts"] = json::parse(R"([{"part": "bottom", "joint_angles": [0, 0, 10]}])");
  std::unique_ptr<PlayedScene> played = samples::PlayDocument(scene);
  ASSERT_NE(played, nullptr);
  const Clip& clip = played->playback->clip();
  EXPECT_EQ(clip.loop, LoopMode::kLoop);
  const std::size_t bottom = played->Part("bottom");
  EXPECT_FALSE(clip.parts[bottom].rotation.IsEmpty());
  EXPECT_EQ(clip.parts[bottom].joint_angles.Sample(0.2), Vec3(0, 0, 10));

  scene["clips"][0]["parts"] = json::parse(R"([{"part": "bottom", "rotation": [0, 0, 1]}])");
  EXPECT_EQ(samples::SceneError(scene),
            "scene \"chain\": /clips/0/parts/0/rotation: the motion drives this part's rotation");
  // A track of the clip's own is checked against the motion's duration (0.5 s here) under
  // the clip's own index, not its place among the motion's tracks.
  scene["clips"][0]["parts"] = json::parse(R"([{"part": "top", "point_loads": [
      {"at": 0.5, "magnitude": {"keys": [[0, 0], [2, 10]]}, "direction": [1, 0, 0]}]}])");
  EXPECT_EQ(samples::SceneError(scene),
            "scene \"chain\": /clips/0: parts[0].point_loads[0].magnitude.keys[1].time: must "
            "lie within the clip, [0, duration] (the motion lasts 0.5 s)");
  fs::remove_all(folder);
}

// ---------------------------------------------------------------------------------------------
// Bad input.

std::string BvhError(const std::string& text) {
  Result<MotionCapture> parsed = ParseBvh(text, "bad.bvh");
  return parsed.ok() ? "ok" : parsed.error();
}

// kThreeJoints with one piece replaced.
std::string ThreeJointsWith(const std::string& from, const std::string& to) {
  std::string text = kThreeJoints;
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(MotionErrors, BvhHierarchyAndMotionMustAgree) {
  EXPECT_EQ(BvhError(ThreeJointsWith("0 4 0 30 0 0 0 90 0 45 0 0", "0 4 0 30 0 0 0 90 0 45 0")),
            "bad.bvh: line 25: frame 1 has 11 values; the hierarchy's 3 joints have 12 channels");
  EXPECT_EQ(BvhError(ThreeJointsWith("0 4 0 30 0 0 0 90 0 45 0 0", "0 4 0 30 0 0 0 90 0 45 0 0 7")),
            "bad.bvh: line 25: frame 1 has 13 values; the hierarchy's 3 joints have 12 channels");
  EXPECT_EQ(BvhError(ThreeJointsWith("Frames: 2", "Frames: 3")),
            "bad.bvh: line 25: \"Frames: 3\" but the file holds 2 frame lines");
  EXPECT_EQ(BvhError(ThreeJointsWith("Frames: 2", "Frames: 1")),
            "bad.bvh: line 25: more frame lines than \"Frames: 1\" says");
  EXPECT_EQ(BvhError(ThreeJointsWith("CHANNELS 3 Zrotation Xrotation Yrotation",
                                     "CHANNELS 4 Zrotation Xrotation Yrotation")),
            "bad.bvh: line 10: CHANNELS in joint \"B\" says \"4\" but names only 3");
  EXPECT_EQ(BvhError(ThreeJointsWith("Xrotation Yrotation", "Xrotation Wrotation")),
            "bad.bvh: line 9: CHANNELS in joint \"B\": unknown channel \"Wrotation\" "
            "(Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation)");
  EXPECT_EQ(BvhError(ThreeJointsWith("JOINT C", "JOINT B")),
            "bad.bvh: line 10: a second joint named \"B\"");
  EXPECT_EQ(BvhError(ThreeJointsWith("}\nMOTION", "MOTION")),
            "bad.bvh: line 20: \"MOTION\" before joint \"A\" is closed with \"}\"");
  EXPECT_EQ(BvhError(ThreeJointsWith("OFFSET 10 0 0\n    CHANNELS", "OFFSET 10 0\n    CHANNELS")),
            "bad.bvh: line 9: in joint \"B\"'s OFFSET: \"CHANNELS\" is not a number");
  EXPECT_EQ(BvhError("ROOT A"),
            "bad.bvh: line 1: expected \"HIERARCHY\" at the start of the "
            "file, found \"ROOT\"");
  EXPECT_EQ(BvhError(ThreeJointsWith("MOTION\nFrames: 2\nFrame Time: 0.5\n", "")),
            "bad.bvh: line 21: expected \"MOTION\" after the hierarchy, found \"0\"");
  // Non-finite values, named by frame, value and channel.
  EXPECT_EQ(BvhError(ThreeJointsWith("0 90 0 45 0 0", "0 90 0 nan 0 0")),
            "bad.bvh: line 25: frame 1, value 9 (C Zrotation): \"nan\" is not finite");
  EXPECT_EQ(BvhError(ThreeJointsWith("0 90 0 45 0 0", "0 90 0 1e999 0 0")),
            "bad.bvh: line 25: frame 1, value 9 (C Zrotation): \"1e999\" is not finite");
  EXPECT_EQ(BvhError(ThreeJointsWith("Frame Time: 0.5", "Frame Time: 0")),
            "bad.bvh: line 23: Frame Time: must be a number of seconds in [1e-4, 1e6], not \"0\"");
  EXPECT_EQ(BvhError(ThreeJointsWith("Frame Time: 0.5", "Frame Time: 1e-300")),
            "bad.bvh: line 23: Frame Time: must be a number of seconds in [1e-4, 1e6], not "
            "\"1e-300\"");
  EXPECT_EQ(BvhError(ThreeJointsWith("OFFSET 5 0 0", "OFFSET 5 inf 0")),
            "bad.bvh: line 16: the End Site OFFSET of \"C\": \"inf\" is not finite");
  // Every truncation of the file is refused (and nothing crashes).
  const std::string whole = kThreeJoints;
  for (std::size_t n = 0; n + 1 < whole.size(); ++n) {
    const std::string cut = whole.substr(0, n);
    if (cut.ends_with("0 4 0 30 0 0 0 90 0 45 0 0")) continue;  // whole but the newline
    EXPECT_NE(BvhError(cut), "ok") << "cut at " << n;
  }
  // A header claiming more frames than the file holds allocates nothing for them.
  EXPECT_EQ(BvhError(ThreeJointsWith("Frames: 2", "Frames: 8000000")),
            "bad.bvh: line 25: \"Frames: 8000000\" but the file holds 2 frame lines");
  // A file that is not there.
  EXPECT_EQ(LoadBvh("/nonexistent/motion.bvh").error(), "/nonexistent/motion.bvh: no such file");
}

TEST(MotionErrors, MappingsMustNameJointsAndPartsThatExist) {
  const fs::path folder = TempFolder();
  const fs::path bvh = WriteFile(folder / "three.bvh", kThreeJoints);
  auto error_with = [&](const json& mapping) {
    const fs::path path = WriteFile(folder / "bad.mapping.json", mapping.dump());
    return samples::SceneError(ChainScene(bvh, path));
  };
  const std::string mapping_file = (folder / "bad.mapping.json").string();
  const std::string prefix = "scene \"chain\": /clips/0/motion/mapping: " + mapping_file + ": ";
  json mapping = json::parse(kThreeJointMapping);
  mapping["joints"]["Elbow"] = "middle";
  mapping["joints"].erase("B");
  EXPECT_EQ(error_with(mapping),
            prefix + "/joints/Elbow: " + bvh.string() + " has no joint of this name");
  mapping = json::parse(kThreeJointMapping);
  mapping["joints"]["C"] = "foot";
  EXPECT_EQ(error_with(mapping), prefix +
                                     "/joints/C/part: the rig has no part \"foot\" (parts: top, "
                                     "middle, bottom)");
  mapping = json::parse(kThreeJointMapping);
  mapping["joints"]["B"] = {{"part", "middle"}, {"tip", "A"}};
  EXPECT_EQ(error_with(mapping),
            prefix + "/joints/B/tip: \"A\" is not below joint \"B\" in " + bvh.string());
  mapping = json::parse(kThreeJointMapping);
  mapping["joints"]["C"] = "middle";
  EXPECT_EQ(error_with(mapping),
            prefix + "/joints/C: part \"middle\" is already driven by joint \"B\"");
  mapping = json::parse(kThreeJointMapping);
  mapping["source"]["up_axis"] = "w";
  EXPECT_EQ(error_with(mapping), prefix + "/source/up_axis: must be \"x\", \"y\" or \"z\"");
  mapping = json::parse(kThreeJointMapping);
  mapping["limits"] = "soft";
  EXPECT_EQ(error_with(mapping),
            prefix + "/limits: must be \"pass_to_parents\", \"clamp\" or \"ignore\"");
  mapping = json::parse(kThreeJointMapping);
  mapping["floor"] = "below";
  EXPECT_EQ(error_with(mapping), prefix + "/floor: must be \"above\" or \"free\"");
  mapping = json::parse(kThreeJointMapping);
  mapping["source"]["unit_scale"] = -1;
  EXPECT_EQ(error_with(mapping), prefix +
                                     "/source/unit_scale: must be a finite number of metres "
                                     "per unit in [1e-9, 1e9]");
  // Non-finite: JSON has no infinities; a literal too large for a double is refused.
  WriteFile(folder / "bad.mapping.json",
            R"({"format": "wirerig.motion_mapping", "version": 1, "source": {"unit_scale": 1e999},
                "joints": {"A": "top"}})");
  EXPECT_EQ(samples::SceneError(ChainScene(bvh, folder / "bad.mapping.json"))
                .substr(0, prefix.size() + 31),
            prefix + "not valid JSON: line 1, column ");
  mapping = json::parse(kThreeJointMapping);
  mapping["joints"]["B"] = {{"part", "middle"}, {"bone", "C"}};
  EXPECT_EQ(error_with(mapping),
            prefix + "/joints/B/bone: unknown field (known fields: part, tip)");
  // A mapped root without a leg below it cannot scale its translation by leg length.
  mapping = json::parse(kThreeJointMapping);
  mapping["joints"].erase("C");
  EXPECT_EQ(error_with(mapping).substr(0, prefix.size() + 14), prefix + "/root_scale: \"");
  mapping["root_scale"] = "unit";
  EXPECT_EQ(error_with(mapping), "ok");
  // The scene's motion object.
  json scene = ChainScene(bvh, folder / "missing.mapping.json");
  EXPECT_EQ(samples::SceneError(scene), "scene \"chain\": /clips/0/motion/mapping: " +
                                            (folder / "missing.mapping.json").string() +
                                            ": no such file");
  scene["clips"][0]["duration"] = 3;
  EXPECT_EQ(samples::SceneError(scene),
            "/clips/0/duration: a clip with a motion takes its duration from the motion (cut it "
            "with motion/frames)");
  scene = ChainScene(bvh, folder / "missing.mapping.json");
  scene["clips"][0]["motion"].erase("mapping");
  EXPECT_EQ(samples::SceneError(scene),
            "/clips/0/motion: a BVH motion needs \"mapping\" (a wirerig.motion_mapping file)");
  scene = ChainScene(bvh, WriteFile(folder / "good.mapping.json", kThreeJointMapping));
  scene["clips"][0]["motion"]["frames"] = json::array({1, 5});
  EXPECT_EQ(samples::SceneError(scene),
            "scene \"chain\": /clips/0/motion/frames: [1, 5] must be first <= last within the "
            "capture's frames 0..1 (" +
                bvh.string() + ")");
  scene["clips"][0]["motion"]["frames"] = json::array({1, 1});
  EXPECT_EQ(samples::SceneError(scene), "ok");
  // A capture longer than a clip may be is its frames' problem, not the mapping's.
  std::string three_frames =
      ThreeJointsWith("Frames: 2\nFrame Time: 0.5", "Frames: 3\nFrame Time: 600000");
  three_frames += three_frames.substr(three_frames.rfind('\n', three_frames.size() - 2) + 1);
  const fs::path slow = WriteFile(folder / "slow.bvh", three_frames);
  scene = ChainScene(slow, folder / "good.mapping.json");
  EXPECT_EQ(samples::SceneError(scene),
            "scene \"chain\": /clips/0/motion/frames: [0, 2] of " + slow.string() +
                " last 1.2e+06 s at its Frame Time of 600000 s, more than a clip may (1e6 s)");
  scene["clips"][0]["motion"]["frames"] = json::array({1, 1});
  EXPECT_EQ(samples::SceneError(scene), "ok");
  scene = ChainScene(WriteFile(folder / "short.bvh", ThreeJointsWith("0 90 0 45 0 0", "0 90")),
                     folder / "good.mapping.json");
  EXPECT_EQ(samples::SceneError(scene),
            "scene \"chain\": /clips/0/motion/file: " + (folder / "short.bvh").string() +
                ": line 25: frame 1 has 8 values; the hierarchy's 3 joints have 12 channels");
  fs::remove_all(folder);
}

TEST(MotionErrors, AnimationsMustExist) {
  json scene = AssetScene("assimp/X/anim_test.x", 3);
  const std::string file = Asset("assimp/X/anim_test.x").string();
  EXPECT_EQ(samples::SceneError(scene),
            "scene \"asset\": /clips/0/motion/animation: " + file +
                ": animation index 3 is out of range: it holds 1 animation (cylinder_test)");
  scene = AssetScene("assimp/X/Testwuson.X", "Wuson_Jump");
  EXPECT_EQ(
      samples::SceneError(scene),
      "scene \"asset\": /clips/0/motion/animation: " + Asset("assimp/X/Testwuson.X").string() +
          ": no animation named \"Wuson_Jump\" (it holds: Wuson_Run, Wuson_Walk, "
          "Wuson_Bind)");
  scene = AssetScene("assimp/X/anim_test.x", -1);
  EXPECT_EQ(samples::SceneError(scene),
            "/clips/0/motion/animation: must be an index (0, 1, ...) or a name");
  scene = AssetScene("assimp/X/anim_test.x", 0);
  scene["clips"][0]["motion"]["mapping"] = "x.json";
  EXPECT_EQ(samples::SceneError(scene),
            "/clips/0/motion/mapping: is for BVH motion captures (\"file\" names no .bvh file); a "
            "skinned asset plays on its "
            "own skeleton");
  // A file without animations.
  scene = AssetScene("assimp/X/anim_test.x", 0);
  scene["clips"][0]["motion"]["file"] = Asset("assimp/X/test.x").string();
  EXPECT_EQ(samples::SceneError(scene),
            "scene \"asset\": /clips/0/motion/file: " + Asset("assimp/X/test.x").string() +
                ": holds no animation");
  // A folder where the file should be: said so, not "no such motion file".
  scene["clips"][0]["motion"]["file"] = Asset("assimp/X").string();
  EXPECT_EQ(samples::SceneError(scene),
            "scene \"asset\": /clips/0/motion/file: " + Asset("assimp/X").string() +
                ": is a directory, not a motion file");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

// Motion files go through Assimp as meshes do: with the scene's import isolation, in a child
// process, so a file that crashes Assimp ends the child only.
TEST(MotionIsolation, AnIsolatedImportGivesTheSameClipAsInProcess) {
  std::unique_ptr<PlayedScene> played =
      samples::PlayDocument(AssetScene("assimp/X/Testwuson.X", "Wuson_Run"));
  ASSERT_NE(played, nullptr);
  AssetAnimationOptions options;
  options.animation_name = "Wuson_Run";
  const fs::path file = Asset("assimp/X/Testwuson.X");
  Result<RawClip> in_process =
      ClipFromAssetAnimation(file, played->scene.mesh, played->scene.model, options);
  ASSERT_TRUE(in_process) << in_process.error();
  options.import.isolation = ImportIsolation{};
  Result<RawClip> isolated =
      ClipFromAssetAnimation(file, played->scene.mesh, played->scene.model, options);
  ASSERT_TRUE(isolated) << isolated.error();
  EXPECT_GT(in_process.value().parts.size(), 3u);
  EXPECT_EQ(ClipToJson(isolated.value()), ClipToJson(in_process.value()));
}

// One byte of Assimp's binary X test cube changed: Assimp reads through a bad pointer
// (tests/rig/isolated_import_test.cpp). As a scene's motion file it fails the scene naming the
// file, and this process lives on.
TEST(MotionIsolation, ACorruptedMotionFileCrashesOnlyTheChild) {
  const fs::path source = Asset("assimp/X/test_cube_binary.x");
  std::ifstream in(source, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 2816u) << source;
  bytes[2609] = static_cast<char>(0xb2);
  const fs::path folder = fs::temp_directory_path() / "wirerig_motion_isolation";
  fs::create_directories(folder);
  const fs::path corrupted = WriteFile(folder / "corrupted.x", bytes);
  json document = AssetScene("assimp/X/anim_test.x", 0);
  document["clips"][0]["motion"]["file"] = corrupted.string();
  Result<SceneDescription> scene = ParseScene(document, folder);
  ASSERT_TRUE(scene) << scene.error();
  scene.value().mesh.import.isolation = ImportIsolation{};
  const Result<BuiltScene> built = BuildScene(scene.value());
  ASSERT_FALSE(built);
  EXPECT_NE(built.error().find("/clips/0/motion/file: " + corrupted.string() +
                               ": the importer crashed on this file ("),
            std::string::npos)
      << built.error();
  fs::remove_all(folder);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
