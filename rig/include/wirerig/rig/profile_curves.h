// Profile curves (paper section 2.1): the central curve of a part is divided into
// profile_count + 1 equal segments; at each of the profile_count interface points,
// points_per_profile rays are cast in the plane normal to the curve, at equal angles from the
// curve's rotation-minimizing normal; the nearest hit of each ray on the part's triangles is a
// profile point. A part's surface is open where it joins its neighbours: a ray that leaves
// through such a junction takes its first hit on the whole mesh (counted in other_part_hits).
// All rays hit: a closed loop. Some miss (an open surface): an open profile, the longest run of
// consecutive hits. The central curve only needs to be rough: a closed profile's
// rays are cast again from its centroid (in the same plane) until the origin moves less than
// 1e-9 of the profile's size, at most `recentre_passes` times; only loops wholly on the part's
// own surface are re-centred (at a junction the loop's centroid says nothing about the part).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "wirerig/rig/triangle_bvh.h"
#include "wirerig/runtime/curve.h"
#include "wirerig/runtime/parallel.h"

namespace wirerig {

struct ProfileCurve {
  double v = 0.0;              // interface parameter on the central curve, in (0, 1)
  Vec3 origin = Vec3::Zero();  // the rays' origin: on the central curve, then re-centred
  Frame frame;                 // frame.tangent is the normal of the profile's plane
  bool closed = false;
  std::vector<Vec3> points;  // in ray order (counter-clockwise about frame.tangent)
};

// Per part, never silently dropped: every count is reported.
struct ProfileDiagnostics {
  std::size_t rays = 0;
  std::size_t misses = 0;           // rays that hit nothing of the part
  std::size_t other_part_hits = 0;  // rays whose point is on another part's surface
  std::size_t wrap_hits = 0;        // rays that escaped through a hole: the wrap's hit stood in
  std::size_t open_profiles = 0;
  std::size_t empty_profiles = 0;      // fewer than 2 hits: dropped, and counted here
  std::size_t self_intersecting = 0;   // profiles whose loop crosses itself
  std::size_t crossing_neighbour = 0;  // adjacent profiles that cross each other
  std::size_t outside_profiles = 0;    // origin outside the part (hits enter the surface):
                                       // dropped, and counted here
};

struct ProfileSet {
  std::vector<ProfileCurve> profiles;
  // Per profile: how many of its points lie on another part (a junction profile).
  std::vector<std::size_t> foreign_points;
  ProfileDiagnostics diagnostics;
};

struct ProfileRequest {
  const Curve* central_curve = nullptr;
  int profile_count = 12;
  int points_per_profile = 24;
  const TriangleBvh* part_bvh = nullptr;  // the part's triangles
  // Optional: the whole mesh's BVH (active triangles) and its triangle -> part map, for rays
  // that leave the part through a junction and for other_part_hits.
  const TriangleBvh* mesh_bvh = nullptr;
  // Optional: a watertight stand-in of an open mesh (watertight_proxy.h); a ray that meets
  // nothing of the mesh (it escapes through a hole) takes the stand-in's hit instead.
  const TriangleBvh* wrap_bvh = nullptr;
  std::span<const int> triangle_part;
  int part = -1;
  int recentre_passes = 8;
  // Optional, the mesh the BVHs index (outward-facing triangles): a profile whose rays mostly
  // enter the surface instead of leaving it has its origin outside the part and is dropped.
  std::span<const Vec3> positions;
  std::span<const Triangle> triangles;
  bool inward_facing = false;  // the triangles face inwards (negative signed volume)
  // Optional: generates the profiles as parallel tasks (e.g. a ThreadPool made once). Null (the
  // default): on the calling thread. The set is identical either way.
  const ParallelFor* parallel = nullptr;
};

ProfileSet GenerateProfiles(const ProfileRequest& request);

// The profiles of several parts at once (their `parallel` fields are ignored): every profile of
// every request is one task of `parallel` (null: the calling thread), so a whole mesh's profiles
// share the threads in one go. sets[i] is identical to GenerateProfiles(requests[i]).
std::vector<ProfileSet> GenerateProfiles(std::span<const ProfileRequest> requests,
                                         const ParallelFor* parallel);

// The area centroid of a closed profile (a planar polygon), or the mean of an open one's points.
Vec3 ProfileCentroid(const ProfileCurve& profile);

}  // namespace wirerig
