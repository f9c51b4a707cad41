#include "wirerig/rig/profile_curves.h"

#include "wirerig/runtime/spine_interpolation.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace wirerig {
namespace {

constexpr double kFar = std::numeric_limits<double>::max();

// Orientation of r relative to the line pq (2D coordinates): > 0 to the left.
inline double Orient(double px, double py, double qx, double qy, double rx, double ry) {
  return (qx - px) * (ry - py) - (qy - py) * (rx - px);
}

// Strictly opposite signs.
inline bool Straddles(double s0, double s1) {
  return (s0 > 0.0 && s1 < 0.0) || (s0 < 0.0 && s1 > 0.0);
}

// Whether two non-adjacent edges of the profile's polygon (in the profile plane) properly cross:
// each edge's endpoints strictly on opposite sides of the other's line. Each edge's line is
// tested against all later vertices at once (a vectorisable loop); only edges whose endpoints
// straddle it get the second test. `scratch` is reused between calls.
bool SelfIntersects(const ProfileCurve& profile, std::vector<double>& scratch) {
  const std::size_t n = profile.points.size();
  if (n < 4) return false;
  scratch.resize(3 * (n + 1));
  double* x = scratch.data();
  double* y = x + (n + 1);
  double* side = y + (n + 1);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 d = profile.points[i] - profile.origin;
    x[i] = d.dot(profile.frame.normal);
    y[i] = d.dot(profile.frame.binormal);
  }
  x[n] = x[0];  // edge n - 1 of a closed profile ends at vertex 0
  y[n] = y[0];
  const std::size_t edges = profile.closed ? n : n - 1;
  for (std::size_t i = 0; i < edges; ++i) {
    // Edges j in [i + 2, end), but not edge n - 1 with edge 0 (adjacent through the seam).
    const std::size_t end = profile.closed && i == 0 ? n - 1 : edges;
    if (i + 2 >= end) continue;
    const double ax = x[i], ay = y[i], bx = x[i + 1], by = y[i + 1];
    // Edge j straddles edge i's line (side[j], side[j + 1] known); then edge i must straddle
    // edge j's.
    auto crosses = [&](std::size_t j) {
      if (!Straddles(side[j], side[j + 1])) return false;
      const double o3 = Orient(x[j], y[j], x[j + 1], y[j + 1], ax, ay);
      const double o4 = Orient(x[j], y[j], x[j + 1], y[j + 1], bx, by);
      return ((o3 > 0.0) != (o4 > 0.0)) && o3 != 0.0 && o4 != 0.0;
    };
    std::size_t k = i + 2;  // next vertex whose side is computed
#if defined(__SSE2__)
    // Two vertices at a time; candidate edges j have side[j] * side[j + 1] <= 0, which holds
    // whenever the two straddle (a product that underflows is still -0).
    const __m128d vax = _mm_set1_pd(ax), vay = _mm_set1_pd(ay);
    const __m128d vdx = _mm_set1_pd(bx - ax), vdy = _mm_set1_pd(by - ay);
    const __m128d zero = _mm_setzero_pd();
    __m128d previous = _mm_set1_pd(1.0);  // lane 1: side[k - 1]
    auto sides = [&](std::size_t first) {
      return _mm_sub_pd(_mm_mul_pd(vdx, _mm_sub_pd(_mm_loadu_pd(y + first), vay)),
                        _mm_mul_pd(vdy, _mm_sub_pd(_mm_loadu_pd(x + first), vax)));
    };
    // Lanes of shuffle(previous, current) * current: (side[k - 1], side[k]) times
    // (side[k], side[k + 1]), for edges k - 1 and k.
    for (; k + 3 <= end; k += 4) {
      const __m128d low = sides(k), high = sides(k + 2);
      _mm_storeu_pd(side + k, low);
      _mm_storeu_pd(side + k + 2, high);
      const __m128d p0 = _mm_mul_pd(_mm_shuffle_pd(previous, low, 1), low);
      const __m128d p1 = _mm_mul_pd(_mm_shuffle_pd(low, high, 1), high);
      previous = high;
      unsigned m = static_cast<unsigned>(_mm_movemask_pd(_mm_cmple_pd(p0, zero))) |
                   static_cast<unsigned>(_mm_movemask_pd(_mm_cmple_pd(p1, zero))) << 2;
      for (; m != 0; m &= m - 1) {
        const std::size_t j = k - 1 + static_cast<std::size_t>(std::countr_zero(m));
        if (j >= i + 2 && crosses(j)) return true;
      }
    }
    for (; k + 1 <= end; k += 2) {
      const __m128d current = sides(k);
      _mm_storeu_pd(side + k, current);
      const __m128d product = _mm_mul_pd(_mm_shuffle_pd(previous, current, 1), current);
      previous = current;
      for (unsigned m = static_cast<unsigned>(_mm_movemask_pd(_mm_cmple_pd(product, zero))); m != 0;
           m &= m - 1) {
        const std::size_t j = k - 1 + static_cast<std::size_t>(std::countr_zero(m));
        if (j >= i + 2 && crosses(j)) return true;
      }
    }
#endif
    for (; k <= end; ++k) {
      side[k] = Orient(ax, ay, bx, by, x[k], y[k]);
      if (k >= i + 3 && crosses(k - 1)) return true;
    }
  }
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
// `cosines` and `sines`: of the rays' angles 2 pi j / rays.
CastResult CastRays(const ProfileRequest& request, ProfileCurve& profile,
                    const std::vector<double>& cosines, const std::vector<double>& sines,
                    std::vector<Vec3>& hits, std::vector<bool>& hit,
                    ProfileDiagnostics* diagnostics) {
  const int rays = request.points_per_profile;
  CastResult result;
  for (int j = 0; j < rays; ++j) {
    const Vec3 direction = cosines[j] * profile.frame.normal + sines[j] * profile.frame.binormal;
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
  std::vector<double> cosines(static_cast<std::size_t>(std::max(rays, 0)));
  std::vector<double> sines(cosines.size());
  for (int j = 0; j < rays; ++j) {
    const double angle = 2.0 * std::numbers::pi * j / rays;
    cosines[j] = std::cos(angle);
    sines[j] = std::sin(angle);
  }
  std::vector<double> scratch;
  for (int k = 1; k <= count; ++k) {
    ProfileCurve profile;
    profile.v = double(k) / double(count + 1);
    profile.origin = request.central_curve->Position(profile.v);
    profile.frame = request.central_curve->FrameAt(profile.v);
    for (int pass = 0; pass < request.recentre_passes; ++pass) {
      const CastResult cast = CastRays(request, profile, cosines, sines, hits, hit, nullptr);
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
    const CastResult cast = CastRays(request, profile, cosines, sines, hits, hit, &set.diagnostics);
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
    if (SelfIntersects(profile, scratch)) ++set.diagnostics.self_intersecting;
    set.profiles.push_back(std::move(profile));
    set.foreign_points.push_back(cast.other_part);
  }
  for (std::size_t k = 0; k + 1 < set.profiles.size(); ++k)
    if (ProfilesCross(set.profiles[k].points, set.profiles[k].origin, set.profiles[k].frame.tangent,
                      set.profiles[k + 1].points, set.profiles[k + 1].origin,
                      set.profiles[k + 1].frame.tangent))
      ++set.diagnostics.crossing_neighbour;
  return set;
}

}  // namespace wirerig
