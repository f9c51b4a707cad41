// Clips: the tracks that drive one rig over a stretch of time. Raw description (names, as a
// scene file holds them) -> BuildClip against a RigModel (names resolved to part and profile
// indices, every track built) -> an immutable Clip that ClipSampler samples at any time.
//
// What a clip can drive, per part (every track optional; an absent track is its default):
//   spine bending: boundary-condition family (step keys), point loads (position v along the
//     spine, magnitude, direction in the spine's local axes: x normal, y binormal), line loads
//     (from, to, force per length), tip force (cantilevers), end displacements X0 and X1 (m);
//   spine axial: point and line loads along the spine, and where it is held (axial_fixed_at);
//   rigid pose: rotation (axis-angle vector, rad, world axes, about the spine's root point) and
//     translation (m);
//   a tip couple (free cantilevers), large curls (large_deflection), and a reach target (wire
//     IK, ReachChannels);
//   joint angles: degrees about the part's joint axes X, Y, Z (joint.h), clamped to the joint's
//     type and limits when sampled; they turn the part about its root point (after `rotation`);
//   rigid-body dynamics (rigid parts only): forces applied at points of the body and a torque,
//     world axes, and a drag (RigidDrag), integrated by Playback.
// and per profile wire (paper Fig. 8): the stretch [from, to] of the loop that deforms, its
// boundary condition, point and line loads in the profile's spine frame.
//
// RawClip rules (ValidateRawClip; BuildClip adds the rig's): a name; duration in (0, 1e6] s;
// every track follows ValidateRawTrack's rules with key times within [0, duration]; boundary
// keys strictly increasing within [0, duration]; part names known to the rig and each part
// listed at most once; profile indices within the part; rigid-body forces only on rigid parts;
// joint angles only on parts with a parent (the root has no joint); a point load's direction
// keys of non-zero length and a line load's stretch non-empty (to > from, both clamped to
// [0, 1]) at some key of its ends: a load that would never act is refused, not skipped;
// translation keys within 1e6 m.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "wirerig/anim/track.h"
#include "wirerig/io/result.h"
#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/rig_model.h"

namespace wirerig {

inline constexpr double kMaxClipDuration = 1e6;     // s
inline constexpr double kMaxClipTranslation = 1e6;  // m, a part's translation key

enum class LoopMode : int {
  kOnce = 0,      // times beyond the duration hold the last frame
  kLoop = 1,      // time wraps around the duration
  kPingPong = 2,  // time runs forward, then back
};
// Names used in files: "once", "loop", "ping_pong".
std::string_view ToString(LoopMode mode);
bool ParseLoopMode(std::string_view name, LoopMode* out);

// The axes a load's direction is given in. kLocal: the wire's local axes (x normal, y
// binormal, z tangent). kWorld: world axes of the rest pose, turned into the local axes at the
// load (a line load: at the middle of its stretch) when sampled; the part's pose then carries
// the load along, as it does local loads. The tangential part of a world direction is dropped
// from bending loads (it is an axial load).
enum class LoadAxes : int { kLocal = 0, kWorld = 1 };

// Channel groups, shared by the raw form (TrackT = RawTrack) and the built form (Track).
template <template <typename> class TrackT>
struct PointLoadChannels {
  TrackT<double> at;         // v in [0, 1] along the wire (clamped when sampled)
  TrackT<double> magnitude;  // N
  TrackT<Vec3> direction;    // normalized when sampled (zero: no force)
  LoadAxes axes = LoadAxes::kLocal;
};

template <template <typename> class TrackT>
struct LineLoadChannels {
  TrackT<double> from;            // v in [0, 1]; default 0
  TrackT<double> to;              // v in [0, 1]; default 1 (a stretch of zero width is skipped)
  TrackT<Vec3> force_per_length;  // N/m
  LoadAxes axes = LoadAxes::kLocal;
};

template <template <typename> class TrackT>
struct AxialPointLoadChannels {
  TrackT<double> at;     // v in [0, 1]
  TrackT<double> force;  // N, positive towards v = 1
};

template <template <typename> class TrackT>
struct AxialLineLoadChannels {
  TrackT<double> from;              // default 0
  TrackT<double> to;                // default 1
  TrackT<double> force_per_length;  // N/m, positive towards v = 1
};

template <template <typename> class TrackT>
struct RigidForceChannels {
  Vec3 at = Vec3::Zero();  // the point of the body the force acts on, at rest, world, m
  TrackT<Vec3> force;      // N, world axes
};

// Drag on a rigid body moving through a fluid (water, air): a force -(linear + quadratic |v|) v
// at the centre of mass, v its velocity, and a torque -angular w about it, w its angular
// velocity. Constant over the clip; zero: no drag.
struct RigidDrag {
  double linear = 0.0;     // N s/m
  double quadratic = 0.0;  // N s^2/m^2
  double angular = 0.0;    // N m s
  bool IsZero() const { return linear == 0.0 && quadratic == 0.0 && angular == 0.0; }
};

// Wire IK in a clip ("reach this point", wire_ik.h): the tip force that puts the tip of the
// part's spine on a target, solved every step of playback (corotational_wire_ik.h for parts
// with large_deflection), blended in by weight: at weight w the part's own bending loads are
// scaled by 1 - w and the solved tip force by w. The part's support is placed by its pose and
// its parents' poses (a parent's own bending is not followed: exact under rigid parents).
template <template <typename> class TrackT>
struct ReachChannels {
  TrackT<Vec3> target;  // m, world axes (of the rest rig, see parent_frame); no keys: none
  // The target rides with the part's parent (given at the parent's rest placement): a point on
  // or beside a moving body. Otherwise a fixed point of the world.
  bool parent_frame = false;
  TrackT<double> weight;  // clamped to [0, 1] when sampled; no keys: 1
  // Bound on the solved force, N, in [0, 1e12]; 0: 16 EI / L^2 (a tip force that turns a
  // cantilever's tip by about 80 degrees).
  double max_force = 0.0;
};

struct BoundaryKey {
  double time = 0.0;  // s; the family holds from this key to the next
  BoundaryCondition boundary = BoundaryCondition::kCantileverFree;
};

template <template <typename> class TrackT>
struct PartChannels {
  std::vector<BoundaryKey> boundary;  // empty: cantilever with a free end
  std::vector<PointLoadChannels<TrackT>> point_loads;
  std::vector<LineLoadChannels<TrackT>> line_loads;
  TrackT<Vec3> tip_force;   // N, local axes, cantilevers only
  TrackT<Vec3> tip_couple;  // N m: the direction the tip turns towards; free tips
  LoadAxes tip_couple_axes = LoadAxes::kLocal;  // kWorld: turned into the tip's rest frame
  TrackT<Vec3> start_displacement;              // X0, m, local axes
  TrackT<Vec3> end_displacement;                // X1, m, local axes (simply supported and clamped)
  double axial_fixed_at = 0.0;                  // v where the spine is held axially
  std::vector<AxialPointLoadChannels<TrackT>> axial_point_loads;
  std::vector<AxialLineLoadChannels<TrackT>> axial_line_loads;
  TrackT<Vec3> rotation;      // axis-angle vector, rad, world axes
  TrackT<Vec3> translation;   // m, world axes
  TrackT<Vec3> joint_angles;  // degrees about the joint's X, Y, Z axes
  std::vector<RigidForceChannels<TrackT>> rigid_forces;
  TrackT<Vec3> rigid_torque;  // N m, world axes
  RigidDrag rigid_drag;       // rigid parts only
  // Deformable cantilevers: the spine curls past small-deflection theory (SpineLoads::
  // large_deflection); every boundary key must then be a cantilever.
  bool large_deflection = false;
  ReachChannels<TrackT> reach;  // deformable cantilevers only
};

template <template <typename> class TrackT>
struct ProfileChannels {
  std::vector<std::uint32_t> profiles;  // which profile wires of the part; empty: all
  double from = 0.0;                    // stretch of the loop, 0 <= from < to <= 1
  double to = 1.0;
  BoundaryCondition boundary = BoundaryCondition::kClamped;
  std::vector<PointLoadChannels<TrackT>> point_loads;
  std::vector<LineLoadChannels<TrackT>> line_loads;
};

struct RawPartTracks {
  std::string part;  // the rig part's name
  PartChannels<RawTrack> channels;
};

struct RawProfileTracks {
  std::string part;
  ProfileChannels<RawTrack> channels;
};

struct RawClip {
  std::string name;
  double duration = 1.0;  // s
  LoopMode loop = LoopMode::kOnce;
  std::vector<RawPartTracks> parts;
  std::vector<RawProfileTracks> profiles;
};

// Empty when valid, else "<where>: <reason>", e.g. "parts[2].point_loads[0].magnitude.keys[3].
// time: beyond the clip's duration".
std::string ValidateRawClip(const RawClip& raw);

struct Clip {
  std::string name;
  double duration = 1.0;
  LoopMode loop = LoopMode::kOnce;
  std::vector<PartChannels<Track>> parts;  // one per rig part, in the rig's order
  struct ProfileGroup {
    std::uint32_t part = 0;
    ProfileChannels<Track> channels;  // profiles resolved: never empty
  };
  std::vector<ProfileGroup> profiles;
  // Every key time of every track, sorted and unique (for timelines and rigid-body steps).
  std::vector<double> key_times;

  // The clip-local time for a playback time t (s), by the loop mode.
  double LocalTime(double t) const;
  // True if any part is driven by rigid-body dynamics (needs Playback's integration).
  bool HasDynamics() const;
};

// Resolves names against the model; errors read "<where>: <reason>".
Result<Clip> BuildClip(const RawClip& raw, const RigModel& model);

}  // namespace wirerig
