// Joint rotation gizmo: the rings a user drags in the 3D view to turn a part's joint, as pure
// geometry (no GL, no ImGui), so it can be tested; the viewer draws and drives it.
//
// One ring per angle the joint's type allows (ball: X, Y and Z; hinge: X; fixed: none), centred
// on the joint and drawn at a constant size on screen. The rings are the joint's gimbal: its
// angles apply X, then Y, then Z (joint.h), so ring X turns about the joint's X axis as its
// parent holds it, ring Y about Y after the X turn, ring Z about the child's bone after the X
// and Y turns. Turning the part about ring k's axis by an angle therefore changes exactly angle
// k by that angle, and the other two rings stay where they are while ring k is dragged.
//
// A drag on a ring is the signed angle the mouse sweeps around the ring's projected centre
// (right-hand rule about the ring's axis: a positive turn about an axis pointing at the eye is
// anticlockwise on screen). A ring seen nearly edge-on projects to a line through its centre,
// where that angle means little: there the drag follows the ring's screen tangent at the
// grabbed point (one ring radius of travel along it is one radian).
#pragma once

#include <vector>

#include "wirerig/runtime/joint.h"
#include "wirerig/runtime/rig_evaluation.h"
#include "wirerig/runtime/rig_model.h"
#include "wirerig/viewer/camera.h"

namespace wirerig {

// Where a part's joint is after an evaluation and how its axes stand there with the part's own
// interactive angles at zero.
struct PosedJoint {
  Vec3 center = Vec3::Zero();     // the joint's pivot (the part's root point), world, m
  Mat3 frame = Mat3::Identity();  // columns X, Y, Z: the joint's axes, world
};

// After `workspace` was evaluated with `pose` for part `part` (EvaluateRigJob, or a Playback's
// workspace() and sample().poses): the part turns about its rest root point by pose.rotation,
// moves by pose.translation, then follows its parent's deformed frame at its attachment
// (rig_evaluation.h). `interactive_degrees` are the angles whose JointRotation the pose's
// rotation ends with (Playback::InteractiveJointAngles; zero for none): they are taken out, so
// `frame` is the parent's turn times the rest of the pose's rotation times joint.axes.
PosedJoint PoseJoint(const RigModel& model, const RigWorkspace& workspace, std::size_t part,
                     const PartPose& pose, const Vec3& interactive_degrees);

// The world axes the rings turn about, as columns X, Y, Z, for the joint posed at `frame`
// (PosedJoint::frame) and turned by `degrees` (clamped to the joint's type and limits first):
// X = frame e_x, Y = frame Rx(a) e_y, Z = frame Rx(a) Ry(b) e_z.
Mat3 JointGizmoAxes(const JointModel& joint, const Mat3& frame, const Vec3& degrees);

struct JointGizmoOptions {
  float radius_pixels = 90.0f;  // ring radius on screen (at the joint's depth)
  int segments = 96;            // polyline points per ring
  float pick_pixels = 7.0f;     // how near the mouse must be to a ring to grab it
  // Below this |cos| between a ring's axis and the line of sight the ring counts as edge-on and
  // drags along its tangent.
  float edge_on_cosine = 0.2f;
};

struct JointGizmoRing {
  int axis = 0;                     // 0: X (red), 1: Y (green), 2: Z (blue)
  Vec3 world_axis = Vec3::UnitX();  // unit
  // Closed polyline (first point not repeated), in pixels, in the order a positive turn about
  // world_axis moves a point of the ring. Point 0 is the ring's point nearest the eye (when the
  // ring is seen face-on: its top on screen).
  std::vector<Vec2f> pixels;
  // Per point: (point - centre) . (unit vector to the eye) / radius, in [-1, 1]; > 0 on the
  // half of the ring facing the eye.
  std::vector<float> toward_eye;
  double facing = 0.0;  // world_axis . (unit vector from the joint to the eye)
};

struct JointGizmo {
  bool visible = false;  // a joint that turns, in front of the eye
  Vec3 center = Vec3::Zero();
  Vec2f center_pixel = Vec2f::Zero();
  double radius = 0.0;  // m, in the world
  float radius_pixels = 0.0f;
  JointGizmoOptions options;
  std::vector<JointGizmoRing> rings;  // in axis order; none for a fixed joint
};

// The rings for a joint at `center` whose ring axes are the columns of `axes` (JointGizmoAxes),
// seen by `camera` in an image of `size`. Not visible (no rings) for a fixed joint, or when the
// joint or a ring point is behind the eye.
JointGizmo BuildJointGizmo(const Camera& camera, Size size, const Vec3& center, const Mat3& axes,
                           JointType type, const JointGizmoOptions& options = {});

// The ring (index into gizmo.rings) nearest `pixel` within options.pick_pixels, or -1. Points on
// a ring's back half count 2 pixels farther, so the front ring wins where two rings cross.
int HitTestJointGizmo(const JointGizmo& gizmo, const Vec2f& pixel);

// The signed angle, degrees in (-180, 180], that the mouse sweeps around the ring's projected
// centre going from `from` to `to`, by the right-hand rule about the ring's axis as seen from
// the eye. Zero when either is on the centre.
double SweptRingDegrees(const JointGizmo& gizmo, int ring, const Vec2f& from, const Vec2f& to);

// A drag in progress on a ring.
struct JointGizmoDrag {
  int ring = -1;  // index into JointGizmo::rings; -1: no drag
  int axis = 0;   // the joint angle it changes
  Vec3 start_degrees = Vec3::Zero();
  double swept_degrees = 0.0;  // accumulated over the drag, not clamped
  Vec2f last_pixel = Vec2f::Zero();
  bool along_tangent = false;      // the ring was edge-on when grabbed
  Vec2f tangent = Vec2f::UnitX();  // unit: where a positive turn moves the grabbed point
};

// Starts dragging ring `ring` of `gizmo` (e.g. HitTestJointGizmo's answer) from `pixel`, the
// joint standing at `degrees`.
JointGizmoDrag BeginJointGizmoDrag(const JointGizmo& gizmo, int ring, const Vec2f& pixel,
                                   const Vec3& degrees);

// Moves the drag to `pixel` (with the gizmo as it was when the drag began): adds the angle swept
// since the last call and returns the joint's angles: the start angles plus the swept angle on
// the ring's axis, clamped to the joint's type and limits (ClampJointAngles).
Vec3 UpdateJointGizmoDrag(const JointGizmo& gizmo, const JointModel& joint, const Vec2f& pixel,
                          JointGizmoDrag* drag);

// The joint's angles `degrees` turned by `delta` degrees about axis `axis` (0, 1, 2), clamped to
// the joint's type and limits.
Vec3 TurnJointAngles(const JointModel& joint, const Vec3& degrees, int axis, double delta);

}  // namespace wirerig
