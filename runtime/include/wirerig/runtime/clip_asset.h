// A clip sampled for the runtime (.wclip): every part's pose and spine loads and the profile
// loads at a fixed frame rate, as the offline playback produced them (keyed forces, joint
// angles, articulated dynamics and rigid bodies already resolved), so an engine plays a wirerig
// clip with the runtime alone. SampleClipJob turns a time into EvaluateRigJob's inputs.
//
// File layout: as a .wrig (rig_asset.h: magic, version, payload size, CRC-32 of the payload)
// with the magic "WCLP"; the payload is the clip's fields in declaration order, each array
// preceded by its u32 element count (clip_asset.cpp).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "wirerig/runtime/modal_wire.h"
#include "wirerig/runtime/rig_evaluation.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

// 2: parts carry tip couples and large curls. 3: wires' motion beyond their static shape.
// 4: profile wires' motion (the skin's flesh).
inline constexpr std::uint32_t kClipAssetVersion = 4;

enum class ClipLoop : int { kOnce = 0, kLoop = 1, kPingPong = 2 };

// [first, first + count) of one of SampledClip's load arrays.
struct LoadRange {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
};

// One part at one frame: PartPose with its loads as ranges into the clip's arrays.
struct PartKey {
  Quat rotation = Quat::Identity();
  Vec3 translation = Vec3::Zero();
  BoundaryCondition boundary = BoundaryCondition::kCantileverFree;
  Vec3 tip_force = Vec3::Zero();
  Vec3 tip_couple = Vec3::Zero();
  bool large_deflection = false;
  std::uint32_t curl_segments = 0;
  Vec3 start_displacement = Vec3::Zero();
  Vec3 end_displacement = Vec3::Zero();
  double axial_fixed_at = 0.0;
  LoadRange point_loads, line_loads, axial_point_loads, axial_line_loads;
};

// One profile's loads at one frame (ProfileLoads with ranges).
struct ProfileKey {
  std::uint32_t part = 0;
  std::uint32_t profile = 0;
  double from = 0.0;
  double to = 1.0;
  BoundaryCondition boundary = BoundaryCondition::kClamped;
  LoadRange point_loads, line_loads;
};

// A wire whose motion beyond the static shape of its loads the clip records (the offline
// playback's wire dynamics, modal_wire.h): enough to rebuild that motion from ModalResiduals.
struct ClipWire {
  std::uint32_t part = 0;
  BoundaryCondition boundary = BoundaryCondition::kCantileverFree;  // the modes' family
  std::uint32_t modes = 0;                                          // in [1, ModalBasis::kMaxModes]
  std::uint32_t samples = 0;       // the part's spine samples (v_k = k / (samples - 1)), >= 2
  double length = 0.0;             // the spine's L, m
  double bending_stiffness = 0.0;  // its EI, N m^2
};

// A profile wire whose motion the clip records (the offline playback's profile_wires): the whole
// loop of profile `profile` of part `part` as a clamped wire over its points (v_q = q / points
// closed, q / (points - 1) open), its motion eased by EaseLoopMotion(weights, reach).
struct ClipProfileWire {
  std::uint32_t part = 0;
  std::uint32_t profile = 0;
  std::uint32_t modes = 0;  // in [1, ModalBasis::kMaxModes]
  bool closed = true;
  double length = 0.0;             // the loop's perimeter L, m
  double bending_stiffness = 0.0;  // its EI, N m^2
  double reach = 0.0;              // m, the most a point moves
  std::vector<double> weights;     // one per profile point, in [0, 1]
};

struct SampledClip {
  std::string name;
  double duration = 0.0;    // s, > 0
  double frame_rate = 0.0;  // frames per second, > 0; frame k is at k / frame_rate
  ClipLoop loop = ClipLoop::kOnce;
  std::uint32_t part_count = 0;  // the rig's parts
  std::vector<PartKey> parts;    // frame-major: frame k's part p at k * part_count + p
  std::vector<LoadRange> profile_keys_of_frame;  // per frame: its range of profile_keys
  std::vector<ProfileKey> profile_keys;
  std::vector<PointLoad> point_loads;  // what the ranges point into
  std::vector<LineLoad> line_loads;
  std::vector<AxialPointLoad> axial_point_loads;
  std::vector<AxialLineLoad> axial_line_loads;
  // Wires with inertia, and per frame (frame-major) and wire (in `wires` order) its
  // ModalResidual: `modes` coordinates (m), then the uniform and the turning load (N/m).
  std::vector<ClipWire> wires;
  std::vector<Vec3> wire_motion;
  // Profile wires, and per frame and profile wire its ModalResidual: `modes` coordinates (m),
  // then the uniform load (N/m).
  std::vector<ClipProfileWire> profile_wires;
  std::vector<Vec3> profile_wire_motion;

  std::size_t frame_count() const { return profile_keys_of_frame.size(); }
  // Elements of wire_motion per frame: the sum of every wire's modes + 2.
  std::size_t wire_motion_stride() const;
  // Elements of profile_wire_motion per frame: the sum of every profile wire's modes + 1.
  std::size_t profile_wire_motion_stride() const;
};

// Whether a clip is safe to play on a model with `part_count` parts whose profiles `model`
// names (model may be null: profile indices and wires' parts are then not checked): positive
// duration and frame rate, one key per part per frame, ranges inside their arrays, finite unit
// rotations, loads with v in [0, 1], finite numbers; wires on distinct parts (deformable ones
// with as many spine samples, given the model) with one residual per frame; profile wires on
// distinct profiles (with as many points and the same closure, given the model), likewise.
Status ValidateSampledClip(const SampledClip& clip, const RigModel* model = nullptr);

std::vector<std::uint8_t> SerializeClipAsset(const SampledClip& clip);
// Parses and validates (without a model) bytes made by SerializeClipAsset; on failure *out is
// unchanged. Refusals name the field as ParseRigAsset's do.
Status ParseClipAsset(std::span<const std::uint8_t> bytes, SampledClip* out);

// What SampleClipJob writes: the poses and profile loads for EvaluateRigJob, with the loads
// they point into. Made once per clip and thread (MakeClipPlaybackBuffers); reused every frame.
struct ClipPlaybackBuffers {
  std::vector<PartPose> poses;  // one per part
  std::vector<ProfileLoads> profile_loads;
  std::size_t profile_load_count = 0;  // how many of profile_loads this frame uses
  std::vector<PointLoad> point_loads;
  std::vector<LineLoad> line_loads;
  std::vector<AxialPointLoad> axial_point_loads;
  std::vector<AxialLineLoad> axial_line_loads;
  // Per clip wire: its sample parameters and mode tables, and the motion SampleClipJob points
  // the part's SpineLoads::extra_displacement / extra_slope at.
  struct Wire {
    std::vector<double> samples, mode_values, mode_slopes;
    std::vector<Vec3> displacement, slope;
  };
  std::vector<Wire> wires;
  // Per clip profile wire: its tables and the motion its ProfileLoads points at (appended after
  // the clip's own profile loads).
  struct ProfileWire {
    std::vector<double> samples, mode_values;
    std::vector<Vec3> displacement;
  };
  std::vector<ProfileWire> profile_wires;
  std::span<const ProfileLoads> used_profile_loads() const {
    return {profile_loads.data(), profile_load_count};
  }
};
// For a valid clip (ParseClipAsset, ValidateSampledClip); a wire whose modes cannot be built
// gets no tables, and SampleClipJob refuses the buffers.
ClipPlaybackBuffers MakeClipPlaybackBuffers(const SampledClip& clip);

// The clip's inputs at playback time `time` (s; mapped by the loop mode like anim's clips):
// rotations slerped and translations, displacements and tip forces interpolated linearly between
// the two frames around the time; loads interpolated too where both frames have the same loads
// (same counts and boundaries), else taken from the nearer frame; the wires' residuals
// interpolated and evaluated (ModalResidualJob) into the buffers, the profile wires' as well
// (eased by EaseLoopMotion, one whole-loop ProfileLoads each). Allocates nothing.
struct SampleClipJob {
  const SampledClip* clip = nullptr;
  double time = 0.0;
  ClipPlaybackBuffers* buffers = nullptr;  // made for this clip

  Status Validate() const;
  Status Run() const;
};

// The clip-local time of playback time t by the loop mode: once clamps t to [0, duration];
// loop and ping-pong wrap any t, negative too (period duration, 2 duration); 0 for a t that is
// not finite.
double ClipLocalTime(ClipLoop loop, double duration, double t);

}  // namespace wirerig
