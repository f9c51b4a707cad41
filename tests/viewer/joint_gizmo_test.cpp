// The joint rotation gizmo: rings per joint type, hit-testing, the angle a drag sweeps (signed by
// the right-hand rule about the ring's axis as seen from the eye), clamping to the joint's
// limits, the posed joint frame, and a scripted drag on a ring in the scene viewer turning the
// joint.
#include "wirerig/viewer/joint_gizmo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>

#include <nlohmann/json.hpp>

#include "test_scenes.h"
#include "wirerig/anim/scene.h"
#include "wirerig/viewer/scene_frame.h"
#include "wirerig/viewer/scene_viewer.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using testing::ScopedNoFpTraps;

constexpr double kPi = std::numbers::pi;

Vec2f Pixel(const Camera& camera, Size size, const Vec3& p) {
  Vec2f pixel = Vec2f::Zero();
  EXPECT_TRUE(ProjectToPixel(camera, size, p.cast<float>(), &pixel));
  return pixel;
}

float DistanceToRing(const JointGizmoRing& ring, const Vec2f& p) {
  float best = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < ring.pixels.size(); ++i) {
    const Vec2f a = ring.pixels[i], b = ring.pixels[(i + 1) % ring.pixels.size()];
    const float t =
        std::clamp((p - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-12f), 0.0f, 1.0f);
    best = std::min(best, (a + t * (b - a) - p).norm());
  }
  return best;
}

// A camera on +Z looking at the origin: world X is screen right, Y screen up, Z at the eye.
class JointGizmoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    camera_.yaw = 0.0f;
    camera_.pitch = 0.0f;
    camera_.distance = 4.0f;
    camera_.target = Vec3f::Zero();
  }
  JointGizmo Ball(const Mat3& axes = Mat3::Identity()) const {
    return BuildJointGizmo(camera_, size_, Vec3::Zero(), axes, JointType::kBall);
  }

  Camera camera_;
  Size size_{800, 600};
};

TEST_F(JointGizmoTest, BallHasThreeRingsHingeOneFixedNone) {
  const JointGizmo ball = Ball();
  ASSERT_TRUE(ball.visible);
  ASSERT_EQ(ball.rings.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(ball.rings[std::size_t(k)].axis, k);
  const JointGizmo hinge =
      BuildJointGizmo(camera_, size_, Vec3::Zero(), Mat3::Identity(), JointType::kHinge);
  ASSERT_TRUE(hinge.visible);
  ASSERT_EQ(hinge.rings.size(), 1u);
  EXPECT_EQ(hinge.rings[0].axis, 0);
  EXPECT_TRUE(hinge.rings[0].world_axis.isApprox(Vec3::UnitX()));
  const JointGizmo fixed =
      BuildJointGizmo(camera_, size_, Vec3::Zero(), Mat3::Identity(), JointType::kFixed);
  EXPECT_FALSE(fixed.visible);
  EXPECT_TRUE(fixed.rings.empty());
  EXPECT_EQ(HitTestJointGizmo(fixed, Vec2f(400.0f, 300.0f)), -1);
  // Behind the eye: nothing to draw.
  const JointGizmo behind =
      BuildJointGizmo(camera_, size_, Vec3(0, 0, 10), Mat3::Identity(), JointType::kBall);
  EXPECT_FALSE(behind.visible);
}

TEST_F(JointGizmoTest, RingsKeepTheirSizeOnScreenAndStartNearestTheEye) {
  const JointGizmo gizmo = Ball();
  EXPECT_LT((gizmo.center_pixel - Vec2f(400.0f, 300.0f)).norm(), 1e-3f);
  // Ring Z faces the eye: a circle of radius_pixels, starting at its top on screen.
  const JointGizmoRing& z = gizmo.rings[2];
  EXPECT_NEAR(z.facing, 1.0, 1e-6);
  for (const Vec2f& p : z.pixels)
    EXPECT_NEAR((p - gizmo.center_pixel).norm(), gizmo.radius_pixels, 0.05f);
  EXPECT_NEAR(z.pixels[0].x(), 400.0f, 1e-3f);
  EXPECT_LT(z.pixels[0].y(), 300.0f);
  // Twice as far, twice as large in the world, same on screen.
  camera_.distance = 8.0f;
  const JointGizmo far = Ball();
  EXPECT_NEAR(far.radius, 2.0 * gizmo.radius, 1e-6 * gizmo.radius);
  EXPECT_NEAR((far.rings[2].pixels[5] - far.center_pixel).norm(), far.radius_pixels, 0.05f);
  // Ring X is edge-on: point 0, nearest the eye, is the world point (0, 0, r).
  EXPECT_NEAR(gizmo.rings[0].facing, 0.0, 1e-6);
  EXPECT_LT((gizmo.rings[0].pixels[0] - Pixel(camera_, size_, Vec3(0, 0, gizmo.radius))).norm(),
            1e-2f);
}

TEST_F(JointGizmoTest, APointOnARingHitsThatRingAndAFarPointNothing) {
  const JointGizmo gizmo = Ball();
  // Ring Z at 45 degrees: away from rings X (a vertical line) and Y (a horizontal line).
  const JointGizmoRing& z = gizmo.rings[2];
  const std::size_t eighth = z.pixels.size() / 8;
  const Vec2f on_z = 0.5f * (z.pixels[eighth] + z.pixels[eighth + 1]);
  EXPECT_EQ(HitTestJointGizmo(gizmo, on_z), 2);
  EXPECT_EQ(HitTestJointGizmo(gizmo, on_z + Vec2f(3.0f, -2.0f)), 2);  // within a few pixels
  EXPECT_EQ(HitTestJointGizmo(gizmo, Vec2f(700.0f, 300.0f)), -1);     // far outside
  EXPECT_EQ(HitTestJointGizmo(gizmo, Vec2f(430.0f, 330.0f)), -1);     // inside, off every ring
  // On ring X's projection (the vertical line through the centre), off ring Y's.
  EXPECT_EQ(HitTestJointGizmo(gizmo, Vec2f(400.5f, 300.0f - 0.5f * gizmo.radius_pixels)), 0);
}

TEST_F(JointGizmoTest, EveryRingIsHitOnItsOwnPolylineFromAnObliqueCamera) {
  camera_.yaw = 0.6f;
  camera_.pitch = 0.35f;
  const Mat3 axes = Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const JointGizmo gizmo = Ball(axes);
  ASSERT_EQ(gizmo.rings.size(), 3u);
  for (std::size_t r = 0; r < 3; ++r) {
    const JointGizmoRing& ring = gizmo.rings[r];
    bool tested = false;
    for (std::size_t i = 0; i < ring.pixels.size() && !tested; ++i) {
      const Vec2f p = 0.5f * (ring.pixels[i] + ring.pixels[(i + 1) % ring.pixels.size()]);
      bool clear = ring.toward_eye[i] > 0.0f;
      for (std::size_t o = 0; o < 3; ++o)
        if (o != r) clear = clear && DistanceToRing(gizmo.rings[o], p) > 12.0f;
      if (!clear) continue;
      EXPECT_EQ(HitTestJointGizmo(gizmo, p), int(r)) << "ring " << r << " point " << i;
      tested = true;
    }
    EXPECT_TRUE(tested) << "ring " << r;
  }
}

TEST_F(JointGizmoTest, AQuarterTurnAroundTheCentreIsNinetyDegreesByTheRightHandRule) {
  const JointGizmo gizmo = Ball();
  const JointGizmoRing& z = gizmo.rings[2];  // axis +Z points at the eye
  ASSERT_GT(z.facing, 0.9);
  // A positive quarter turn about +Z takes (r, 0, 0) to (0, r, 0): right of the centre to
  // above it, anticlockwise on screen.
  const double r = gizmo.radius;
  const Vec3 start(r, 0, 0);
  const Vec3 end = Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()) * start;
  const Vec2f from = Pixel(camera_, size_, start), to = Pixel(camera_, size_, end);
  EXPECT_GT(from.x(), gizmo.center_pixel.x() + 80.0f);
  EXPECT_LT(to.y(), gizmo.center_pixel.y() - 80.0f);
  EXPECT_NEAR(SweptRingDegrees(gizmo, 2, from, to), 90.0, 1e-3);
  EXPECT_NEAR(SweptRingDegrees(gizmo, 2, to, from), -90.0, 1e-3);
  // The same mouse path on a ring whose axis points away from the eye turns it the other way.
  Mat3 flipped = Mat3::Identity();
  flipped.col(2) = -Vec3::UnitZ();
  flipped.col(1) = -Vec3::UnitY();  // keep the frame right-handed
  const JointGizmo away = Ball(flipped);
  ASSERT_LT(away.rings[2].facing, -0.9);
  EXPECT_NEAR(SweptRingDegrees(away, 2, from, to), -90.0, 1e-3);
  // Dragged in small steps through the whole quarter, from the start angles, the joint turns by
  // +90 about Z.
  JointModel ball;
  JointGizmoDrag drag = BeginJointGizmoDrag(gizmo, 2, from, Vec3(10, 0, 0));
  EXPECT_EQ(drag.axis, 2);
  EXPECT_FALSE(drag.along_tangent);
  Vec3 angles = Vec3::Zero();
  for (int step = 1; step <= 9; ++step) {
    const Vec3 p = Eigen::AngleAxisd(kPi / 2 * step / 9.0, Vec3::UnitZ()) * start;
    angles = UpdateJointGizmoDrag(gizmo, ball, Pixel(camera_, size_, p), &drag);
  }
  EXPECT_NEAR(angles.x(), 10.0, 1e-9);
  EXPECT_NEAR(angles.y(), 0.0, 1e-9);
  EXPECT_NEAR(angles.z(), 90.0, 1e-3);
}

TEST_F(JointGizmoTest, WalkingARingInItsOrderSweepsPlusOneTurnFromAnyCamera) {
  camera_.yaw = -0.9f;
  camera_.pitch = 0.5f;
  const Mat3 axes = Eigen::AngleAxisd(1.1, Vec3(0.3, -1, 0.2).normalized()).toRotationMatrix();
  const JointGizmo gizmo = Ball(axes);
  for (std::size_t r = 0; r < gizmo.rings.size(); ++r) {
    const JointGizmoRing& ring = gizmo.rings[r];
    if (std::abs(ring.facing) < gizmo.options.edge_on_cosine) continue;
    double total = 0.0;
    for (std::size_t i = 0; i < ring.pixels.size(); ++i)
      total += SweptRingDegrees(gizmo, int(r), ring.pixels[i],
                                ring.pixels[(i + 1) % ring.pixels.size()]);
    EXPECT_NEAR(total, 360.0, 1e-2) << "ring " << r;
  }
}

TEST_F(JointGizmoTest, AnEdgeOnRingDragsAlongItsTangent) {
  const JointGizmo gizmo = Ball();
  // Ring X is seen edge-on. Its point nearest the eye, (0, 0, r), is on the centre of the
  // screen; a positive turn about +X moves it along X x Z = -Y: down the screen.
  const JointGizmoRing& x = gizmo.rings[0];
  ASSERT_LT(std::abs(x.facing), gizmo.options.edge_on_cosine);
  JointGizmoDrag drag = BeginJointGizmoDrag(gizmo, 0, x.pixels[0], Vec3::Zero());
  ASSERT_TRUE(drag.along_tangent);
  EXPECT_GT(drag.tangent.y(), 0.99f);
  // One ring radius of travel along the tangent is one radian; a quarter turn is pi/2 radii.
  const Vec2f end = x.pixels[0] + Vec2f(0.0f, float(kPi / 2) * gizmo.radius_pixels);
  const Vec3 angles = UpdateJointGizmoDrag(gizmo, JointModel{}, end, &drag);
  EXPECT_NEAR(angles.x(), 90.0, 0.5);
  EXPECT_NEAR(angles.y(), 0.0, 1e-12);
}

TEST(JointGizmo, RingAxesAreTheJointsGimbalSoEachRingTurnsItsOwnAngle) {
  JointModel joint;
  joint.axes = Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
  const Vec3 degrees(25, -40, 60);
  const Mat3 axes = JointGizmoAxes(joint, joint.axes, degrees);
  const Quat now = JointRotation(joint, degrees);
  for (int k = 0; k < 3; ++k) {
    Vec3 turned = degrees;
    turned[k] += 17.0;
    const Quat expected = JointRotation(joint, turned);
    const Quat about_ring = Quat(Eigen::AngleAxisd(17.0 * kPi / 180.0, axes.col(k))) * now;
    EXPECT_TRUE(expected.toRotationMatrix().isApprox(about_ring.toRotationMatrix(), 1e-12))
        << "axis " << k;
  }
}

TEST(JointGizmo, DraggedAnglesAreClampedToTheJointsLimitsAndType) {
  JointModel hinge;
  hinge.type = JointType::kHinge;
  hinge.min_degrees = Vec3(-10, -180, -180);
  hinge.max_degrees = Vec3(60, 180, 180);
  EXPECT_EQ(TurnJointAngles(hinge, Vec3(50, 0, 0), 0, 30.0), Vec3(60, 0, 0));
  EXPECT_EQ(TurnJointAngles(hinge, Vec3(0, 0, 0), 0, -90.0), Vec3(-10, 0, 0));
  EXPECT_EQ(TurnJointAngles(hinge, Vec3(20, 0, 0), 1, 45.0), Vec3(20, 0, 0));  // no Y angle
  JointModel ball;
  ball.min_degrees = Vec3(-90, -20, -45);
  ball.max_degrees = Vec3(90, 20, 45);
  EXPECT_EQ(TurnJointAngles(ball, Vec3(5, 0, 0), 1, 90.0), Vec3(5, 20, 0));
  JointModel fixed;
  fixed.type = JointType::kFixed;
  EXPECT_EQ(TurnJointAngles(fixed, Vec3(5, 5, 5), 2, 10.0), Vec3::Zero());

  // A drag through a full quarter turn on a hinge limited to [-10, 60] stops at 60, and
  // dragging back from beyond the limit turns back from where the mouse is, not from 60.
  Camera camera;
  camera.yaw = 0.0f;
  camera.pitch = 0.0f;
  Mat3 axes = Mat3::Identity();  // the hinge axis X points at the eye
  axes.col(0) = Vec3::UnitZ();
  axes.col(1) = Vec3::UnitX();
  axes.col(2) = Vec3::UnitY();
  const Size size{800, 600};
  const JointGizmo gizmo = BuildJointGizmo(camera, size, Vec3::Zero(), axes, JointType::kHinge);
  ASSERT_EQ(gizmo.rings.size(), 1u);
  const Vec2f c = gizmo.center_pixel;
  const float r = gizmo.radius_pixels;
  JointGizmoDrag drag = BeginJointGizmoDrag(gizmo, 0, c + Vec2f(r, 0), Vec3::Zero());
  Vec3 angles = Vec3::Zero();
  for (int step = 1; step <= 10; ++step) {
    const double a = kPi / 2 * step / 10.0;  // anticlockwise on screen
    angles = UpdateJointGizmoDrag(gizmo, hinge,
                                  c + r * Vec2f(float(std::cos(a)), -float(std::sin(a))), &drag);
  }
  EXPECT_NEAR(drag.swept_degrees, 90.0, 1e-3);
  EXPECT_EQ(angles, Vec3(60, 0, 0));
  const double back = kPi / 2 * 0.5;  // back to 45 degrees
  angles = UpdateJointGizmoDrag(
      gizmo, hinge, c + r * Vec2f(float(std::cos(back)), -float(std::sin(back))), &drag);
  EXPECT_NEAR(angles.x(), 45.0, 1e-3);
}

// Two parts of a cylinder standing on +Y: "base" (the root) from the top down to the middle,
// and "arm" hanging from it, on a hinge whose axis faces the viewer's default camera.
nlohmann::json JointedScene() {
  return nlohmann::json::parse(R"({
    "format": "wirerig.scene", "version": 1, "name": "jointed",
    "mesh": {"procedural": "cylinder", "parameters": {"radius": 0.1, "height": 1.0}},
    "rig": {"description": {"parts": [
      {"name": "base", "central_curve": [[0, 1, 0], [0, 0.5, 0]],
       "profile_count": 6, "points_per_profile": 24},
      {"name": "arm", "parent": "base", "central_curve": [[0, 0.5, 0], [0, 0, 0]],
       "profile_count": 6, "points_per_profile": 24,
       "joint": {"type": "hinge", "axis": [0.565, 0, 0.825], "limits": {"x": [-90, 90]}}}]}}
  })");
}

TEST(JointGizmo, PosedJointFollowsTheParentAndLeavesOutTheInteractiveTurn) {
  const BuiltScene scene = BuildScene(ParseScene(JointedScene(), ".").value()).value();
  const RigModel& model = scene.model;
  ASSERT_EQ(model.parts.size(), 2u);
  ASSERT_EQ(model.parts[1].parent, 0);
  const JointModel& joint = model.parts[1].joint;
  EXPECT_EQ(joint.type, JointType::kHinge);
  RigWorkspace workspace = MakeRigWorkspace(model);
  std::vector<Vec3> positions(model.vertices.size());
  std::vector<PartPose> poses(2);
  // The base turns 90 degrees about +Z about its root (the top); the arm by 30 on its hinge.
  const Quat base_turn(Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()));
  poses[0].rotation = base_turn;
  const Vec3 interactive(30, 0, 0);
  poses[1].rotation = JointRotation(joint, interactive);
  EvaluateRigJob job;
  job.model = &model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  ASSERT_TRUE(job.Run().ok());
  const PosedJoint posed = PoseJoint(model, workspace, 1, poses[1], interactive);
  // The joint at (0, 0.5, 0) swings about the top (0, 1, 0) to (0.5, 1, 0).
  const Vec3 root = model.parts[1].spine_points.front();
  const Vec3 top = model.parts[0].spine_points.front();
  EXPECT_TRUE(posed.center.isApprox(top + base_turn * (root - top), 1e-9));
  EXPECT_LT((posed.center - workspace.spine_points[1].front()).norm(), 1e-9);
  EXPECT_TRUE(posed.frame.isApprox(base_turn.toRotationMatrix() * joint.axes, 1e-9));
  // The arm's bone, turned by the hinge, leaves the joint along the posed frame's gimbal.
  const Mat3 axes = JointGizmoAxes(joint, posed.frame, interactive);
  const Vec3 bone = (workspace.spine_points[1].back() - workspace.spine_points[1].front());
  const Vec3 expected = Eigen::AngleAxisd(30.0 * kPi / 180.0, axes.col(0)) *
                        (base_turn * (model.parts[1].spine_points.back() - root));
  EXPECT_LT((bone - expected).norm(), 1e-6);
}

// The scene viewer, driven by a script: select the arm by clicking its spine, then drag the
// hinge's ring an eighth of a turn along it. The joint turns by about +45 degrees, the skin
// follows, and the camera does not orbit. Headless; in a GLFW window with ImGui (drawing the
// gizmo) when WIRERIG_TEST_WINDOW is set (the ctest runs that under xvfb-run).
TEST(SceneViewerGizmo, ScriptedDragOnTheRingTurnsTheJoint) {
  ScopedNoFpTraps no_traps;
  const std::filesystem::path folder = std::filesystem::path(WIRERIG_TEST_OUTPUT_DIR);
  const std::filesystem::path scene_path = folder / "gizmo_jointed.scene.json";
  std::ofstream(scene_path) << JointedScene().dump(2);
  const BuiltScene scene = BuildScene(ParseScene(JointedScene(), folder).value()).value();
  const std::uint32_t arm_spine = SceneFrame(scene).SpineId(1);
  const std::filesystem::path script_path = folder / "gizmo_drag.input";
  std::ofstream(script_path) << "2 move-to-wire " << arm_spine << " 0.6\n"
                             << "3 press left\n"
                             << "4 release left\n"
                             << "6 move-to-gizmo x 0\n"
                             << "7 press left\n"
                             << "8 move-to-gizmo x 0.03\n"
                             << "9 move-to-gizmo x 0.06\n"
                             << "10 move-to-gizmo x 0.09\n"
                             << "11 move-to-gizmo x 0.125\n"
                             << "13 release left\n";

  struct Viewer : SceneViewer {
    using SceneViewer::SceneViewer;
    const Camera& view() const { return camera(); }
  };
  SceneViewerOptions options;
  options.scene = scene_path;
  Viewer viewer(options);
  ApplicationOptions run;
  run.frames = 16;
  run.size = {640, 480};
  run.input_script = script_path;
  run.no_window = std::getenv("WIRERIG_TEST_WINDOW") == nullptr;
  run.screenshot = folder / (run.no_window ? "gizmo_headless.png" : "gizmo_window.png");
  const Camera defaults;  // the orbit the viewer opens with (the scene has no camera hint)
  ::testing::internal::CaptureStdout();
  const Result<bool> ran = viewer.Run(run);
  const std::string printed = ::testing::internal::GetCapturedStdout();
  ASSERT_TRUE(ran.ok()) << ran.error();
  EXPECT_EQ(viewer.selected_part(), 1);
  const Vec3 angles = viewer.playback().InteractiveJointAngles(1);
  EXPECT_NEAR(angles.x(), 45.0, 6.0);
  EXPECT_EQ(angles.y(), 0.0);
  EXPECT_EQ(angles.z(), 0.0);
  EXPECT_EQ(viewer.view().yaw, defaults.yaw);  // the ring drag did not orbit
  EXPECT_EQ(viewer.view().pitch, defaults.pitch);
  // The arm turned in the viewer's last evaluation: its spine's end, about 0.5 m below the
  // hinge, swung along the chord 2 L sin(angle / 2); the summary line reports the drag and the
  // skin's motion (the arm's bottom rim swings about 0.39 m).
  const PartModel& arm = scene.model.parts[1];
  const double length = (arm.spine_points.back() - arm.spine_points.front()).norm();
  const std::vector<Vec3>& spine = viewer.playback().workspace().spine_points[1];
  EXPECT_NEAR((spine.back() - arm.spine_points.back()).norm(),
              2.0 * length * std::sin(0.5 * angles.x() * kPi / 180.0), 1e-3);
  EXPECT_NE(printed.find("picks=1 "), std::string::npos) << printed;
  EXPECT_NE(printed.find("gizmo_drags=1 joint=arm:"), std::string::npos) << printed;
  const std::size_t at = printed.find("max_mesh_motion=");
  ASSERT_NE(at, std::string::npos) << printed;
  EXPECT_GT(std::stod(printed.substr(at + 16)), 0.3) << printed;
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
