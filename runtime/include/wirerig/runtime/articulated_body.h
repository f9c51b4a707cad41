// Articulated rigid-body dynamics of a bone chain: the rigid spine wires of a character (paper
// section 4.2, PHYSICS.md section 7) joined into a tree by joints and moved together by
// Featherstone's articulated-body algorithm (ABA) in spatial-vector form, O(bodies) per
// evaluation. docs/articulated-dynamics.md states the model, the integrators, the limits and the
// tests' references.
//
// Frames. Every body has a body frame whose origin is its joint (the point it turns about) and
// whose axes are the joint's rest axes turned by the joint: body -> parent is
//   x_parent = joint_position + joint_rotation * (translation + rotation * x_body),
// with `translation` used by floating joints only and `rotation` the joint's rotation (hinge:
// about the joint's X axis, as JointModel's hinge). A root's parent is the world.
// Quaternions are Eigen's (constructed (w, x, y, z)), unit, rotating child axes into parent axes.
//
// Angles. Joint angles are radians, except the limits, which are degrees as in JointModel and
// refer to the same X-then-Y-then-Z intrinsic Euler angles (rotation = Rx(x) Ry(y) Rz(z)).
//
// Workflow: describe the bodies (ArticulatedBodyDesc), Build an ArticulatedModel once, make its
// ArticulatedState and ArticulatedWorkspace once, then per frame set the targets and forces and
// Run an ArticulatedStepJob (allocation-free, deterministic: the same inputs give bit-identical
// outputs). A model may be shared by several threads, each with its own state and workspace.
#pragma once

#include <span>
#include <vector>

#include "wirerig/runtime/conventions.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

enum class ArticulatedJointType : int {
  kFixed = 0,     // welded to the parent: no degree of freedom
  kHinge = 1,     // 1 DOF: an angle about the joint's X axis
  kBall = 2,      // 3 DOF: a unit quaternion; angular velocity in the body (joint) frame
  kFloating = 3,  // 6 DOF, roots only: a ball joint plus a translation
};

// One body and the joint that joins it to its parent: the raw description Build checks.
struct ArticulatedBodyDesc {
  int parent = -1;  // an earlier body (parents come first), or -1: the world
  ArticulatedJointType joint = ArticulatedJointType::kBall;
  // The joint's rest frame in the parent's body frame (in the world for a root).
  Vec3 joint_position = Vec3::Zero();      // m
  Quat joint_rotation = Quat::Identity();  // unit: rest joint axes -> parent axes
  // Mass properties in the body frame.
  double mass = 1.0;                   // kg, > 0
  Vec3 center_of_mass = Vec3::Zero();  // m, from the joint
  // About the centre of mass, body axes, kg m^2: symmetric, positive definite and physical
  // (each principal moment at most the sum of the other two).
  Mat3 inertia = Mat3::Identity();
  // Passive viscous damping of the joint's motion, N m s/rad, >= 0 (hinge and ball joints).
  double damping = 0.0;
  // Limits, degrees, on the hinge angle (X) or the ball joint's X, Y, Z Euler angles (JointModel's
  // convention: X and Z in (-180, 180], Y in [-90, 90]; put the bone along the joint's Z axis so
  // X and Y are its bends and Z its twist). A bound at or beyond +-180 is no bound; keep Y
  // bounds well inside +-90 (the chart's gimbal lock, where X and Z are ill-defined).
  // A limit is a stiff one-sided spring-damper (it pushes, never pulls) whose stiffness and
  // damping are scaled by the inertia d the limited angle sees (its subtree's, parent held, the
  // joint's other angles free): stiffness (2 pi f)^2 d and damping 2 zeta (2 pi f) d, so the
  // limit rings at f with damping ratio zeta whatever the limb, a finger and a torso alike.
  Vec3 min_degrees = Vec3::Constant(-180.0);
  Vec3 max_degrees = Vec3::Constant(180.0);
  double limit_frequency = 30.0;     // f, Hz, > 0
  double limit_damping_ratio = 1.0;  // zeta, >= 0 (1: critically damped, no bounce)
};

// The immutable model: the descriptions plus what the solver precomputes from them.
class ArticulatedModel {
 public:
  // Refuses (leaving *out untouched), naming the field with index = the body:
  //   "out"                 null;
  //   "bodies"              empty (index -1);
  //   "parent"              not -1 and not an earlier body;
  //   "joint"               unknown, or kFloating on a body with a parent;
  //   "joint_position"      not finite; "joint_rotation" not finite or |q|^2 not within 1e-6 of 1;
  //   "mass"                not positive and finite; "center_of_mass" not finite;
  //   "inertia"             not finite, not symmetric (to 1e-9 relative), not positive definite
  //                         or not physical (a principal moment exceeds the sum of the others by
  //                         more than 1e-9 relative);
  //   "damping"             negative or not finite;
  //   "limits"              not finite or min > max (member "x", "y" or "z");
  //   "limit_frequency"     not positive and finite; "limit_damping_ratio" negative or infinite.
  static Status Build(std::span<const ArticulatedBodyDesc> bodies, ArticulatedModel* out);

  int body_count() const { return static_cast<int>(bodies_.size()); }
  int dof_count() const { return dof_count_; }  // velocity degrees of freedom, all joints
  double total_mass() const { return total_mass_; }
  const ArticulatedBodyDesc& body(int i) const { return bodies_[i]; }
  // Degrees of freedom of body i's joint (0, 1, 3 or 6) and its tree's root.
  int dofs(int i) const { return dofs_[i]; }
  int root(int i) const { return roots_[i]; }
  // Spatial inertia of body i about its joint, body axes: [[Ic - m cx cx, m cx], [-m cx, m 1]],
  // cx the cross-product matrix of the centre of mass (angular rows and columns first).
  const Mat6& spatial_inertia(int i) const { return spatial_inertia_[i]; }
  // The rotation matrix of body i's joint_rotation (rest joint axes -> parent axes).
  const Mat3& joint_axes(int i) const { return joint_axes_[i]; }
  // Body i's limits in radians; a bound outside (-pi, pi) is no bound (+-infinity here).
  const Vec3& lower_limit(int i) const { return lower_limit_[i]; }
  const Vec3& upper_limit(int i) const { return upper_limit_[i]; }
  // Whether body i's joint has any bound.
  bool limited(int i) const { return limited_[i]; }

 private:
  std::vector<ArticulatedBodyDesc> bodies_;
  std::vector<int> dofs_;
  std::vector<int> roots_;
  std::vector<Mat6> spatial_inertia_;
  std::vector<Mat3> joint_axes_;
  std::vector<Vec3> lower_limit_, upper_limit_;
  std::vector<bool> limited_;
  int dof_count_ = 0;
  double total_mass_ = 0.0;
};

// The coordinates and velocities of one joint. Which members a joint reads depends on its type:
//   fixed     none (Run writes rotation = identity and zero velocities);
//   hinge     angle and angular_velocity.x() (the angle's rate); Run writes rotation = Rx(angle)
//             and angular_velocity = (rate, 0, 0);
//   ball      rotation and angular_velocity;
//   floating  rotation, angular_velocity, translation and linear_velocity.
struct JointState {
  Quat rotation = Quat::Identity();  // unit: body axes -> rest joint axes
  double angle = 0.0;                // hinge, rad; not wrapped (limits see the true angle)
  // Of the body relative to its parent, in the body's own axes, rad/s.
  Vec3 angular_velocity = Vec3::Zero();
  // Floating: the body origin in the joint's rest frame (the world for a root at rest at the
  // origin), m, and its rate of change, m/s, in the same axes.
  Vec3 translation = Vec3::Zero();
  Vec3 linear_velocity = Vec3::Zero();
};

// Where a body is and how it moves, world axes: x_world = translation + rotation * x_body.
struct BodyMotion {
  Quat rotation = Quat::Identity();      // body axes -> world axes, unit
  Vec3 translation = Vec3::Zero();       // the body origin (its joint), m
  Vec3 angular_velocity = Vec3::Zero();  // rad/s, world axes
  Vec3 linear_velocity = Vec3::Zero();   // of the body origin, m/s, world axes
};

struct ArticulatedState {
  std::vector<JointState> joints;  // one per body: the state proper (read and written by Run)
  // One per body: the world motion of each body, consistent with `joints` after Run or
  // EvaluateArticulatedBodies (written only; never read by Run).
  std::vector<BodyMotion> bodies;
  double time = 0.0;  // s
};

// A state at rest: identity rotations, zero angles and velocities, bodies evaluated.
ArticulatedState MakeArticulatedState(const ArticulatedModel& model);

// Recomputes state->bodies from state->joints (forward kinematics and velocities); call it after
// writing joints by hand. Refuses like ArticulatedStepJob::Validate's "state".
Status EvaluateArticulatedBodies(const ArticulatedModel& model, ArticulatedState* state);

// Totals of a state, from state.bodies (keep them evaluated), for checks and diagnostics.
struct ArticulatedMeasures {
  double mass = 0.0;                     // kg
  Vec3 center_of_mass = Vec3::Zero();    // m, world
  Vec3 linear_momentum = Vec3::Zero();   // kg m/s, world
  Vec3 angular_momentum = Vec3::Zero();  // about the world origin, kg m^2/s, world axes
  double kinetic_energy = 0.0;           // J
  double potential_energy = 0.0;         // J, of gravity: -sum m g . x_com (0 at the origin)
};
// Refuses "state" when its bodies do not match the model, "gravity" when not finite.
Status MeasureArticulated(const ArticulatedModel& model, const ArticulatedState& state,
                          const Vec3& gravity, ArticulatedMeasures* out);

// The joint's angles in degrees, in JointModel's X-Y-Z intrinsic convention (hinge: (angle, 0,
// 0); ball and floating: the Euler angles of `rotation`, Y in [-90, 90]; fixed: 0).
Vec3 JointAnglesDegrees(ArticulatedJointType type, const JointState& joint);
// Sets the joint's coordinates from such angles (hinge: angle = x; ball and floating: rotation
// = Rx Ry Rz; fixed: nothing). Velocities are left alone.
void SetJointAnglesDegrees(ArticulatedJointType type, const Vec3& degrees, JointState* joint);

// Scratch sized for one model (made by MakeArticulatedWorkspace); internal to the solver.
struct ArticulatedWorkspace {
  struct Coordinates {  // a joint's position coordinates, or their time derivative
    Eigen::Vector4d quaternion = Eigen::Vector4d(0.0, 0.0, 0.0, 1.0);  // (x, y, z, w)
    Vec3 translation = Vec3::Zero();
    double angle = 0.0;
  };
  struct Body {
    Mat3 rotation = Mat3::Identity();        // body axes -> parent axes
    Vec3 position = Vec3::Zero();            // body origin in the parent's frame
    Mat3 world_rotation = Mat3::Identity();  // body axes -> world axes
    Vec3 world_position = Vec3::Zero();
    Vec6 velocity = Vec6::Zero();           // spatial, body coordinates (angular first)
    Vec6 bias_acceleration = Vec6::Zero();  // c = v x S qdot
    Mat6 inertia = Mat6::Zero();            // articulated inertia I^A
    Mat6 reduced_inertia = Mat6::Zero();    // I^a = I^A - U D^-1 U^T, handed to the parent
    Vec6 joint_force = Vec6::Zero();        // tau, head(dofs)
    Vec6 bias_force = Vec6::Zero();         // articulated bias force p^A
    Mat6 inverse_d = Mat6::Zero();          // (S^T I^A S + implicit terms)^-1, dofs x dofs
    Vec6 u = Vec6::Zero();                  // tau - S^T p^A
    Vec6 acceleration = Vec6::Zero();       // spatial, body coordinates, gravity offset
    Vec6 external = Vec6::Zero();           // external wrench about the world origin, world
  };
  struct Tree {  // per floating root: momentum bookkeeping (angular first, then linear)
    Vec6 momentum = Vec6::Zero();      // at the start: (about the centre of mass, linear)
    Vec3 start_center = Vec3::Zero();  // the centre of mass at the start
    Vec6 impulse = Vec6::Zero();       // the external wrench about the centre of mass times dt
    Vec6 wrenches = Vec6::Zero();      // sum of the external wrenches on the tree, about the origin
    // Sums over the tree at a stage or at the end: momentum about the origin, mass, first
    // moment of mass; at the end also the inertia about the centre of mass (world axes).
    Vec6 origin_momentum = Vec6::Zero();
    double mass = 0.0;
    Vec3 first_moment = Vec3::Zero();
    Mat3 inertia = Mat3::Zero();
  };
  std::vector<Body> bodies;
  std::vector<Tree> trees;  // indexed by body (root slots used)
  // RK4 only: set when a joint's explicit damping or stiffness is too stiff for the step.
  bool too_stiff = false;
  std::vector<Coordinates> q0, q, dq[4];  // start, stage, stage derivatives (RK4)
  std::vector<Vec6> v0, v, dv[4];         // generalised velocities, head(dofs) used
};
ArticulatedWorkspace MakeArticulatedWorkspace(const ArticulatedModel& model);

enum class ArticulatedIntegrator : int {
  // Velocities first, then positions from the new velocities (quaternions by the exponential
  // map, the floating base by SE(3)'s); joint damping, PD tracking and active limits implicit in
  // the joint's own coordinates, so stiff gains stay stable; the velocity-product (gyroscopic,
  // Coriolis) terms at the step's midpoint velocity after `corrections` fixed-point passes
  // (explicit, they pump energy into slender spinning limbs). 1 + corrections ABA per step;
  // first order.
  kSemiImplicitEuler = 0,
  // Classic RK4 on (coordinates, velocities), quaternions normalised after the step; every force
  // explicit (stable while dt times each spring-damper's fastest rate stays below about 2.8).
  // Four ABA per step; fourth order on smooth motion; for references and soft gains.
  kRk4 = 1,
};

// An external force, world axes, acting at a world point, plus a pure torque; both held fixed in
// the world over the step (sample them per step).
struct ExternalWrench {
  int body = 0;
  Vec3 force = Vec3::Zero();   // N
  Vec3 point = Vec3::Zero();   // m, where the force acts
  Vec3 torque = Vec3::Zero();  // N m
};

// PD tracking of a target pose by one joint: tau = stiffness * error - damping * velocity, the
// error being the hinge's (target angle - angle), or for a ball joint the rotation vector of
// target * rotation^-1 (rest joint axes) expressed in the body axes, i.e. log(rotation^-1 target).
// Ignored by fixed and floating joints.
struct JointTarget {
  Quat rotation = Quat::Identity();  // ball: unit
  double angle = 0.0;                // hinge, rad
  double stiffness = 0.0;            // kp, N m/rad, >= 0
  double damping = 0.0;              // kd, N m s/rad, >= 0
};

// One fixed step of length dt: state->joints and time advance, state->bodies are re-evaluated.
// With conserve_momentum, each tree with a floating root is corrected after the step by a rigid
// motion of the whole tree (a twist added to its root's velocity, a translation to its root's
// position): its linear momentum becomes p0 + dt F (F the external force, gravity included,
// constant over the step), its angular momentum about its centre of mass L0 + the external
// moment about the moving centre of mass integrated over the step (RK4: Simpson's weights over
// the stages; gravity has none), and its centre of mass x0 + dt (p0 + p1) / 2M, the exact
// ballistic motion. Linear momentum is then conserved to round-off under no external force,
// angular momentum likewise when torque-free, and the centre of mass flies exactly. Internal
// forces (joints, damping, PD, limits) never change these.
// Validate() refuses, naming the field: "model", "workspace", "state" null or sized for another
// model; "integrator" unknown; "dt" not positive and finite, or (RK4) too long for an active
// limit (2 pi f dt > 2.5); "corrections" outside [0, 4]; "gravity" not finite; "wrenches" (index =
// the wrench) member "body" out of range or "force", "point", "torque" not finite; "targets"
// neither empty nor one per body, or (index = the body) member "rotation" not unit, "angle" not
// finite, "stiffness" or "damping" negative or not finite; "state" (index = the body) member
// "rotation" (ball, floating) not unit within 1e-6, or "angle", "angular_velocity", "translation",
// "linear_velocity" not finite or beyond 1e150, or member "time" not finite.
// Run() also refuses "dt", leaving *state untouched: under RK4 when a joint's damping C or
// stiffness K (passive damping, PD gains, an active limit; joint-space matrices) is too stiff
// for the step at its start: dt |lambda| > 2.5 with lambda the faster root of
// l^2 + c l + k = 0, c and k the largest eigenvalues of D^-1 C and D^-1 K, D the joint's
// articulated inertia (parent held: a light parent, such as a clavicle under an arm, makes the
// true mode faster than this check sees); and with reason "diverged" when the step produced a
// non-finite or enormous value (a step far too long for the motion). The semi-implicit step is
// the one to use with stiff gains and limits.
struct ArticulatedStepJob {
  const ArticulatedModel* model = nullptr;
  ArticulatedIntegrator integrator = ArticulatedIntegrator::kSemiImplicitEuler;
  double dt = 0.0;                           // s
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);      // m/s^2, world
  std::span<const ExternalWrench> wrenches;  // any number
  std::span<const JointTarget> targets;      // empty (no tracking) or one per body
  bool conserve_momentum = true;
  // Semi-implicit Euler: passes re-evaluating the velocity-product terms at the midpoint
  // velocity, in [0, 4]. 0 is the plain explicit form; 1 (the default) removes its energy pumping
  // (docs/articulated-dynamics.md); more change little.
  int corrections = 1;
  ArticulatedWorkspace* workspace = nullptr;
  ArticulatedState* state = nullptr;  // in/out

  Status Validate() const;
  Status Run() const;  // validates, then steps; never allocates
};

}  // namespace wirerig
