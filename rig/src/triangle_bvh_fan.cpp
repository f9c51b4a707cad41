// TriangleBvh::RaycastFan: the nearest hits of a fan of rays sharing an origin and a plane, in
// one traversal of the BVH.
//
// Traversal. The wide float tree Raycast uses (RayNode) is walked once, keeping the children
// whose boxes reach within `slab` of the fan's plane (a plane-box test in float unit
// coordinates, with a margin that bounds every float rounding). `slab` bounds how far any hit
// can lie from the plane: ray directions stray from it by rounding only.
//
// Candidate rays. A ray can only hit a triangle where the triangle lies within `slab` of the
// plane: the triangle clipped to that band is a convex polygon whose vertices are the
// triangle's vertices inside the band and its edges' crossings of the band's faces. The rays
// whose angles (pseudo-angles, see FanAngle) fall in the polygon's angular extent seen from
// the origin, widened by kAngleMargin, are the candidates; a polygon with a point too close to
// the origin (relative to its vertices' distances) or whose extent reaches half a turn takes
// every ray. The rays' angles are bucketed so a range's first ray is found in O(1).
//
// Exact test. Each candidate (ray, triangle) pair gets Raycast's watertight test with the same
// floating-point operations, so t, u, v (and so the point) are bit for bit Raycast's for the
// same triangle; the nearest hit per ray wins as in Raycast (the later of equal t).
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>

#include "triangle_bvh_shared.h"
#include "wirerig/rig/triangle_bvh.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace wirerig {
namespace {

using namespace bvh_shared;

// A monotonic stand-in for the angle of (x, y) about the origin, in [0, 4] (the "diamond
// angle"): 0, 1, 2, 3 along +x, +y, -x, -y, p(angle + pi) = p(angle) + 2 (mod 4), so an arc
// longer than half a turn is longer than 2, and |dp / dangle| <= 1. (x, y) must not be (0, 0).
// Without branches: quadrant q (0..3 counter-clockwise from +x), then q + r or q + 1 - r with
// r = |y| / (|x| + |y|).
inline double FanAngle(double x, double y) {
  const int below = y < 0.0, left = x < 0.0;
  const int q = 2 * below + (left ^ below);
  const double ax = std::abs(x), ay = std::abs(y);
  const double r = ay / (ax + ay);
  return double(q + (q & 1)) + double(1 - 2 * (q & 1)) * r;
}

// A product the compiler cannot contract into a fused multiply-add with what follows.
inline double FanRounded(double x) {
#if defined(__SSE2__)
  asm("" : "+x"(x));
#endif
  return x;
}

// Raycast's edge function p x q: with both products rounded on their own it is exactly
// antisymmetric (and equals Raycast's value for the same vertices).
inline double FanEdge(const double* p, const double* q) {
  return FanRounded(p[0] * q[1]) - FanRounded(p[1] * q[0]);
}

// Pseudo-angle margin of a triangle's angular extent (covers rounding many times over), and
// the squared relative distance from the origin under which a point's angle is not trusted.
constexpr double kAngleMargin = 1e-6;
constexpr double kNearOrigin2 = 1e-12;
// Buckets of the pseudo-angle range [0, 4) for finding a range's first ray.
constexpr int kAngleBuckets = 128;

}  // namespace

void TriangleBvh::RaycastFan(const Vec3& origin, const Vec3& normal, const Vec3& binormal,
                             std::span<const double> cosines, std::span<const double> sines,
                             std::span<std::optional<RayHit>> hits) const {
  const std::size_t n = std::min({hits.size(), cosines.size(), sines.size()});
  for (std::optional<RayHit>& hit : hits) hit.reset();
  if (ray_nodes_.empty() || n == 0) return;
  auto direction = [&](std::size_t j) -> Vec3 { return cosines[j] * normal + sines[j] * binormal; };
  auto ray_by_ray = [&] {
    for (std::size_t j = 0; j < n; ++j) hits[j] = Raycast(origin, direction(j), 0.0, kHuge);
  };
  // The fan's plane, with unit normal `plane`.
  Vec3 plane = normal.cross(binormal);
  const double plane_norm = plane.norm();
  if (n > kMaxFanRays || !(plane_norm > 1e-3 * normal.norm() * binormal.norm()) ||
      !(plane_norm < 1e100) || !origin.allFinite())
    return ray_by_ray();
  plane /= plane_norm;
  // The origin in unit coordinates; far from the root box the float plane test's rounding is
  // not bounded below, and such fans go ray by ray.
  const double to_unit = PowerOfTwo(-unit_exponent_);
  double start[3], start_sum = 0.0;
  for (int a = 0; a < 3; ++a) {
    start[a] = (origin[a] - unit_centre_[a]) * to_unit;
    start_sum += std::abs(start[a]);
  }
  if (!(start_sum <= 64.0)) return ray_by_ray();

  // The rays: shear constants (Raycast's, per ray j: axes kx, ky, kz, shear sx, sy, scale sz),
  // the pseudo-angles of their images in (normal, binormal) coordinates measured from the first
  // ray's (strictly increasing), and how far their directions stray from the plane (rounding):
  // stray >= |plane . d| / |d| for every ray.
  alignas(16) double ray_sx[kMaxFanRays + 1], ray_sy[kMaxFanRays + 1], ray_sz[kMaxFanRays + 1];
  std::uint8_t ray_axis[kMaxFanRays + 1];  // kz, with kx = kz + 1, ky = kz + 2 (mod 3)
  double angles[kMaxFanRays], image_v[kMaxFanRays];
  double off_max = 0.0, length2_min = kHuge;
  bool usable = true;
  // In simple loops (no early exits) so the divisions of different rays overlap.
  for (std::size_t j = 0; j < n; ++j) {
    const Vec3 d = direction(j);
    const double x = std::abs(d[0]), y = std::abs(d[1]), z = std::abs(d[2]);
    const int kz = z > std::max(x, y) ? 2 : y > x ? 1 : 0;
    const int kx = kz == 2 ? 0 : kz + 1;
    const int ky = kx == 2 ? 0 : kx + 1;
    const double length2 = d.squaredNorm();
    const double u = d.dot(normal), v = d.dot(binormal);
    usable = usable & (std::abs(d[kz]) >= kTinyDirection) & (length2 < 1e200) &
             (u * u + v * v > 1e-6 * length2);
    ray_axis[j] = static_cast<std::uint8_t>(kz);
    ray_sz[j] = d[kz];  // replaced by its reciprocal below
    ray_sx[j] = d[kx];
    ray_sy[j] = d[ky];
    angles[j] = u;  // replaced by the angle below
    image_v[j] = v;
    off_max = std::max(off_max, std::abs(plane.dot(d)));
    length2_min = std::min(length2_min, length2);
  }
  if (!usable) return ray_by_ray();
  for (std::size_t j = 0; j < n; ++j) {
    ray_sz[j] = 1.0 / ray_sz[j];
    ray_sx[j] *= ray_sz[j];
    ray_sy[j] *= ray_sz[j];
    angles[j] = FanAngle(angles[j], image_v[j]);
  }
  const double base = angles[0];
  for (std::size_t j = 0; j < n; ++j) {
    angles[j] -= base;
    if (angles[j] < 0.0) angles[j] += 4.0;
    usable = usable & (j == 0 || angles[j] > angles[j - 1]) & (angles[j] < 4.0);
  }
  if (!usable) return ray_by_ray();
  ray_axis[n] = 3;  // no ray: never shares a pair with ray n - 1
  // length2_min >= kTinyDirection^2 > 0.
  const double stray = off_max / std::sqrt(length2_min) * (1.0 + 8.0 * kEps);
  // first_ray[b]: the first ray whose angle is at least b * 4 / kAngleBuckets.
  std::uint16_t first_ray[kAngleBuckets];
  for (std::size_t b = 0, j = 0; b < kAngleBuckets; ++b) {
    const double from = double(b) * (4.0 / kAngleBuckets);
    while (j < n && angles[j] < from) ++j;
    first_ray[b] = static_cast<std::uint16_t>(j);
  }

  // Every point a ray can hit lies in the root box, within `reach` of the origin, and so within
  // reach * stray of the plane: triangles and boxes farther from the plane than `slab` (which
  // adds room for the rounding of the distances) cannot be hit.
  const Node& root = nodes_[0];
  double reach2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double d = std::max(std::abs(origin[a] - root.min[a]), std::abs(origin[a] - root.max[a]));
    reach2 += d * d;
  }
  const double slab = std::sqrt(reach2) * (2.0 * stray + 64.0 * kEps);

  // The float plane test: a box is kept when the plane distances of its nearest and farthest
  // corners, s = plane . (x - start) in units, bracket [-slab, slab] widened by `margin`. With
  // |box| <= 1.02 and the float normal within 2^-24 of `plane` per component, the rounding of
  // s (products, sums, the normal and start's conversion) stays below 2^-24 (16 + 4 |start|_1);
  // `margin` is 16 times that, plus the rounding of start itself (inside_error_).
  const double margin = (16.0 + 4.0 * start_sum) * 0x1p-20 + 2.0 * inside_error_;
  const auto band = static_cast<float>((slab * to_unit + margin) * (1.0 + 0x1p-20));
  double plane_start = 0.0;
  for (int a = 0; a < 3; ++a) plane_start += plane[a] * start[a];
  const auto offset = static_cast<float>(plane_start);
  int low_row[3], high_row[3];  // per axis: the box side of least and greatest plane distance
  float plane_f[3];
  for (int a = 0; a < 3; ++a) {
    plane_f[a] = static_cast<float>(plane[a]);
    const int negative = plane_f[a] < 0.0f;
    low_row[a] = a + 3 * negative;
    high_row[a] = a + 3 - 3 * negative;
  }

  // Per ray, the nearest hit so far: t, and the triangle's index and edge functions v, w and
  // their sum det (u = v / det, v = w / det in RayHit's terms, divided at the end).
  double best[kMaxFanRays], hit_det[kMaxFanRays], hit_v[kMaxFanRays], hit_w[kMaxFanRays];
  std::uint32_t hit_triangle[kMaxFanRays];
  std::fill(best, best + n, kMaxT);
  std::fill(hit_triangle, hit_triangle + n, kIndexMask);

  // Raycast's watertight test, given the edge functions u, v, w and the vertices' depths z
  // along ray j; keeps the nearest hit.
  auto finish = [&](std::size_t j, double u, double v, double w, const double* z,
                    std::uint32_t index) {
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return;
    const double det = u + v + w;
    const double scaled_t = u * z[0] + v * z[1] + w * z[2];
    if (!(std::abs(det) > std::abs(scaled_t) * 1e-300)) return;
    const double t = scaled_t / det;
    if (!(t > 0.0 && t <= best[j])) return;
    best[j] = t;
    hit_triangle[j] = index;
    hit_det[j] = det;
    hit_v[j] = v;
    hit_w[j] = w;
  };
  // Ray j against the triangle with vertex offsets d (vertex - origin), as Raycast does it.
  auto test = [&](std::size_t j, const double(*d)[3], std::uint32_t index) {
    const int kz = ray_axis[j], kx = kz == 2 ? 0 : kz + 1, ky = kx == 2 ? 0 : kx + 1;
    double p[3][3];
    for (int k = 0; k < 3; ++k) {
      const double pz = d[k][kz];
      p[k][0] = d[k][kx] - ray_sx[j] * pz;
      p[k][1] = d[k][ky] - ray_sy[j] * pz;
      p[k][2] = ray_sz[j] * pz;
    }
    const double z[3] = {p[0][2], p[1][2], p[2][2]};
    finish(j, FanEdge(p[1], p[2]), FanEdge(p[2], p[0]), FanEdge(p[0], p[1]), z, index);
  };
#if defined(__SSE2__)
  // Rays j and j + 1 (which share their axes) at once: the same operations, lane by lane.
  auto test_pair = [&](std::size_t j, const double(*d)[3], std::uint32_t index) {
    const int kz = ray_axis[j], kx = kz == 2 ? 0 : kz + 1, ky = kx == 2 ? 0 : kx + 1;
    const __m128d sx = _mm_loadu_pd(ray_sx + j), sy = _mm_loadu_pd(ray_sy + j),
                  sz = _mm_loadu_pd(ray_sz + j);
    __m128d x[3], y[3];
    alignas(16) double z[3][2];
    for (int k = 0; k < 3; ++k) {
      const __m128d pz = _mm_set1_pd(d[k][kz]);
      x[k] = _mm_sub_pd(_mm_set1_pd(d[k][kx]), _mm_mul_pd(sx, pz));
      y[k] = _mm_sub_pd(_mm_set1_pd(d[k][ky]), _mm_mul_pd(sy, pz));
      _mm_store_pd(z[k], _mm_mul_pd(sz, pz));
    }
    alignas(16) double e[3][2];
    _mm_store_pd(e[0], bvh_shared::EdgePair(x[1], y[1], x[2], y[2]));
    _mm_store_pd(e[1], bvh_shared::EdgePair(x[2], y[2], x[0], y[0]));
    _mm_store_pd(e[2], bvh_shared::EdgePair(x[0], y[0], x[1], y[1]));
    for (int lane = 0; lane < 2; ++lane) {
      const double depth[3] = {z[0][lane], z[1][lane], z[2][lane]};
      finish(j + lane, e[0][lane], e[1][lane], e[2][lane], depth, index);
    }
  };
#endif
  // The rays whose angle lies in [from, to], from >= -1.
  auto test_range = [&](double from, double to, const double(*d)[3], std::uint32_t index) {
    const int b = std::clamp(int(from * (kAngleBuckets / 4.0)), 0, kAngleBuckets - 1);
    std::size_t j = first_ray[b];
    while (j < n && angles[j] < from) ++j;
#if defined(__SSE2__)
    for (; j + 1 < n && angles[j + 1] <= to && ray_axis[j] == ray_axis[j + 1]; j += 2)
      test_pair(j, d, index);
#endif
    for (; j < n && angles[j] <= to; ++j) test(j, d, index);
  };
  // The rays whose angle lies in the arc from `lo` (a pseudo-angle) over `arc` (< 2), widened
  // by kAngleMargin on both sides.
  auto test_arc = [&](double lo, double arc, const double(*d)[3], std::uint32_t index) {
    double from = lo - base - kAngleMargin;
    if (from < 0.0) from += 4.0;
    const double to = from + arc + 2.0 * kAngleMargin;
    test_range(from, to, d, index);
    if (to >= 4.0) test_range(-1.0, to - 4.0, d, index);
  };
  // A triangle with no vertex within the band (the common case): exactly two of its edges cross
  // the band, from the lone vertex i (alone on its side of the plane) to the others. Their
  // crossings of the plane in homogeneous form, H = (s_l p_i - s_i p_l) sign(s_l - s_i) (p: the
  // images in (normal, binormal) coordinates; the point is |H| / |s_l - s_i| along H's
  // direction), bound the cut segment. The band's crossings move H by slab |p_l - p_i|,
  // accepted when below 1e-8 |H|; H's rounding is below 1e-8 |H| when |H| >= 1e-6
  // |s_l - s_i| sum |d|. Returns false (the general clipping decides) otherwise.
  auto cut_segment = [&](const double* x, const double* y, const double* s, const double(*d)[3],
                         std::uint32_t index) {
    static constexpr int kLone[8] = {0, 0, 1, 2, 2, 1, 0, 0};  // by the vertices' sides
    const int i = kLone[int(s[0] > 0.0) | int(s[1] > 0.0) << 1 | int(s[2] > 0.0) << 2];
    const int j = i == 2 ? 0 : i + 1, k = j == 2 ? 0 : j + 1;
    const double flip = s[i] > 0.0 ? -1.0 : 1.0;
    double size = 0.0;
    for (int v = 0; v < 3; ++v) size += std::abs(d[v][0]) + std::abs(d[v][1]) + std::abs(d[v][2]);
    double h[2][2], angle[2];
    int e = 0;
    for (const int l : {j, k}) {
      h[e][0] = flip * (s[l] * x[i] - s[i] * x[l]);
      h[e][1] = flip * (s[l] * y[i] - s[i] * y[l]);
      const double norm = std::abs(h[e][0]) + std::abs(h[e][1]);
      const double weight = std::abs(s[l]) + std::abs(s[i]);
      const double move = slab * (std::abs(x[l] - x[i]) + std::abs(y[l] - y[i]));
      if (!(norm >= 1e-6 * weight * size && move <= 1e-8 * norm)) return false;
      ++e;
    }
    angle[0] = FanAngle(h[0][0], h[0][1]);
    angle[1] = FanAngle(h[1][0], h[1][1]);
    double lo = angle[0], arc = angle[1] - angle[0];
    if (arc < 0.0) arc += 4.0;
    if (arc > 2.0) {
      lo = angle[1];
      arc = 4.0 - arc;
    }
    // A segment passing (nearly) through the origin: the general case (every ray).
    if (!(arc < 2.0 - 4.0 * kAngleMargin)) return false;
    test_arc(lo, arc, d, index);
    return true;
  };
  // Any triangle: its band-clipped polygon's angular extent, then the rays in it.
  auto clipped = [&](const double* x, const double* y, const double* s, const double(*d)[3],
                     std::uint32_t index) {
    double a[6];
    int m = 0;
    bool every_ray = false;
    auto add = [&](double px, double py, double scale2) {
      if (!(px * px + py * py > kNearOrigin2 * scale2)) {
        every_ray = true;
        return;
      }
      a[m++] = FanAngle(px, py);
    };
    double length2[3];
    for (int k = 0; k < 3; ++k) {
      length2[k] = d[k][0] * d[k][0] + d[k][1] * d[k][1] + d[k][2] * d[k][2];
      if (std::abs(s[k]) <= slab) add(x[k], y[k], length2[k]);
    }
    // Edge crossings of the band's faces s = -slab and s = slab (in the plane's coordinates,
    // a linear map, so the crossing's image is the images' interpolation).
    for (int k = 0; k < 3; ++k) {
      const int l = k == 2 ? 0 : k + 1;
      for (const double level : {-slab, slab}) {
        const double sk = s[k] - level, sl = s[l] - level;
        if (!((sk < 0.0 && sl > 0.0) || (sk > 0.0 && sl < 0.0))) continue;
        const double lambda = sk / (sk - sl);
        add(x[k] + lambda * (x[l] - x[k]), y[k] + lambda * (y[l] - y[k]),
            std::max(length2[k], length2[l]));
      }
    }
    if (!every_ray && m > 0) {
      // The extent is the complement of the widest gap between the points' angles; with no
      // gap over half a turn the polygon surrounds the origin.
      for (int i = 1; i < m; ++i)
        for (int k = i; k > 0 && a[k] < a[k - 1]; --k) std::swap(a[k], a[k - 1]);
      double gap = a[0] + 4.0 - a[m - 1];
      int after = 0;  // the first point after the widest gap
      for (int i = 1; i < m; ++i) {
        if (a[i] - a[i - 1] > gap) {
          gap = a[i] - a[i - 1];
          after = i;
        }
      }
      if (gap > 2.0 + 4.0 * kAngleMargin) {
        test_arc(a[after], 4.0 - gap, d, index);
        return;
      }
    }
    for (std::size_t j = 0; j < n; ++j) test(j, d, index);
  };

  std::uint32_t stack[(kRayWidth - 1) * kStackSize + 1];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const std::uint32_t current = stack[--top];
    if (!(current & kLeafRef)) {
      const RayNode& node = ray_nodes_[current];
      unsigned mask = 0;
#if defined(__SSE2__)
      const __m128 off = _mm_set1_ps(offset), hi = _mm_set1_ps(band), lo = _mm_set1_ps(-band);
      for (int g = 0; g < kRayWidth; g += 4) {
        __m128 low = _mm_setzero_ps(), high = _mm_setzero_ps();
        for (int a = 0; a < 3; ++a) {
          const __m128 p = _mm_set1_ps(plane_f[a]);
          low = _mm_add_ps(low, _mm_mul_ps(p, _mm_load_ps(node.box[low_row[a]] + g)));
          high = _mm_add_ps(high, _mm_mul_ps(p, _mm_load_ps(node.box[high_row[a]] + g)));
        }
        low = _mm_sub_ps(low, off);
        high = _mm_sub_ps(high, off);
        const __m128 keep = _mm_and_ps(_mm_cmple_ps(low, hi), _mm_cmpge_ps(high, lo));
        mask |= static_cast<unsigned>(_mm_movemask_ps(keep)) << g;
      }
#else
      for (int k = 0; k < kRayWidth; ++k) {
        float low = 0.0f, high = 0.0f;
        for (int a = 0; a < 3; ++a) {
          low += plane_f[a] * node.box[low_row[a]][k];
          high += plane_f[a] * node.box[high_row[a]][k];
        }
        if (low - offset <= band && high - offset >= -band) mask |= 1u << k;
      }
#endif
      for (; mask != 0; mask &= mask - 1) {
        assert(top < (kRayWidth - 1) * kStackSize + 1);
        stack[top++] = node.child[std::countr_zero(mask)];
      }
      continue;
    }
    const std::size_t leaf = current & ~kLeafRef;
    const double* vertices = &ray_vertices_[36 * leaf];
    const std::uint32_t* ids = &ray_triangles_[4 * leaf];
    // Per slot: vertex offsets from the origin, their plane distances and images.
    double d[4][3][3], s[4][3], x[4][3], y[4][3];
#if defined(__SSE2__)
    for (int pair = 0; pair < 2; ++pair) {
      for (int k = 0; k < 3; ++k) {
        __m128d offset_k[3];
        for (int a = 0; a < 3; ++a) {
          offset_k[a] =
              _mm_sub_pd(_mm_load_pd(vertices + 18 * pair + 6 * k + 2 * a), _mm_set1_pd(origin[a]));
          _mm_storel_pd(&d[2 * pair][k][a], offset_k[a]);
          _mm_storeh_pd(&d[2 * pair + 1][k][a], offset_k[a]);
        }
        auto dot = [&](const Vec3& w) {
          return _mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_set1_pd(w[0]), offset_k[0]),
                                       _mm_mul_pd(_mm_set1_pd(w[1]), offset_k[1])),
                            _mm_mul_pd(_mm_set1_pd(w[2]), offset_k[2]));
        };
        const __m128d sk = dot(plane), xk = dot(normal), yk = dot(binormal);
        _mm_storel_pd(&s[2 * pair][k], sk);
        _mm_storeh_pd(&s[2 * pair + 1][k], sk);
        _mm_storel_pd(&x[2 * pair][k], xk);
        _mm_storeh_pd(&x[2 * pair + 1][k], xk);
        _mm_storel_pd(&y[2 * pair][k], yk);
        _mm_storeh_pd(&y[2 * pair + 1][k], yk);
      }
    }
#else
    for (int slot = 0; slot < 4; ++slot) {
      for (int k = 0; k < 3; ++k) {
        for (int a = 0; a < 3; ++a)
          d[slot][k][a] = vertices[18 * (slot / 2) + 6 * k + 2 * a + slot % 2] - origin[a];
        const double* o = d[slot][k];
        s[slot][k] = plane[0] * o[0] + plane[1] * o[1] + plane[2] * o[2];
        x[slot][k] = normal[0] * o[0] + normal[1] * o[1] + normal[2] * o[2];
        y[slot][k] = binormal[0] * o[0] + binormal[1] * o[1] + binormal[2] * o[2];
      }
    }
#endif
    for (int slot = 0; slot < 4; ++slot) {
      if (slot > 0 && ids[slot] == ids[slot - 1]) break;  // a short leaf repeats its last
      const double* t = s[slot];
      if ((t[0] > slab && t[1] > slab && t[2] > slab) ||
          (t[0] < -slab && t[1] < -slab && t[2] < -slab))
        continue;
      const bool clear = std::abs(t[0]) > slab && std::abs(t[1]) > slab && std::abs(t[2]) > slab;
      if (!clear || !cut_segment(x[slot], y[slot], t, d[slot], ids[slot]))
        clipped(x[slot], y[slot], t, d[slot], ids[slot]);
    }
  }

  for (std::size_t j = 0; j < n; ++j) {
    if (hit_triangle[j] == kIndexMask) continue;
    RayHit hit;
    hit.t = best[j];
    hit.triangle = hit_triangle[j];
    hit.u = hit_v[j] / hit_det[j];
    hit.v = hit_w[j] / hit_det[j];
    const Triangle& tri = triangles_[hit.triangle];
    const Vec3 &a = positions_[tri[0]], &b = positions_[tri[1]], &c = positions_[tri[2]];
    hit.point = a + hit.u * (b - a) + hit.v * (c - a);
    hits[j] = hit;
  }
}

}  // namespace wirerig
