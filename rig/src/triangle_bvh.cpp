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

#include "triangle_bvh_shared.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace wirerig {
namespace {

using namespace bvh_shared;

constexpr int kBins = 12;
constexpr std::uint32_t kMaxLeafSize = 4;
constexpr int kMaxSahDepth = 48;
// Deepest possible node: kMaxSahDepth SAH levels, then median splits of < 2^31 triangles.
static_assert(kStackSize == kMaxSahDepth + 40, "kStackSize (triangle_bvh_shared.h) is the depth");
constexpr double kBoxPad = 1e-12;
// Relative widening of a box's exit distance: covers the rounding of the slab test (pbrt's
// 1 + 2 gamma(3), with room to spare).
constexpr double kSlabSlack = 8.0 * kEps;

// Ray tree (see TriangleBvh::RayNode). Float boxes are in unit coordinates, so every box lies
// within [-1.01, 1.01]^3; the ray's start point is moved into the root box and its direction
// scaled by a power of two so its largest component is in [1, 2), which bounds every float
// slab distance of a relevant box by a few units.
static_assert(kMaxLeafSize <= 4, "ray leaves have 4 triangle slots");
constexpr float kEmptyBox = 1024.0f;  // unused child slots: the box [1024, -1024], never hit
// Relative widening of the float exit distance: covers the three roundings of a float slab
// distance (difference, reciprocal, product) many times over.
constexpr float kFloatSlack = 1.0f / 262144.0f;  // 2^-18
// Minimum padding of the ray's start point, in units: covers the rounding of the start point
// to float and of the float offsets start -+ pad.
constexpr double kUnitPad = 1.0 / 262144.0;  // 2^-18
// Beyond this (in units) the double-precision errors of placing a ray in unit coordinates are
// too large to bound boxes tightly: such a ray (its origin ~2^35 scene sizes away) tests
// every box, with exact double-precision triangle tests as always.
constexpr double kCoarseLimit = 1.0 / 4096.0;
// Largest float reciprocal direction component: smaller components are treated as this
// (their slab distances only grow, see Raycast).
constexpr float kMaxInverse = 1073741824.0f;  // 2^30

// The exponent e of a normal, positive x = m 2^e, m in [1, 2).
inline int Exponent(double x) {
  return static_cast<int>((std::bit_cast<std::uint64_t>(x) >> 52) & 0x7ff) - 1023;
}

// x rounded to a float, downwards or upwards; |x| must be below the float range's limit.
inline float FloatDown(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -kEmptyBox * 2.0f);
  return f;
}
inline float FloatUp(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, kEmptyBox * 2.0f);
  return f;
}

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

#if !defined(__SSE2__)
// 2D cross product p x q, exactly antisymmetric in its arguments whatever the compiler's
// contraction of a*b - c*d into an FMA: the pair is always evaluated in lexicographic order.
// (The scalar path's; with SSE2, bvh_shared::EdgePair.)
inline double Edge(const double* p, const double* q) {
  if (p[0] < q[0] || (p[0] == q[0] && p[1] < q[1])) return p[0] * q[1] - p[1] * q[0];
  if (p[0] == q[0] && p[1] == q[1]) return 0.0;
  return -(q[0] * p[1] - q[1] * p[0]);
}
#endif

// Per-ray constants for the slab test and the watertight triangle test.
struct Ray {
  double o[3];
  double inv[3];      // reciprocal direction, +-1/kTinyDirection for (near) zero components
  int kx, ky, kz;     // kz: the axis of largest |direction|
  double sx, sy, sz;  // shear and scale into the ray frame
  double t_min;

  // Vertex in the ray frame: (x, y) relative to the ray, z = distance along it.
  void Transform(const double* p, double* out) const {
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
  bvh.BuildRayTree();
  return bvh;
}

void TriangleBvh::BuildRayTree() {
  // Unit coordinates: centred on the root box, scaled by a power of two >= its half extent.
  const Node& root = nodes_[0];
  double half = 0.0;
  for (int a = 0; a < 3; ++a) {
    unit_centre_[a] = 0.5 * (root.min[a] + root.max[a]);
    half = std::max(half, 0.5 * (root.max[a] - root.min[a]));
  }
  int exponent = 0;
  std::frexp(half, &exponent);  // half < 2^exponent (0 for half == 0)
  unit_exponent_ = std::clamp(exponent, -600, 200);
  const double to_unit = PowerOfTwo(-unit_exponent_);
  // Rounding errors (in units) of a ray starting within a unit of the centre: see Raycast.
  double centre = 0.0;
  for (int a = 0; a < 3; ++a) centre = std::max(centre, std::abs(unit_centre_[a]));
  inside_error_ = (centre * to_unit + 2.0) * 0x1p-47;

  auto half_area = [](const Node& n) {
    const Vec3 e = n.max - n.min;
    return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
  };
  // Each 4-wide node takes a binary node's children, then repeatedly replaces the inner child
  // of largest area by its two children while it has fewer than 4 (ties: the first one).
  struct Item {
    std::uint32_t node;    // binary node
    std::uint32_t parent;  // 4-wide node whose child it becomes, and the slot there
    int slot;
  };
  std::vector<Item> stack;
  ray_nodes_.reserve(nodes_.size() / 2 + 1);
  ray_vertices_.reserve(36 * (order_.size() / 2 + 1));
  ray_triangles_.reserve(4 * (order_.size() / 2 + 1));
  stack.push_back({0, 0, -1});
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const auto index = static_cast<std::uint32_t>(ray_nodes_.size());
    ray_nodes_.push_back(RayNode{});
    if (item.slot >= 0) ray_nodes_[item.parent].child[item.slot] = index;
    std::uint32_t children[kRayWidth];
    int n = 0;
    if (nodes_[item.node].count > 0) {
      children[n++] = item.node;  // a leaf root: a single child
    } else {
      children[n++] = nodes_[item.node].first;
      children[n++] = nodes_[item.node].first + 1;
      while (n < kRayWidth) {
        int best = -1;
        double best_area = -1.0;
        for (int k = 0; k < n; ++k) {
          const Node& c = nodes_[children[k]];
          if (c.count == 0 && half_area(c) > best_area) {
            best = k;
            best_area = half_area(c);
          }
        }
        if (best < 0) break;
        const std::uint32_t left = nodes_[children[best]].first;
        for (int k = n; k > best + 1; --k) children[k] = children[k - 1];
        children[best] = left;
        children[best + 1] = left + 1;
        ++n;
      }
    }
    RayNode& node = ray_nodes_[index];
    for (int k = 0; k < kRayWidth; ++k) {
      for (int a = 0; a < 3; ++a) {
        node.box[a][k] = kEmptyBox;
        node.box[3 + a][k] = -kEmptyBox;
      }
      node.child[k] = kLeafRef;
    }
    for (int k = 0; k < n; ++k) {
      const Node& c = nodes_[children[k]];
      std::uint32_t ids[4];
      std::uint32_t m = 0;
      if (c.count > 0) {
        for (std::uint32_t i = c.first; i < c.first + c.count; ++i)
          if (!(order_[i] & kDegenerateBit)) ids[m++] = order_[i];
        if (m == 0) continue;  // only degenerate triangles: an empty slot
      }
      for (int a = 0; a < 3; ++a) {
        node.box[a][k] = FloatDown((c.min[a] - unit_centre_[a]) * to_unit);
        node.box[3 + a][k] = FloatUp((c.max[a] - unit_centre_[a]) * to_unit);
      }
      if (c.count == 0) continue;  // inner: its index is filled in when it is processed
      node.child[k] = kLeafRef | static_cast<std::uint32_t>(ray_triangles_.size() / 4);
      for (; m < 4; ++m) ids[m] = ids[m - 1];  // repeat the last: same hit, same result
      for (std::uint32_t pair = 0; pair < 2; ++pair)
        for (int v = 0; v < 3; ++v)
          for (int a = 0; a < 3; ++a)
            for (std::uint32_t lane = 0; lane < 2; ++lane)
              ray_vertices_.push_back(positions_[triangles_[ids[2 * pair + lane]][v]][a]);
      for (std::uint32_t slot = 0; slot < 4; ++slot) ray_triangles_.push_back(ids[slot]);
    }
    for (int k = n - 1; k >= 0; --k)
      if (nodes_[children[k]].count == 0) stack.push_back({children[k], index, k});
  }
}

std::optional<RayHit> TriangleBvh::Raycast(const Vec3& origin, const Vec3& direction, double t_min,
                                           double t_max) const {
  if (nodes_.empty()) return std::nullopt;
  Ray ray;
  {
    const double x = std::abs(direction[0]), y = std::abs(direction[1]), z = std::abs(direction[2]);
    ray.kz = z > std::max(x, y) ? 2 : y > x ? 1 : 0;  // the first largest (NaN: 0)
  }
  // Also rejects NaN directions and a NaN t_min.
  if (!(std::abs(direction[ray.kz]) >= kTinyDirection)) return std::nullopt;
  double best = std::min(t_max, kMaxT);
  if (!(t_min < best)) return std::nullopt;
  ray.t_min = t_min;
  ray.kx = ray.kz == 2 ? 0 : ray.kz + 1;
  ray.ky = ray.kx == 2 ? 0 : ray.kx + 1;
  ray.sz = 1.0 / direction[ray.kz];
  ray.sx = direction[ray.kx] * ray.sz;
  ray.sy = direction[ray.ky] * ray.sz;
  for (int a = 0; a < 3; ++a) ray.o[a] = origin[a];

  // The ray in unit coordinates, in float: start point s = (origin + t0 direction - centre) /
  // unit, direction direction / 2^e (largest component in [1, 2)), parameter
  // u = (t - t0) 2^e / unit. Boxes are tested against the start point displaced by +-pad
  // towards the box (the box grown by pad), which covers every rounding of the start point,
  // of t0 * direction and of the boxes' offsets from the centre (`error` bounds them all); the
  // float slab distances then only carry relative errors, covered by kFloatSlack. Within the
  // root box |s| <= 1 and |u| <= 2.1. t0 is 0 when the origin is within a unit of the centre,
  // else where the ray enters the root box (tested in double precision), t_min at the latest.
  const int exponent = Exponent(std::abs(direction[ray.kz]));
  const double to_unit = PowerOfTwo(-unit_exponent_);
  const double down = PowerOfTwo(-exponent), scale = PowerOfTwo(exponent - unit_exponent_);
  const double limit = PowerOfTwo(unit_exponent_ - exponent + 3);  // u(t0 + limit) = 8
  double start[3], t0 = 0.0, error = inside_error_, u_min = 0.0;
  bool inside = true;
  for (int a = 0; a < 3; ++a) {
    start[a] = (origin[a] - unit_centre_[a]) * to_unit;
    inside = inside && std::abs(start[a]) <= 1.0;
  }
  if (inside) {
    u_min = t_min < -limit ? -8.0 : t_min > limit ? 8.0 : t_min * scale;
  } else {
    for (int a = 0; a < 3; ++a)
      ray.inv[a] = std::abs(direction[a]) >= kTinyDirection
                       ? 1.0 / direction[a]
                       : std::copysign(1.0 / kTinyDirection, direction[a]);
    if (!HitBox(nodes_[0].min, nodes_[0].max, ray, best, t0)) return std::nullopt;
    // |t0 direction| is below |origin| + |centre| + unit where the root box is hit.
    double magnitude = 0.0;
    for (int a = 0; a < 3; ++a) {
      magnitude = std::max({magnitude, std::abs(origin[a]), std::abs(unit_centre_[a])});
      start[a] =
          std::clamp(((origin[a] + t0 * direction[a]) - unit_centre_[a]) * to_unit, -2.0, 2.0);
    }
    error = (magnitude * to_unit + 1.0) * 0x1p-47;
  }
  const bool coarse = !(error <= kCoarseLimit);
  // Coarse: a pad of 16 units puts the start point in every (grown) box for any u in
  // [-64, 64], which holds every box's slab range.
  const float pad = coarse ? 16.0f : static_cast<float>(kUnitPad + 2.0 * error);
  const float u_lo = coarse ? -64.0f : static_cast<float>(u_min) - 2.0f * pad;
  // u(t), widened, clamped to [-8, 8]; the limit keeps (t - t0) * scale from overflowing.
  auto upper = [&](double t) {
    if (coarse) return 64.0f;
    if (!(t - t0 < limit)) return 8.0f;
    const double u = std::max((t - t0) * scale, -8.0);
    return static_cast<float>(u) * (1.0f + kFloatSlack) + 2.0f * pad;
  };
  float u_hi = upper(best);
  // Exit distances use the reciprocal widened by kFloatSlack (u_hi already is).
  float near_offset[3], far_offset[3], inverse[3], far_inverse[3];
  int near_row[3], far_row[3];
  for (int a = 0; a < 3; ++a) {
    const auto s = static_cast<float>(start[a]);
    const auto d = static_cast<float>(direction[a] * down);
    // Components below 2^-30 move the ray by less than 2^-29 units over |u| <= 2.1, far less
    // than the pad: treating them as 2^-30 (with their sign) can only shrink slab distances'
    // magnitudes where the start point is outside the grown slab, and puts every relevant u
    // inside it where the start point is inside.
    inverse[a] = std::copysign(1.0f / std::max(std::abs(d), 1.0f / kMaxInverse), d);
    far_inverse[a] = inverse[a] * (1.0f + kFloatSlack);
    const int negative = inverse[a] < 0.0f;
    near_row[a] = a + 3 * negative;
    far_row[a] = a + 3 - 3 * negative;
    near_offset[a] = s + std::copysign(pad, inverse[a]);
    far_offset[a] = s - std::copysign(pad, inverse[a]);
  }

  RayHit hit;
  bool found = false;
  struct Entry {
    std::uint32_t ref;
    float u;
  };
  // Each level pushes at most kRayWidth - 1 entries.
  Entry stack[(kRayWidth - 1) * kStackSize];
  int top = 0;
  std::uint32_t current = 0;
#if defined(__SSE2__)
  const __m128 near_off[3] = {_mm_set1_ps(near_offset[0]), _mm_set1_ps(near_offset[1]),
                              _mm_set1_ps(near_offset[2])};
  const __m128 far_off[3] = {_mm_set1_ps(far_offset[0]), _mm_set1_ps(far_offset[1]),
                             _mm_set1_ps(far_offset[2])};
  const __m128 inv[3] = {_mm_set1_ps(inverse[0]), _mm_set1_ps(inverse[1]), _mm_set1_ps(inverse[2])};
  const __m128 far_inv[3] = {_mm_set1_ps(far_inverse[0]), _mm_set1_ps(far_inverse[1]),
                             _mm_set1_ps(far_inverse[2])};
  const __m128 lo_v = _mm_set1_ps(u_lo);
  const __m128d okx = _mm_set1_pd(origin[ray.kx]), oky = _mm_set1_pd(origin[ray.ky]),
                okz = _mm_set1_pd(origin[ray.kz]);
  const __m128d vsx = _mm_set1_pd(ray.sx), vsy = _mm_set1_pd(ray.sy), vsz = _mm_set1_pd(ray.sz);
#endif
  for (;;) {
    if (!(current & kLeafRef)) {
      const RayNode& node = ray_nodes_[current];
      alignas(16) float entry[kRayWidth];
      unsigned mask = 0;
#if defined(__SSE2__)
      const __m128 hi_v = _mm_set1_ps(u_hi);
      for (int g = 0; g < kRayWidth; g += 4) {
        __m128 t_near[3], t_far[3];
        for (int a = 0; a < 3; ++a) {
          t_near[a] =
              _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.box[near_row[a]] + g), near_off[a]), inv[a]);
          t_far[a] =
              _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.box[far_row[a]] + g), far_off[a]), far_inv[a]);
        }
        // Balanced, for a short dependency chain.
        const __m128 tn = _mm_max_ps(_mm_max_ps(t_near[0], t_near[1]), _mm_max_ps(t_near[2], lo_v));
        const __m128 tf = _mm_min_ps(_mm_min_ps(t_far[0], t_far[1]), _mm_min_ps(t_far[2], hi_v));
        mask |= static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(tn, tf))) << g;
        _mm_store_ps(entry + g, tn);
      }
#else
      for (int k = 0; k < kRayWidth; ++k) {
        float tn = u_lo, tf = u_hi;
        for (int a = 0; a < 3; ++a) {
          tn = std::max(tn, (node.box[near_row[a]][k] - near_offset[a]) * inverse[a]);
          tf = std::min(tf, (node.box[far_row[a]][k] - far_offset[a]) * far_inverse[a]);
        }
        entry[k] = tn;
        if (tn <= tf) mask |= 1u << k;
      }
#endif
      if (mask != 0) {
        // Visit the hit children nearest first: push the others, farthest first.
        const int k0 = std::countr_zero(mask);
        const unsigned rest = mask & (mask - 1);
        if (rest == 0) {
          current = node.child[k0];
          continue;
        }
        if ((rest & (rest - 1)) == 0) {
          const int k1 = std::countr_zero(rest);
          const bool swap = entry[k1] < entry[k0];
          const int near = swap ? k1 : k0, far = swap ? k0 : k1;
          assert(top < (kRayWidth - 1) * kStackSize);
          stack[top++] = Entry{node.child[far], entry[far]};
          current = node.child[near];
          continue;
        }
        int order[kRayWidth];
        int n = 0;
        for (; mask != 0; mask &= mask - 1) {
          const int k = std::countr_zero(mask);
          int j = n++;
          for (; j > 0 && entry[order[j - 1]] < entry[k]; --j) order[j] = order[j - 1];
          order[j] = k;
        }
        for (int j = 0; j + 1 < n; ++j) {
          assert(top < (kRayWidth - 1) * kStackSize);
          stack[top++] = Entry{node.child[order[j]], entry[order[j]]};
        }
        current = node.child[order[n - 1]];
        continue;
      }
    } else {
      const std::size_t leaf = current & ~kLeafRef;
      const double* vertices = &ray_vertices_[36 * leaf];
      alignas(16) double edge[3][4], depth[3][4];
      unsigned pass = 0;
#if defined(__SSE2__)
      for (int pair = 0; pair < 2; ++pair) {
        __m128d x[3], y[3], z[3];
        for (int k = 0; k < 3; ++k) {
          const double* vertex = vertices + 18 * pair + 6 * k;
          const __m128d pz = _mm_sub_pd(_mm_load_pd(vertex + 2 * ray.kz), okz);
          x[k] = _mm_sub_pd(_mm_sub_pd(_mm_load_pd(vertex + 2 * ray.kx), okx), _mm_mul_pd(vsx, pz));
          y[k] = _mm_sub_pd(_mm_sub_pd(_mm_load_pd(vertex + 2 * ray.ky), oky), _mm_mul_pd(vsy, pz));
          z[k] = _mm_mul_pd(vsz, pz);
        }
        const __m128d e0 = bvh_shared::EdgePair(x[1], y[1], x[2], y[2]);  // u = Edge(b, c)
        const __m128d e1 = bvh_shared::EdgePair(x[2], y[2], x[0], y[0]);  // v = Edge(c, a)
        const __m128d e2 = bvh_shared::EdgePair(x[0], y[0], x[1], y[1]);  // w = Edge(a, b)
        // Missed: some edge function negative and some positive.
        const __m128d zero = _mm_setzero_pd();
        const __m128d lowest = _mm_min_pd(_mm_min_pd(e0, e1), e2);
        const __m128d highest = _mm_max_pd(_mm_max_pd(e0, e1), e2);
        const __m128d missed = _mm_and_pd(_mm_cmplt_pd(lowest, zero), _mm_cmpgt_pd(highest, zero));
        pass |= (~static_cast<unsigned>(_mm_movemask_pd(missed)) & 3u) << (2 * pair);
        _mm_store_pd(edge[0] + 2 * pair, e0);
        _mm_store_pd(edge[1] + 2 * pair, e1);
        _mm_store_pd(edge[2] + 2 * pair, e2);
        for (int k = 0; k < 3; ++k) _mm_store_pd(depth[k] + 2 * pair, z[k]);
      }
#else
      for (int slot = 0; slot < 4; ++slot) {
        double p[3][3];
        for (int k = 0; k < 3; ++k) {
          double vertex[3];
          for (int a = 0; a < 3; ++a)
            vertex[a] = vertices[18 * (slot / 2) + 6 * k + 2 * a + slot % 2];
          ray.Transform(vertex, p[k]);
          depth[k][slot] = p[k][2];
        }
        edge[0][slot] = Edge(p[1], p[2]);
        edge[1][slot] = Edge(p[2], p[0]);
        edge[2][slot] = Edge(p[0], p[1]);
        const double u = edge[0][slot], v = edge[1][slot], w = edge[2][slot];
        if (!((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)))
          pass |= 1u << slot;
      }
#endif
      // The slots in order, as a sequence of single triangle tests.
      for (; pass != 0; pass &= pass - 1) {
        const int slot = std::countr_zero(pass);
        const double u = edge[0][slot], v = edge[1][slot], w = edge[2][slot];
        const double det = u + v + w;
        const double scaled_t = u * depth[0][slot] + v * depth[1][slot] + w * depth[2][slot];
        // det == 0 (ray in the triangle's plane) fails too; otherwise |t| <= 1e300.
        if (!(std::abs(det) > std::abs(scaled_t) * 1e-300)) continue;
        const double t = scaled_t / det;
        if (!(t > t_min && t <= best)) continue;
        best = t;
        found = true;
        hit.t = t;
        hit.triangle = ray_triangles_[4 * leaf + slot];
        hit.u = v / det;
        hit.v = w / det;
        u_hi = upper(t);
      }
    }
    // Pop the next subtree that can still hold a nearer hit.
    bool next = false;
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.u <= u_hi) {
        current = e.ref;
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
