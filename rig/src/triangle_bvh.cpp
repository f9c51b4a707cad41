// TriangleBvh: binned-SAH bounding volume hierarchy with watertight ray casting and
// branch-and-bound closest points; WindingNumber: the generalised winding number.
//
// Build. Triangles are binned by centroid into kBins bins per axis; the split with the least
// surface-area cost (area_left * n_left + area_right * n_right) over all three axes wins, ties
// going to the lower axis and bin. Nodes with more than kMaxLeafSize triangles are always split,
// so leaves hold 1..4 triangles. From depth kMaxSahDepth on (and when no centroid extent is left)
// the split is at the median, which bounds the depth by kMaxSahDepth + 31 and hence the fixed
// query stacks. Everything is sequential and uses no hashing or pointers as keys: deterministic.
// Node boxes are padded by a relative 1e-12 so rays lying in a box's face plane, and rounding
// in the slab test, never lose a triangle that touches the box boundary.
//
// Ray casting. Slab test against precomputed reciprocal directions; a zero or tiny (< 1e-150)
// direction component uses +-1e150 instead of 1/0, which keeps every product finite while still
// excluding slabs the ray misses. Triangles use the watertight test of Woop, Benthin and Wald
// (JCGT 2013): vertices are moved into a frame where the ray is the +z axis, and the 2D edge
// functions decide the hit. Each edge function is evaluated with its endpoints in a canonical
// (lexicographic) order and negated if needed, so the two triangles sharing an edge compute
// exactly opposite values even under FMA contraction: a ray through a shared edge or vertex
// hits at least one of the triangles around it. The division for t is done only once it cannot
// overflow. Hits with t beyond 1e300 are ignored (t_max is clamped there).
//
// Closest point. Depth-first branch and bound, nearer child (by squared box distance) first,
// Ericson's ClosestPtPointTriangle per triangle with guarded divisions (segment fallback for
// degenerate triangles).
//
// Inputs must be finite with coordinates below 1e50 in magnitude; a ray direction whose largest
// component is below 1e-150 in magnitude hits nothing.
#include "wirerig/rig/triangle_bvh.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

namespace wirerig {
namespace {

constexpr int kBins = 12;
constexpr std::uint32_t kMaxLeafSize = 4;
constexpr int kMaxSahDepth = 48;
// Deepest possible node: kMaxSahDepth SAH levels, then median splits of < 2^31 triangles.
constexpr int kStackSize = kMaxSahDepth + 40;
// order_ entries carry this bit for triangles too thin to hit (see IsDegenerate).
constexpr std::uint32_t kDegenerateBit = 0x80000000u;
constexpr std::uint32_t kIndexMask = ~kDegenerateBit;
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kHuge = std::numeric_limits<double>::max();
constexpr double kMaxT = 1e300;
constexpr double kTinyDirection = 1e-150;
constexpr double kBoxPad = 1e-12;
// Relative widening of a box's exit distance: covers the rounding of the slab test (pbrt's
// 1 + 2 gamma(3), with room to spare).
constexpr double kSlabSlack = 8.0 * kEps;

// Branch-free minimum and maximum (std::min/max return references, which GCC tends to
// compile into unpredictable branches in the binning loop).
inline double Min(double a, double b) { return b < a ? b : a; }
inline double Max(double a, double b) { return a < b ? b : a; }

// A triangle with (almost) collinear vertices: sin(angle at a) below 64 ulp. Its plane and
// hit distance are meaningless, so rays never hit it.
bool IsDegenerate(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const double limit = 64.0 * kEps;
  return e1.cross(e2).squaredNorm() <= limit * limit * e1.squaredNorm() * e2.squaredNorm();
}

// Build record: a triangle's bounds and centroid, and its index (with kDegenerateBit).
struct Prim {
  double lo[3], hi[3], c[3];
  std::uint32_t index;
};

struct Bin {
  double lo[3] = {kHuge, kHuge, kHuge};
  double hi[3] = {-kHuge, -kHuge, -kHuge};
  std::uint32_t count = 0;

  void Grow(const double* plo, const double* phi) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = Min(lo[a], plo[a]);
      hi[a] = Max(hi[a], phi[a]);
    }
  }
  void Grow(const Bin& other) {
    Grow(other.lo, other.hi);
    count += other.count;
  }
  // Half the surface area; only meaningful when count > 0.
  double HalfArea() const {
    const double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return dx * dy + dy * dz + dz * dx;
  }
};

// Bins centroids along one axis: index in [0, kBins).
struct Binner {
  double origin = 0.0, scale = 0.0;
  bool usable = false;

  Binner(double lo, double hi) {
    const double extent = hi - lo;
    // A vanishing extent cannot be binned (and kBins / extent could overflow).
    usable = extent > 1e-280 && extent > 1e-14 * std::max(std::abs(lo), std::abs(hi));
    if (usable) {
      origin = lo;
      scale = kBins * (1.0 - 1e-9) / extent;
    }
  }
  int operator()(double c) const {
    const int k = static_cast<int>((c - origin) * scale);
    return std::clamp(k, 0, kBins - 1);
  }
};

// Binned SAH split of prims[begin, end): returns the first prim of the right side, or `begin`
// when no axis can be binned.
std::uint32_t SahSplit(std::vector<Prim>& prims, std::uint32_t begin, std::uint32_t end,
                       const double* clo, const double* chi) {
  const Binner binners[3] = {{clo[0], chi[0]}, {clo[1], chi[1]}, {clo[2], chi[2]}};
  if (!binners[0].usable && !binners[1].usable && !binners[2].usable) return begin;

  Bin bins[3][kBins];
  for (std::uint32_t i = begin; i < end; ++i) {
    const Prim& p = prims[i];
    for (int a = 0; a < 3; ++a) {
      if (!binners[a].usable) continue;
      Bin& bin = bins[a][binners[a](p.c[a])];
      bin.Grow(p.lo, p.hi);
      ++bin.count;
    }
  }

  double best_cost = std::numeric_limits<double>::infinity();
  int best_axis = -1, best_split = -1;
  for (int a = 0; a < 3; ++a) {
    if (!binners[a].usable) continue;
    // right_cost[s]: cost of bins s+1 .. kBins-1.
    double right_cost[kBins] = {};
    Bin right;
    for (int s = kBins - 1; s > 0; --s) {
      right.Grow(bins[a][s]);
      right_cost[s - 1] = right.count > 0 ? right.HalfArea() * right.count : 0.0;
    }
    Bin left;
    std::uint32_t left_count = 0;
    for (int s = 0; s < kBins - 1; ++s) {
      left.Grow(bins[a][s]);
      left_count = left.count;
      const std::uint32_t right_count = (end - begin) - left_count;
      if (left_count == 0 || right_count == 0) continue;
      const double cost = left.HalfArea() * left_count + right_cost[s];
      if (cost < best_cost) {
        best_cost = cost;
        best_axis = a;
        best_split = s;
      }
    }
  }
  if (best_axis < 0) return begin;
  const Binner& binner = binners[best_axis];
  auto middle = std::partition(prims.begin() + begin, prims.begin() + end,
                               [&](const Prim& p) { return binner(p.c[best_axis]) <= best_split; });
  return static_cast<std::uint32_t>(middle - prims.begin());
}

// Median split along the axis of largest centroid extent (or an arbitrary halving when all
// centroids coincide).
std::uint32_t MedianSplit(std::vector<Prim>& prims, std::uint32_t begin, std::uint32_t end,
                          const double* clo, const double* chi) {
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (chi[a] - clo[a] > chi[axis] - clo[axis]) axis = a;
  const std::uint32_t middle = begin + (end - begin) / 2;
  if (chi[axis] - clo[axis] > 0.0) {
    std::nth_element(prims.begin() + begin, prims.begin() + middle, prims.begin() + end,
                     [axis](const Prim& p, const Prim& q) {
                       return p.c[axis] < q.c[axis] ||
                              (p.c[axis] == q.c[axis] && p.index < q.index);
                     });
  }
  return middle;
}

// 2D cross product p x q, exactly antisymmetric in its arguments whatever the compiler's
// contraction of a*b - c*d into an FMA: the pair is always evaluated in lexicographic order.
inline double Edge(const double* p, const double* q) {
  if (p[0] < q[0] || (p[0] == q[0] && p[1] < q[1])) return p[0] * q[1] - p[1] * q[0];
  if (p[0] == q[0] && p[1] == q[1]) return 0.0;
  return -(q[0] * p[1] - q[1] * p[0]);
}

// Per-ray constants for the slab test and the watertight triangle test.
struct Ray {
  double o[3];
  double inv[3];      // reciprocal direction, +-1/kTinyDirection for (near) zero components
  int kx, ky, kz;     // kz: the axis of largest |direction|
  double sx, sy, sz;  // shear and scale into the ray frame
  double t_min;

  // Vertex in the ray frame: (x, y) relative to the ray, z = distance along it.
  void Transform(const Vec3& p, double* out) const {
    const double px = p[kx] - o[kx], py = p[ky] - o[ky], pz = p[kz] - o[kz];
    out[0] = px - sx * pz;
    out[1] = py - sy * pz;
    out[2] = sz * pz;
  }
};

// Entry distance of the ray into the box within [t_min, t_max], or false.
inline bool HitBox(const Vec3& lo, const Vec3& hi, const Ray& ray, double t_max, double& t_entry) {
  double t0 = ray.t_min, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    const double ta = (lo[a] - ray.o[a]) * ray.inv[a];
    const double tb = (hi[a] - ray.o[a]) * ray.inv[a];
    const double far = Max(ta, tb);
    t0 = Max(t0, Min(ta, tb));
    t1 = Min(t1, far + std::abs(far) * kSlabSlack);
  }
  t_entry = t0;
  return t0 <= t1;
}

inline double BoxDistanceSquared(const Vec3& lo, const Vec3& hi, const Vec3& p) {
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double d = Max(Max(lo[a] - p[a], 0.0), p[a] - hi[a]);
    d2 += d * d;
  }
  return d2;
}

Vec3 ClosestOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double length2 = ab.squaredNorm();
  if (!(length2 > 0.0)) return a;
  const double t = std::clamp((p - a).dot(ab) / length2, 0.0, 1.0);
  return a + t * ab;
}

Vec3 ClosestOnSegments(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  Vec3 best = ClosestOnSegment(p, a, b);
  double best_d2 = (p - best).squaredNorm();
  for (const Vec3& q : {ClosestOnSegment(p, b, c), ClosestOnSegment(p, c, a)}) {
    const double d2 = (p - q).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = q;
    }
  }
  return best;
}

// Ericson, Real-Time Collision Detection, 5.1.5, with every division guarded: a zero
// denominator only happens for degenerate triangles, which fall back to their edges.
Vec3 ClosestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double denom = d1 - d3;
    if (!(denom > 0.0)) return ClosestOnSegments(p, a, b, c);
    return a + (d1 / denom) * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double denom = d2 - d6;
    if (!(denom > 0.0)) return ClosestOnSegments(p, a, b, c);
    return a + (d2 / denom) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double denom = (d4 - d3) + (d5 - d6);
    if (!(denom > 0.0)) return ClosestOnSegments(p, a, b, c);
    return b + ((d4 - d3) / denom) * (c - b);
  }
  const double denom = va + vb + vc;
  if (!(denom > 0.0)) return ClosestOnSegments(p, a, b, c);
  return a + (vb / denom) * ab + (vc / denom) * ac;
}

}  // namespace

TriangleBvh TriangleBvh::Build(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                               std::span<const std::uint32_t> subset) {
  TriangleBvh bvh;
  bvh.positions_ = positions;
  bvh.triangles_ = triangles;
  const std::size_t count = subset.empty() ? triangles.size() : subset.size();
  if (count == 0) return bvh;
  assert(count < kDegenerateBit && triangles.size() < kDegenerateBit);

  std::vector<Prim> prims(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t index = subset.empty() ? static_cast<std::uint32_t>(i) : subset[i];
    assert(index < triangles.size());
    const Triangle& t = triangles[index];
    assert(t[0] < positions.size() && t[1] < positions.size() && t[2] < positions.size());
    const Vec3 &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
    Prim& p = prims[i];
    for (int k = 0; k < 3; ++k) {
      p.lo[k] = std::min({a[k], b[k], c[k]});
      p.hi[k] = std::max({a[k], b[k], c[k]});
      p.c[k] = (a[k] + b[k] + c[k]) / 3.0;
    }
    p.index = index | (IsDegenerate(a, b, c) ? kDegenerateBit : 0u);
  }

  struct Task {
    std::uint32_t node, begin, end;
    int depth;
  };
  std::vector<Task> tasks;
  tasks.push_back({0, 0, static_cast<std::uint32_t>(count), 0});
  bvh.nodes_.reserve(2 * count);  // a binary tree with >= 1 triangle per leaf: < 2n nodes
  bvh.nodes_.push_back(Node{});
  while (!tasks.empty()) {
    const Task task = tasks.back();
    tasks.pop_back();
    double lo[3] = {kHuge, kHuge, kHuge}, hi[3] = {-kHuge, -kHuge, -kHuge};
    double clo[3] = {kHuge, kHuge, kHuge}, chi[3] = {-kHuge, -kHuge, -kHuge};
    for (std::uint32_t i = task.begin; i < task.end; ++i) {
      const Prim& p = prims[i];
      for (int a = 0; a < 3; ++a) {
        lo[a] = Min(lo[a], p.lo[a]);
        hi[a] = Max(hi[a], p.hi[a]);
        clo[a] = Min(clo[a], p.c[a]);
        chi[a] = Max(chi[a], p.c[a]);
      }
    }
    {
      Node& node = bvh.nodes_[task.node];
      double magnitude = 0.0;
      for (int a = 0; a < 3; ++a)
        magnitude = std::max({magnitude, std::abs(lo[a]), std::abs(hi[a])});
      const double pad = kBoxPad * magnitude;
      for (int a = 0; a < 3; ++a) {
        node.min[a] = lo[a] - pad;
        node.max[a] = hi[a] + pad;
      }
    }
    const std::uint32_t n = task.end - task.begin;
    if (n <= kMaxLeafSize) {
      bvh.nodes_[task.node].first = task.begin;
      bvh.nodes_[task.node].count = n;
      continue;
    }
    std::uint32_t middle = task.begin;
    if (task.depth < kMaxSahDepth) middle = SahSplit(prims, task.begin, task.end, clo, chi);
    if (middle == task.begin) middle = MedianSplit(prims, task.begin, task.end, clo, chi);
    const auto left = static_cast<std::uint32_t>(bvh.nodes_.size());
    bvh.nodes_.push_back(Node{});
    bvh.nodes_.push_back(Node{});
    bvh.nodes_[task.node].first = left;
    bvh.nodes_[task.node].count = 0;
    tasks.push_back({left + 1, middle, task.end, task.depth + 1});
    tasks.push_back({left, task.begin, middle, task.depth + 1});
  }

  bvh.order_.resize(count);
  for (std::size_t i = 0; i < count; ++i) bvh.order_[i] = prims[i].index;
  return bvh;
}

std::optional<RayHit> TriangleBvh::Raycast(const Vec3& origin, const Vec3& direction, double t_min,
                                           double t_max) const {
  if (nodes_.empty()) return std::nullopt;
  Ray ray;
  ray.kz = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(direction[a]) > std::abs(direction[ray.kz])) ray.kz = a;
  // Also rejects NaN directions and a NaN t_min.
  if (!(std::abs(direction[ray.kz]) >= kTinyDirection)) return std::nullopt;
  double best = std::min(t_max, kMaxT);
  if (!(t_min < best)) return std::nullopt;
  ray.t_min = t_min;
  ray.kx = (ray.kz + 1) % 3;
  ray.ky = (ray.kz + 2) % 3;
  ray.sz = 1.0 / direction[ray.kz];
  ray.sx = direction[ray.kx] * ray.sz;
  ray.sy = direction[ray.ky] * ray.sz;
  for (int a = 0; a < 3; ++a) {
    ray.o[a] = origin[a];
    ray.inv[a] = std::abs(direction[a]) >= kTinyDirection
                     ? 1.0 / direction[a]
                     : std::copysign(1.0 / kTinyDirection, direction[a]);
  }

  RayHit hit;
  bool found = false;
  struct Entry {
    std::uint32_t node;
    double t;
  };
  Entry stack[kStackSize];
  int top = 0;
  double t_entry = 0.0;
  if (!HitBox(nodes_[0].min, nodes_[0].max, ray, best, t_entry)) return std::nullopt;
  std::uint32_t current = 0;
  for (;;) {
    const Node& node = nodes_[current];
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        const std::uint32_t entry = order_[i];
        if (entry & kDegenerateBit) continue;
        const Triangle& tri = triangles_[entry];
        double a[3], b[3], c[3];
        ray.Transform(positions_[tri[0]], a);
        ray.Transform(positions_[tri[1]], b);
        ray.Transform(positions_[tri[2]], c);
        const double u = Edge(b, c), v = Edge(c, a), w = Edge(a, b);
        if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) continue;
        const double det = u + v + w;
        const double scaled_t = u * a[2] + v * b[2] + w * c[2];
        // det == 0 (ray in the triangle's plane) fails too; otherwise |t| <= 1e300.
        if (!(std::abs(det) > std::abs(scaled_t) * 1e-300)) continue;
        const double t = scaled_t / det;
        if (!(t > t_min && t <= best)) continue;
        best = t;
        found = true;
        hit.t = t;
        hit.triangle = entry;
        hit.u = v / det;
        hit.v = w / det;
      }
    } else {
      const std::uint32_t left = node.first, right = node.first + 1;
      double t_left = 0.0, t_right = 0.0;
      const bool hit_left = HitBox(nodes_[left].min, nodes_[left].max, ray, best, t_left);
      const bool hit_right = HitBox(nodes_[right].min, nodes_[right].max, ray, best, t_right);
      if (hit_left && hit_right) {
        const bool left_first = t_left <= t_right;
        assert(top < kStackSize);
        stack[top++] = left_first ? Entry{right, t_right} : Entry{left, t_left};
        current = left_first ? left : right;
        continue;
      }
      if (hit_left || hit_right) {
        current = hit_left ? left : right;
        continue;
      }
    }
    // Pop the next subtree that can still hold a nearer hit.
    bool next = false;
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.t <= best) {
        current = e.node;
        next = true;
        break;
      }
    }
    if (!next) break;
  }
  if (!found) return std::nullopt;
  const Triangle& tri = triangles_[hit.triangle];
  const Vec3 &a = positions_[tri[0]], &b = positions_[tri[1]], &c = positions_[tri[2]];
  hit.point = a + hit.u * (b - a) + hit.v * (c - a);
  return hit;
}

std::optional<ClosestPoint> TriangleBvh::Closest(const Vec3& point) const {
  if (nodes_.empty()) return std::nullopt;
  ClosestPoint result;
  double best_d2 = std::numeric_limits<double>::infinity();
  struct Entry {
    std::uint32_t node;
    double d2;
  };
  Entry stack[kStackSize];
  int top = 0;
  std::uint32_t current = 0;
  for (;;) {
    const Node& node = nodes_[current];
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        const std::uint32_t entry = order_[i];
        const std::uint32_t index = entry & kIndexMask;
        const Triangle& tri = triangles_[index];
        const Vec3 &a = positions_[tri[0]], &b = positions_[tri[1]], &c = positions_[tri[2]];
        const Vec3 q = (entry & kDegenerateBit) ? ClosestOnSegments(point, a, b, c)
                                                : ClosestOnTriangle(point, a, b, c);
        const double d2 = (point - q).squaredNorm();
        if (d2 < best_d2) {
          best_d2 = d2;
          result.point = q;
          result.triangle = index;
        }
      }
    } else {
      const std::uint32_t left = node.first, right = node.first + 1;
      const double d_left = BoxDistanceSquared(nodes_[left].min, nodes_[left].max, point);
      const double d_right = BoxDistanceSquared(nodes_[right].min, nodes_[right].max, point);
      const bool left_first = d_left <= d_right;
      const Entry near = left_first ? Entry{left, d_left} : Entry{right, d_right};
      const Entry far = left_first ? Entry{right, d_right} : Entry{left, d_left};
      if (near.d2 < best_d2) {
        if (far.d2 < best_d2) {
          assert(top < kStackSize);
          stack[top++] = far;
        }
        current = near.node;
        continue;
      }
    }
    bool next = false;
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.d2 < best_d2) {
        current = e.node;
        next = true;
        break;
      }
    }
    if (!next) break;
  }
  result.distance = std::sqrt(best_d2);
  return result;
}

std::size_t TriangleBvh::triangle_count() const { return order_.size(); }

double WindingNumber(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                     const Vec3& point) {
  // Van Oosterom and Strackee: tan(omega / 2) = a . (b x c) / (|a||b||c| + (a.b)|c| +
  // (b.c)|a| + (c.a)|b|), with a, b, c the vertices relative to the point. A triangle whose
  // plane passes through the point (to rounding) subtends no solid angle and is skipped; this
  // covers the point being at one of its vertices or on it, so a point on a closed surface
  // gets the fraction of directions that enter the solid (1/2 on a flat face).
  double sum = 0.0;
  for (const Triangle& t : triangles) {
    const Vec3 a = positions[t[0]] - point, b = positions[t[1]] - point,
               c = positions[t[2]] - point;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double lengths = la * lb * lc;
    if (std::abs(numerator) <= 64.0 * kEps * lengths) continue;
    const double denominator = lengths + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    sum += std::atan2(numerator, denominator);
  }
  return sum / (2.0 * std::numbers::pi);
}

}  // namespace wirerig
