#include "wirerig/rig/profile_curves.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace wirerig {
namespace {

constexpr double kFar = std::numeric_limits<double>::max();

// Segment intersection in the plane (2D coordinates), proper crossings only.
bool SegmentsCross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  auto orient = [](const Vec2& p, const Vec2& q, const Vec2& r) {
    return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
  };
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
               o4 = orient(c, d, b);
  return ((o1 > 0) != (o2 > 0)) && ((o3 > 0) != (o4 > 0)) && o1 != 0 && o2 != 0 && o3 != 0 &&
         o4 != 0;
}

bool SelfIntersects(const ProfileCurve& profile) {
  const std::size_t n = profile.points.size();
  if (n < 4) return false;
  std::vector<Vec2> q(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 d = profile.points[i] - profile.origin;
    q[i] = Vec2(d.dot(profile.frame.normal), d.dot(profile.frame.binormal));
  }
  const std::size_t edges = profile.closed ? n : n - 1;
  for (std::size_t i = 0; i < edges; ++i)
    for (std::size_t j = i + 2; j < edges; ++j) {
      if (profile.closed && i == 0 && j == n - 1) continue;  // adjacent through the seam
      if (SegmentsCross(q[i], q[(i + 1) % n], q[j], q[(j + 1) % n])) return true;
    }
  return false;
}

// Profiles k and k+1 cross when a point of either lies beyond the other's plane.
bool Cross(const ProfileCurve& a, const ProfileCurve& b) {
  for (const Vec3& p : a.points)
    if ((p - b.origin).dot(b.frame.tangent) > 0.0) return true;
  for (const Vec3& p : b.points)
    if ((p - a.origin).dot(a.frame.tangent) < 0.0) return true;
  return false;
}

// Keeps the longest cyclic run of hits, in ray order, starting after a miss.
std::vector<Vec3> LongestRun(const std::vector<Vec3>& hits, const std::vector<bool>& hit) {
  const std::size_t n = hits.size();
  std::size_t best_start = 0, best_length = 0;
  for (std::size_t start = 0; start < n; ++start) {
    if (!hit[start] || hit[(start + n - 1) % n]) continue;  // runs start right after a miss
    std::size_t length = 0;
    while (length < n && hit[(start + length) % n]) ++length;
    if (length > best_length) best_start = start, best_length = length;
  }
  std::vector<Vec3> run;
  for (std::size_t k = 0; k < best_length; ++k) run.push_back(hits[(best_start + k) % n]);
  return run;
}

struct CastResult {
  std::size_t hits = 0;
  std::size_t entering = 0;    // hits through a front face: the ray came from outside
  std::size_t other_part = 0;  // points on another part's surface
};

// Casts the profile's rays from its origin. Counts misses and other-part hits into
// `diagnostics` only when `diagnostics` is given (the final pass).
CastResult CastRays(const ProfileRequest& request, ProfileCurve& profile, std::vector<Vec3>& hits,
                    std::vector<bool>& hit, ProfileDiagnostics* diagnostics) {
  const int rays = request.points_per_profile;
  CastResult result;
  for (int j = 0; j < rays; ++j) {
    const double angle = 2.0 * std::numbers::pi * j / rays;
    const Vec3 direction =
        std::cos(angle) * profile.frame.normal + std::sin(angle) * profile.frame.binormal;
    std::optional<RayHit> chosen = request.part_bvh->Raycast(profile.origin, direction, 0.0, kFar);
    const std::optional<RayHit> first =
        request.mesh_bvh ? request.mesh_bvh->Raycast(profile.origin, direction, 0.0, kFar)
                         : std::nullopt;
    // Another part's surface counts when the ray leaves through a junction, or meets it first.
    const bool other_part = first && request.triangle_part[first->triangle] != request.part &&
                            (!chosen || first->t < chosen->t * (1.0 - 1e-9));
    if (!chosen) chosen = first;
    hit[j] = chosen.has_value();
    if (diagnostics) ++diagnostics->rays;
    if (!chosen) {
      if (diagnostics) ++diagnostics->misses;
      continue;
    }
    if (other_part) ++result.other_part;
    if (diagnostics && other_part) ++diagnostics->other_part_hits;
    hits[j] = chosen->point;
    ++result.hits;
    if (!request.triangles.empty()) {
      const Triangle& t = request.triangles[chosen->triangle];
      const Vec3& a = request.positions[t[0]];
      const Vec3 normal = (request.positions[t[1]] - a).cross(request.positions[t[2]] - a);
      if ((normal.dot(direction) < 0.0) != request.inward_facing) ++result.entering;
    }
  }
  return result;
}

}  // namespace

Vec3 ProfileCentroid(const ProfileCurve& profile) {
  const std::vector<Vec3>& p = profile.points;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& x : p) mean += x;
  mean /= double(p.size());
  if (!profile.closed || p.size() < 3) return mean;
  // Fan from the mean; signed areas about the profile plane's normal.
  double area = 0.0;
  Vec3 moment = Vec3::Zero();
  const Vec3& n = profile.frame.tangent;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& a = p[i];
    const Vec3& b = p[(i + 1) % p.size()];
    const double signed_area = 0.5 * n.dot((a - mean).cross(b - mean));
    area += signed_area;
    moment += signed_area * (mean + a + b) / 3.0;
  }
  double scale = 0.0;
  for (const Vec3& x : p) scale = std::max(scale, (x - mean).squaredNorm());
  if (std::abs(area) <= 1e-12 * scale) return mean;
  return moment / area;
}

ProfileSet GenerateProfiles(const ProfileRequest& request) {
  ProfileSet set;
  const int count = request.profile_count, rays = request.points_per_profile;
  std::vector<Vec3> hits(static_cast<std::size_t>(rays));
  std::vector<bool> hit(static_cast<std::size_t>(rays));
  for (int k = 1; k <= count; ++k) {
    ProfileCurve profile;
    profile.v = double(k) / double(count + 1);
    profile.origin = request.central_curve->Position(profile.v);
    profile.frame = request.central_curve->FrameAt(profile.v);
    for (int pass = 0; pass < request.recentre_passes; ++pass) {
      const CastResult cast = CastRays(request, profile, hits, hit, nullptr);
      // Only a loop wholly on the part's own surface says where the part's centre is.
      if (cast.hits != std::size_t(rays) || cast.entering > 0 || cast.other_part > 0) break;
      profile.points = hits;
      profile.closed = true;
      Vec3 offset = ProfileCentroid(profile) - profile.origin;
      offset -= offset.dot(profile.frame.tangent) * profile.frame.tangent;
      profile.origin += offset;
      double size = 0.0;
      for (const Vec3& p : hits) size = std::max(size, (p - profile.origin).norm());
      if (offset.norm() <= 1e-9 * size) break;
    }
    const CastResult cast = CastRays(request, profile, hits, hit, &set.diagnostics);
    if (2 * cast.entering > cast.hits) {
      ++set.diagnostics.outside_profiles;
      continue;
    }
    if (cast.hits == std::size_t(rays)) {
      profile.closed = true;
      profile.points = hits;
    } else {
      profile.closed = false;
      profile.points = LongestRun(hits, hit);
      ++set.diagnostics.open_profiles;
    }
    if (profile.points.size() < 2) {
      ++set.diagnostics.empty_profiles;
      continue;
    }
    if (SelfIntersects(profile)) ++set.diagnostics.self_intersecting;
    set.profiles.push_back(std::move(profile));
    set.foreign_points.push_back(cast.other_part);
  }
  for (std::size_t k = 0; k + 1 < set.profiles.size(); ++k)
    if (Cross(set.profiles[k], set.profiles[k + 1])) ++set.diagnostics.crossing_neighbour;
  return set;
}

}  // namespace wirerig
