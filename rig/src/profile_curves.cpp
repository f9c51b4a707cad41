#include "wirerig/rig/profile_curves.h"

#include "wirerig/rig/polygon_crossing.h"

#include "wirerig/runtime/spine_interpolation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <span>
#include <vector>

namespace wirerig {
namespace {

constexpr double kFar = std::numeric_limits<double>::max();

// Per-task scratch, reused from profile to profile.
struct ProfileScratch {
  std::vector<double> x, y;  // a profile's points in its plane's coordinates
  PolygonCrossingScratch crossing;
  std::vector<std::optional<RayHit>> part_hits, mesh_hits;  // per ray
};

// Whether the profile's polygon (in the profile plane) crosses itself (PolygonCrossesItself).
bool SelfIntersects(const ProfileCurve& profile, ProfileScratch& scratch) {
  const std::size_t n = profile.points.size();
  scratch.x.resize(n);
  scratch.y.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 d = profile.points[i] - profile.origin;
    scratch.x[i] = d.dot(profile.frame.normal);
    scratch.y[i] = d.dot(profile.frame.binormal);
  }
  return PolygonCrossesItself(scratch.x, scratch.y, profile.closed, scratch.crossing);
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

// Whether a profile's rays are cast as one fan (TriangleBvh::RaycastFan) on `bvh`: when they
// outnumber the triangles a plane typically cuts on it (about 1.5 sqrt(#T) on a
// part: the fan's cost grows with those, ray-by-ray casting's with the rays). The nearest hits
// are the same either way (but for which of two triangles meeting at a hit edge is reported,
// where the points agree to rounding).
bool UseFan(const TriangleBvh& bvh, int rays) {
  return rays <= int(TriangleBvh::kMaxFanRays) &&
         double(rays) >= 2.0 * std::sqrt(double(bvh.triangle_count()));
}

// The rays' nearest hits on one BVH, as a fan or ray by ray.
void Cast(const TriangleBvh& bvh, const ProfileCurve& profile, const std::vector<double>& cosines,
          const std::vector<double>& sines, std::vector<std::optional<RayHit>>& out) {
  if (UseFan(bvh, int(cosines.size()))) {
    bvh.RaycastFan(profile.origin, profile.frame.normal, profile.frame.binormal, cosines, sines,
                   out);
    return;
  }
  for (std::size_t j = 0; j < cosines.size(); ++j)
    out[j] = bvh.Raycast(profile.origin,
                         cosines[j] * profile.frame.normal + sines[j] * profile.frame.binormal, 0.0,
                         kFar);
}

// Casts the profile's rays from its origin. Counts misses and other-part hits into
// `diagnostics` only when `diagnostics` is given (the final pass).
// `cosines` and `sines`: of the rays' angles 2 pi j / rays.
CastResult CastRays(const ProfileRequest& request, ProfileCurve& profile,
                    const std::vector<double>& cosines, const std::vector<double>& sines,
                    std::vector<Vec3>& hits, std::vector<bool>& hit, ProfileScratch& scratch,
                    ProfileDiagnostics* diagnostics) {
  const int rays = request.points_per_profile;
  CastResult result;
  Cast(*request.part_bvh, profile, cosines, sines, scratch.part_hits);
  if (request.mesh_bvh) Cast(*request.mesh_bvh, profile, cosines, sines, scratch.mesh_hits);
  for (int j = 0; j < rays; ++j) {
    auto direction = [&] {
      return Vec3(cosines[j] * profile.frame.normal + sines[j] * profile.frame.binormal);
    };
    std::optional<RayHit> chosen = scratch.part_hits[j];
    const std::optional<RayHit> first = request.mesh_bvh ? scratch.mesh_hits[j] : std::nullopt;
    // Another part's surface counts when the ray leaves through a junction, or meets it first.
    const bool other_part = first && request.triangle_part[first->triangle] != request.part &&
                            (!chosen || first->t < chosen->t * (1.0 - 1e-9));
    if (!chosen) chosen = first;
    bool through_hole = false;
    if (!chosen && request.wrap_bvh) {
      chosen = request.wrap_bvh->Raycast(profile.origin, direction(), 0.0, kFar);
      through_hole = chosen.has_value();
    }
    hit[j] = chosen.has_value();
    if (diagnostics) ++diagnostics->rays;
    if (!chosen) {
      if (diagnostics) ++diagnostics->misses;
      continue;
    }
    if (other_part) ++result.other_part;
    if (diagnostics && other_part) ++diagnostics->other_part_hits;
    if (diagnostics && through_hole) ++diagnostics->wrap_hits;
    hits[j] = chosen->point;
    ++result.hits;
    if (!request.triangles.empty() && !through_hole) {
      const Triangle& t = request.triangles[chosen->triangle];
      const Vec3& a = request.positions[t[0]];
      const Vec3 normal = (request.positions[t[1]] - a).cross(request.positions[t[2]] - a);
      if ((normal.dot(direction()) < 0.0) != request.inward_facing) ++result.entering;
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

namespace {

// One profile's outcome, before the set is assembled in order.
struct ProfileOutcome {
  bool kept = false;
  ProfileCurve profile;
  std::size_t foreign = 0;
  ProfileDiagnostics diagnostics;  // this profile's counts (crossing_neighbour aside)
};

// The rays' directions, as cosines and sines of 2 pi j / rays.
struct RayTable {
  std::vector<double> cosines, sines;
  explicit RayTable(int rays) {
    cosines.resize(static_cast<std::size_t>(std::max(rays, 0)));
    sines.resize(cosines.size());
    for (int j = 0; j < rays; ++j) {
      const double angle = 2.0 * std::numbers::pi * j / rays;
      cosines[j] = std::cos(angle);
      sines[j] = std::sin(angle);
    }
  }
};

// The table for `rays`, made once per thread for each of the first kCachedTables ray counts it
// is asked for (later ones are made on every call). The tables live as long as the thread.
const RayTable* CachedRayTable(int rays) {
  constexpr std::size_t kCachedTables = 16;
  thread_local std::vector<std::unique_ptr<const RayTable>> tables;
  for (const auto& table : tables)
    if (table->cosines.size() == static_cast<std::size_t>(std::max(rays, 0))) return table.get();
  if (tables.size() == kCachedTables) return nullptr;
  tables.push_back(std::make_unique<const RayTable>(rays));
  return tables.back().get();
}

// Profile k (1-based) of the request: every profile is independent of the others.
void GenerateProfile(const ProfileRequest& request, const RayTable& table, int k,
                     ProfileOutcome& out) {
  const int count = request.profile_count, rays = request.points_per_profile;
  // Scratch reused by the thread's later profiles.
  thread_local std::vector<Vec3> hits;
  thread_local std::vector<bool> hit;
  thread_local ProfileScratch scratch;
  hits.assign(static_cast<std::size_t>(rays), Vec3::Zero());
  hit.assign(static_cast<std::size_t>(rays), false);
  scratch.part_hits.resize(hits.size());
  scratch.mesh_hits.resize(hits.size());
  ProfileCurve& profile = out.profile;
  ProfileDiagnostics& diagnostics = out.diagnostics;
  const std::vector<double>& cosines = table.cosines;
  const std::vector<double>& sines = table.sines;
  profile.v = double(k) / double(count + 1);
  profile.origin = request.central_curve->Position(profile.v);
  profile.frame = request.central_curve->FrameAt(profile.v);
  for (int pass = 0; pass < request.recentre_passes; ++pass) {
    const CastResult cast = CastRays(request, profile, cosines, sines, hits, hit, scratch, nullptr);
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
  const CastResult cast =
      CastRays(request, profile, cosines, sines, hits, hit, scratch, &diagnostics);
  if (2 * cast.entering > cast.hits) {
    ++diagnostics.outside_profiles;
    return;
  }
  if (cast.hits == std::size_t(rays)) {
    profile.closed = true;
    profile.points = hits;
  } else {
    profile.closed = false;
    profile.points = LongestRun(hits, hit);
    ++diagnostics.open_profiles;
  }
  if (profile.points.size() < 2) {
    ++diagnostics.empty_profiles;
    return;
  }
  if (SelfIntersects(profile, scratch)) ++diagnostics.self_intersecting;
  out.kept = true;
  out.foreign = cast.other_part;
}

void Add(ProfileDiagnostics& total, const ProfileDiagnostics& d) {
  total.rays += d.rays;
  total.misses += d.misses;
  total.other_part_hits += d.other_part_hits;
  total.wrap_hits += d.wrap_hits;
  total.open_profiles += d.open_profiles;
  total.empty_profiles += d.empty_profiles;
  total.self_intersecting += d.self_intersecting;
  total.crossing_neighbour += d.crossing_neighbour;
  total.outside_profiles += d.outside_profiles;
}

// The set from its profiles' outcomes, in order.
ProfileSet Assemble(std::span<ProfileOutcome> outcomes) {
  ProfileSet set;
  for (ProfileOutcome& outcome : outcomes) {
    Add(set.diagnostics, outcome.diagnostics);
    if (!outcome.kept) continue;
    set.profiles.push_back(std::move(outcome.profile));
    set.foreign_points.push_back(outcome.foreign);
  }
  for (std::size_t k = 0; k + 1 < set.profiles.size(); ++k)
    if (ProfilesCross(set.profiles[k].points, set.profiles[k].origin, set.profiles[k].frame.tangent,
                      set.profiles[k + 1].points, set.profiles[k + 1].origin,
                      set.profiles[k + 1].frame.tangent))
      ++set.diagnostics.crossing_neighbour;
  return set;
}

// Every profile of every request, as one list of tasks.
struct BatchTasks {
  std::span<const ProfileRequest> requests;
  std::vector<const RayTable*> tables;   // per request (cached or in `owned`)
  std::vector<RayTable> owned;           // tables beyond the cache
  std::vector<std::size_t> first;        // per request: its first task; then the total
  std::vector<ProfileOutcome> outcomes;  // per task

  static void Run(const void* context, std::size_t task) {
    auto& self = *static_cast<BatchTasks*>(const_cast<void*>(context));
    const std::size_t r =
        static_cast<std::size_t>(std::upper_bound(self.first.begin(), self.first.end(), task) -
                                 self.first.begin()) -
        1;
    GenerateProfile(self.requests[r], *self.tables[r], static_cast<int>(task - self.first[r]) + 1,
                    self.outcomes[task]);
  }
};

}  // namespace

std::vector<ProfileSet> GenerateProfiles(std::span<const ProfileRequest> requests,
                                         const ParallelFor* parallel) {
  BatchTasks batch;
  batch.requests = requests;
  batch.owned.reserve(requests.size());  // no reallocation: `tables` points into it
  std::size_t total = 0;
  for (const ProfileRequest& request : requests) {
    const RayTable* table = CachedRayTable(request.points_per_profile);
    if (!table) table = &batch.owned.emplace_back(request.points_per_profile);
    batch.tables.push_back(table);
    batch.first.push_back(total);
    total += static_cast<std::size_t>(std::max(request.profile_count, 0));
  }
  batch.first.push_back(total);
  batch.outcomes.resize(total);
  RunTasks(parallel, total, &BatchTasks::Run, &batch);
  std::vector<ProfileSet> sets;
  sets.reserve(requests.size());
  for (std::size_t r = 0; r < requests.size(); ++r)
    sets.push_back(Assemble(std::span<ProfileOutcome>(batch.outcomes.data() + batch.first[r],
                                                      batch.first[r + 1] - batch.first[r])));
  return sets;
}

ProfileSet GenerateProfiles(const ProfileRequest& request) {
  return std::move(
      GenerateProfiles(std::span<const ProfileRequest>(&request, 1), request.parallel).front());
}

}  // namespace wirerig
