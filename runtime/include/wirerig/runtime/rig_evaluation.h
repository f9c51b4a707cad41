// Per-frame evaluation of a RigModel: part poses and spine loads in, deformed mesh positions
// and normals out, into buffers the caller owns. No allocation per frame: the workspace is made
// once per model and reused; a const model may be evaluated from several threads, each with its
// own workspace.
//
// Order: parts from the root down. A part's rest geometry first bends and stretches under its
// spine loads (deformable parts; displacements in the spine's local frames: bending components
// along the rest normal and binormal, axial along the tangent), then moves rigidly by its pose
// (rotation about its spine's root point, then translation), then follows its parent: the
// parent's deformed frame at the attachment replaces its rest frame there. A child never moves
// its parent. Profiles ride on their spine frames; vertices follow the profiles; vertices near a
// joint then follow its skin bridge by their weight (joint_bridge.h).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "wirerig/runtime/axial_job.h"
#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/joint_bridge.h"
#include "wirerig/runtime/parallel.h"
#include "wirerig/runtime/rig_model.h"
#include "wirerig/runtime/vertex_stage.h"

namespace wirerig {

// Loads on one part's spine. Bending forces are in the spine's local axes: x along the rest
// normal, y along the rest binormal (z, along the tangent, is ignored: axial loads carry it).
struct SpineLoads {
  BoundaryCondition boundary = BoundaryCondition::kCantileverFree;
  std::span<const PointLoad> bending_point_loads;
  std::span<const LineLoad> bending_line_loads;
  Vec3 tip_force = Vec3::Zero();  // local axes, cantilevers only
  // A couple at the free tip, N m, as the local direction the tip turns towards times its
  // magnitude (BendingJob::tip_couple); free cantilevers only.
  Vec3 tip_couple = Vec3::Zero();
  // Prescribed end displacements X0 (v = 0) and X1 (v = 1), m, local axes like the forces;
  // X1 is ignored by cantilevers (their free end is an output).
  Vec3 start_displacement = Vec3::Zero();
  Vec3 end_displacement = Vec3::Zero();
  double axial_fixed_at = 0.0;
  std::span<const AxialPointLoad> axial_point_loads;
  std::span<const AxialLineLoad> axial_line_loads;
  // Added to the closed-form bending at the spine's samples (v_k = k / (n - 1), local axes),
  // each empty or of the part's spine sample count: a wire's motion beyond its static shape
  // (modal dynamics, modal_wire.h), displacement in m and slope dX/ds dimensionless.
  std::span<const Vec3> extra_displacement;
  std::span<const Vec3> extra_slope;
  // Large curls (cantilevers only): the bending in the plane of the spine's largest
  // small-deflection displacement is solved as a co-rotational chain (corotational_wire.h,
  // inextensible, dead loads; the bending loads' tangential components act too, along the rest
  // tangent), so the spine may curl past half a turn; loads across that plane
  // and extra_slope add small turns to the chain's tangents (extra_displacement only chooses
  // the plane). At most 16 point and 8 line loads. The chain is solved from the straight wire
  // every frame (deterministic; a cold solve is 15-80 chain sweeps of K segments (~0.5 us
  // per segment): the octopus's 301 frames with 8 curled arms bake in 1.3 s).
  bool large_deflection = false;
  int curl_segments = 0;  // the chain's K (CorotationalWireJob::segments); 0: automatic
};

// Loads bending one profile wire (paper Fig. 8: the whole or a stretch of all or some profile
// wires). The stretch [from, to] of the profile's parameter (0 at its first point, 1 at its
// last, or back at the first for a closed loop) deforms as a wire held by `boundary` at the
// stretch's ends; point and line loads are placed along the stretch (v in [0, 1]) with forces in
// the profile's spine frame: x along the normal, y along the binormal, z along the tangent.
struct ProfileLoads {
  std::uint32_t part = 0;
  std::uint32_t profile = 0;
  double from = 0.0;
  double to = 1.0;
  BoundaryCondition boundary = BoundaryCondition::kClamped;
  std::span<const PointLoad> point_loads;
  std::span<const LineLoad> line_loads;
  // Added to the closed-form bending (m, the same frame axes): a profile wire's motion beyond
  // its static shape (modal dynamics). Empty, or with from = 0 and to = 1 one per profile point
  // (point q at v = q / m for a closed profile of m points, q / (m - 1) for an open one).
  std::span<const Vec3> extra_displacement;
};

// Translations are within kMaxTranslation (m) per component. The float evaluation works in
// world space: its precision falls with the distance from the origin (about 0.03 mm at 100 m,
// 0.2 mm at 1 km, with normals several degrees off there): keep a character near the origin
// and place it with the engine's model matrix.
inline constexpr double kMaxTranslation = 1e6;
struct PartPose {
  Quat rotation = Quat::Identity();  // about the spine's root point (rest), world axes
  Vec3 translation = Vec3::Zero();   // m, world axes
  SpineLoads loads;                  // used by deformable parts
};

// The rest ends of a part's joint bridge: from blend_length before its root point along the
// joint's parent axis to its spine's point blend_length along it (joint_bridge.h).
BridgeEnds RestBridgeEnds(const PartModel& child);

// The rigid pose that moves a body from its rest mass properties to `state` (for rigid parts
// driven by RigidBodyStepJob): rotation = q q0^-1, translation so the centre lands on x_c.
PartPose PoseFromRigidBody(const PartModel& part, const RigidBodyState& state);
// The rest state of a part's rigid body (centre of mass, principal orientation, at rest).
RigidBodyState RestRigidBodyState(const PartModel& part);

// What a frame's evaluation found about one part, so the modeller can act (paper section 7).
struct PartWarnings {
  double max_slope = 0.0;             // rad, of the spine's bending (deformable parts)
  double max_deflection_ratio = 0.0;  // largest bending deflection / spine length
  // Beyond the range where linear beam theory holds: slope above 0.3 rad or deflection above
  // 10% of the length.
  bool beyond_small_deflection = false;
  // Spine samples whose radius of curvature is below the distance from the spine to the
  // surface (the skin folds into itself there).
  std::size_t tight_bends = 0;
  std::size_t crossing_profiles = 0;  // adjacent profile pairs whose wires cross
  bool any() const { return beyond_small_deflection || tight_bends > 0 || crossing_profiles > 0; }
};

// What the evaluation lays out once per model (made by MakeRigWorkspace; internal to the
// evaluation). Profiles are numbered globally, part by part ("global profile"
// g = profile_base[part] + profile).
struct RigEvaluationLayout {
  std::vector<std::uint32_t> profile_base;  // per part: its first global profile
  std::vector<std::uint32_t> point_base;    // per global profile: its first wire point
  // A vertex on a joint's skin bridge: its own part's spine sample (to undo the own part's
  // motion into rest space) and where it lies on the bridge. A vertex's entries are adjacent and
  // share its own part's spine sample.
  enum class JointBase : std::uint8_t { kParent, kOwn, kChild };
  struct JointVertex {
    std::uint32_t vertex = 0;
    std::uint32_t joint = 0;  // the joint's child part
    std::uint32_t part = 0;   // the vertex's own part
    std::uint32_t sample = 0;
    double u = 0.0, weight = 0.0, bridge = 0.0, section = 1.0;
    // What the bridge's correction is measured from (rig_model.h, JointInfluence): the vertex's
    // own position when it belongs to the joint's child, the child's rigid motion of its rest
    // point when it belongs to a part below the child (an arm's skin on a chest's joint), the
    // parent's otherwise.
    JointBase base = JointBase::kParent;
  };
  std::vector<JointVertex> joint_vertices;   // in vertex order
  std::vector<std::uint32_t> bridged_parts;  // parts whose joint has a skin bridge
  // The (part, spine sample) pairs the entries undo through, sorted.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> undo_samples;
};

// What the evaluation lays out once per model, shared by every workspace (every thread) of it:
// joint entries, rest bridges, the vertex stage's plans. Immutable once made.
struct RigEvaluationPlan {
  std::size_t parts = 0, vertices = 0, triangles = 0;  // of the model it was made for
  RigEvaluationLayout layout;
  std::vector<RestBridge> rest_bridges;  // per part: its joint's skin bridge at rest
  VertexStagePlan<double> stage64;
  VertexStagePlan<float> stage32;
};
std::shared_ptr<const RigEvaluationPlan> MakeRigEvaluationPlan(const RigModel& model);

// Scratch buffers sized for one model; make once per thread, reuse every frame.
struct RigWorkspace {
  std::shared_ptr<const RigEvaluationPlan> plan;               // shared, constant
  std::vector<std::vector<Vec3>> spine_points;                 // per part, deformed, world
  std::vector<std::vector<Frame>> spine_frames;                // per part, deformed, world
  std::vector<std::vector<std::vector<Vec3>>> profile_points;  // per part, per profile, world
  std::vector<std::vector<Vec3>> profile_origins;  // per part, per profile: spine point, world
  std::vector<std::vector<Vec3>> profile_normals;  // per part, per profile: its plane's normal
  std::vector<double> samples;                     // v of the longest spine's samples
  std::vector<Vec3> slope;                         // scratch for the bending job's slope
  std::vector<Vec3> bending;                       // scratch for the bending job
  std::vector<double> axial;                       // scratch for the axial job
  std::vector<Vec3> curl_points, curl_tangents;    // scratch for large curls
  std::vector<Mat3> spine_turns;                   // per spine sample: its frame's local turn
  std::vector<std::vector<double>> strain;         // per part, per spine sample: N / EA
  std::vector<std::vector<double>> profile_scale;  // per part, per profile: in-plane scale
  std::vector<double> profile_samples;             // per point of the longest profile
  std::vector<Vec3> profile_displacement;          // likewise
  std::vector<Mat3> cap_axes;  // by global profile: its cap frame's axes, scaled like the profile
  std::vector<BridgeSamples> bridges;  // per part: its joint's skin bridge this frame
  // Per part, per spine sample: rest axes times the transposed deformed axes (world -> rest).
  std::vector<std::vector<Mat3>> spine_undo;
  // The vertex, bridge and normal passes, in double (positions) and float (float_positions).
  VertexStage<double> stage64;
  VertexStage<float> stage32;
};
// A workspace with a plan of its own.
RigWorkspace MakeRigWorkspace(const RigModel& model);
// A workspace sharing `plan` (made for this model): what each further thread needs, made
// without redoing the plan's work.
RigWorkspace MakeRigWorkspace(const RigModel& model, std::shared_ptr<const RigEvaluationPlan> plan);

// How EvaluateRigJob makes vertex normals.
enum class NormalMode {
  // Area-weighted normals of the deformed triangles (exact for the deformed mesh).
  kFromTriangles,
  // Each vertex's rest normal turned with its own frame (the pair frame of its two profile
  // wires; a cap vertex's cap frame, by its inverse transpose), then normalised; vertices on
  // joint bridges still from their triangles (the same bits as kFromTriangles there). Exact
  // under rigid motion. On the human (docs/benchmarks.md): within 0.3 degrees of the triangles'
  // for 99% of the vertices off the bridges in single-joint bends, but up to tens of degrees on
  // fingers and toes bound far from their wires when the flesh stretches. Pays only where few
  // vertices lie on bridges: two thirds of the human's do, and there it is no faster.
  kRotated,
};

struct EvaluateRigJob {
  const RigModel* model = nullptr;
  std::span<const PartPose> poses;              // one per part
  std::span<const ProfileLoads> profile_loads;  // any number
  RigWorkspace* workspace = nullptr;
  // The output, one of two kinds. Doubles: positions of the #W welded vertices (m) and their
  // unit, area-weighted normals (may be empty).
  std::span<Vec3> positions;
  std::span<Vec3> normals;
  // Or floats, for engine buffers (the evaluation then runs in float, four vertices at a time):
  // vertex v's position at float_positions[v * float_position_stride .. + 3), its normal likewise
  // (may be empty). Strides in floats, at least 3 (e.g. 6 for interleaved position and normal).
  std::span<float> float_positions;
  std::size_t float_position_stride = 3;
  std::span<float> float_normals;
  std::size_t float_normal_stride = 3;
  // Optional: the float buffers in another vertex order, e.g. the source asset's unwelded one
  // (Mesh::weld_map): output vertex i is welded vertex float_vertex_order[i]. Empty: welded order.
  std::span<const std::uint32_t> float_vertex_order;
  // Keep the volume between adjacent profiles when spines stretch or compress (paper section 7):
  // each profile scales in its plane by 1 / sqrt(1 + strain), strain = N / EA of the closed
  // form at the profile.
  bool preserve_volume = false;
  // Optional, one per part: filled with what this frame's deformation warns about.
  std::span<PartWarnings> warnings;
  // Optional: runs the vertex and normal passes as parallel tasks (e.g. a ThreadPool made once,
  // outside the frame loop). Null (the default): everything on the calling thread. The results
  // are bit-identical either way; Run() allocates nothing if `parallel` does not.
  const ParallelFor* parallel = nullptr;
  // The float evaluation runs eight vertices at a time where the CPU has AVX2 (checked once at
  // run time), else four (SSE2, x86-64's baseline); the results are bit-identical. False keeps
  // it on the baseline (for comparisons).
  bool allow_avx2 = true;
  // How the normals are made (when asked for); the positions are the same bits either way.
  NormalMode normal_mode = NormalMode::kFromTriangles;

  Status Validate() const;
  Status Run() const;  // validates, then evaluates; never allocates
};

}  // namespace wirerig
