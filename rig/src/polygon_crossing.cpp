// PolygonCrossesItself: a sweep over the edges' bounding boxes. The boxes are sorted by a
// monotone key of their lower x (the double's order-preserving bits with the low bits replaced
// by the edge index), so the sweep visits every pair whose boxes overlap in x: for box a, the
// boxes after it while their key's high bits do not exceed those of a's upper x. Each visited
// pair gets the exact box overlap test, then the crossing test; the answer is therefore the
// same as for any enumeration of the overlapping pairs.
#include "wirerig/rig/polygon_crossing.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>

namespace wirerig {
namespace {

// Orientation of r relative to the line pq: > 0 to the left.
inline double Orient(double px, double py, double qx, double qy, double rx, double ry) {
  return (qx - px) * (ry - py) - (qy - py) * (rx - px);
}

// Strictly opposite signs.
inline bool Straddles(double s0, double s1) {
  return (s0 > 0.0 && s1 < 0.0) || (s0 < 0.0 && s1 > 0.0);
}

// Bits of x ordered as x is (-0 and +0 alike): x <= y implies Ordered(x) <= Ordered(y).
inline std::uint64_t Ordered(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x + 0.0);
  return (bits >> 63) != 0 ? ~bits : bits | (std::uint64_t{1} << 63);
}

// Sorts distinct keys: a natural merge sort (runs found, descending ones reversed, then merged
// pairwise), O(n log runs). The boxes' lower x along a profile loop rises and falls a few
// times, so its keys come in a few long runs and this is close to linear.
void SortKeys(std::vector<std::uint64_t>& keys, std::vector<std::uint64_t>& buffer,
              std::vector<std::size_t>& runs) {
  const std::size_t n = keys.size();
  runs.clear();
  for (std::size_t i = 0; i < n;) {
    runs.push_back(i);
    std::size_t j = i + 1;
    if (j < n && keys[j] < keys[i]) {
      while (j < n && keys[j] < keys[j - 1]) ++j;
      std::reverse(keys.begin() + i, keys.begin() + j);
    } else {
      while (j < n && keys[j] > keys[j - 1]) ++j;
    }
    i = j;
  }
  runs.push_back(n);
  buffer.resize(n);
  while (runs.size() > 2) {
    std::size_t kept = 0;
    for (std::size_t r = 0; r + 1 < runs.size(); r += 2) {
      const std::size_t begin = runs[r], middle = runs[r + 1];
      const std::size_t end = r + 2 < runs.size() ? runs[r + 2] : middle;
      std::merge(keys.begin() + begin, keys.begin() + middle, keys.begin() + middle,
                 keys.begin() + end, buffer.begin() + begin);
      runs[kept++] = begin;
    }
    runs[kept++] = n;
    runs.resize(kept);
    keys.swap(buffer);
  }
}

// Whether the closed loop through the n points turns strictly one way around (0, 0), each step
// by less than a half-turn, and goes round exactly once: then every edge lies in its own wedge
// from (0, 0), wedges of non-adjacent edges meet at (0, 0) only, which no edge reaches, so no
// two edges cross (exactly, not only as rounded; the polygon is star-shaped around (0, 0)). A
// path's edges are some of its loop's, so the same holds for an open polygon. A turn counts
// only when its cross product clears its rounding error, so a true answer is exact.
bool TurnsOnceAroundTheOrigin(const double* x, const double* y, std::size_t n) {
  constexpr double kRounding = 1e-12;  // relative; the cross product's rounding is ~1e-16
  double sign = 0.0;
  std::size_t windings = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = i + 1 == n ? 0 : i + 1;
    const double cross = x[i] * y[j] - y[i] * x[j];
    const double scale = std::abs(x[i] * y[j]) + std::abs(y[i] * x[j]);
    if (sign == 0.0) sign = cross > 0.0 ? 1.0 : -1.0;
    if (!(sign * cross > kRounding * scale)) return false;
    // Turning counter-clockwise by less than a half-turn, the loop enters y >= 0 from y < 0
    // only through the positive x-axis: once per turn (mirrored for clockwise).
    windings += sign * y[i] < 0.0 && sign * y[j] >= 0.0;
  }
  return windings == 1;
}

}  // namespace

bool PolygonCrossesItself(std::span<const double> xs, std::span<const double> ys, bool closed,
                          PolygonCrossingScratch& scratch) {
  assert(xs.size() == ys.size());
  const std::size_t n = std::min(xs.size(), ys.size());
  if (n < 4) return false;
  scratch.x.resize(n + 1);
  scratch.y.resize(n + 1);
  double* x = scratch.x.data();
  double* y = scratch.y.data();
  double size = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = xs[i];
    y[i] = ys[i];
    size = std::max({size, std::abs(x[i]), std::abs(y[i])});
  }
  x[n] = x[0];  // edge n - 1 of a closed polygon ends at vertex 0
  y[n] = y[0];
  // The common case for a profile (points on rays around the origin, in order): no sweep.
  if (TurnsOnceAroundTheOrigin(x, y, n)) return false;
  const std::size_t edges = closed ? n : n - 1;
  const double pad = 1e-9 * size;
  // box[4 i ..]: edge i's x0, x1, y0, y1.
  scratch.box.resize(4 * edges);
  scratch.keys.resize(edges);
  double* box = scratch.box.data();
  const int shift = static_cast<int>(std::bit_width(edges));  // low bits of a key: its edge
  const std::uint64_t edge_mask = (std::uint64_t{1} << shift) - 1;
  for (std::size_t i = 0; i < edges; ++i) {
    box[4 * i] = std::min(x[i], x[i + 1]) - pad;
    box[4 * i + 1] = std::max(x[i], x[i + 1]) + pad;
    box[4 * i + 2] = std::min(y[i], y[i + 1]) - pad;
    box[4 * i + 3] = std::max(y[i], y[i + 1]) + pad;
    scratch.keys[i] = (Ordered(box[4 * i]) >> shift << shift) | i;
  }
  SortKeys(scratch.keys, scratch.buffer, scratch.runs);
  // Edges i < j, j >= i + 2, but not edge n - 1 with edge 0 (adjacent through the seam): each
  // edge's endpoints strictly on opposite sides of the other's line.
  auto crosses = [&](std::size_t i, std::size_t j) {
    if (j < i + 2 || (closed && i == 0 && j == n - 1)) return false;
    const double ax = x[i], ay = y[i], bx = x[i + 1], by = y[i + 1];
    if (!Straddles(Orient(ax, ay, bx, by, x[j], y[j]), Orient(ax, ay, bx, by, x[j + 1], y[j + 1])))
      return false;
    const double o3 = Orient(x[j], y[j], x[j + 1], y[j + 1], ax, ay);
    const double o4 = Orient(x[j], y[j], x[j + 1], y[j + 1], bx, by);
    return ((o3 > 0.0) != (o4 > 0.0)) && o3 != 0.0 && o4 != 0.0;
  };
  // The boxes in sorted order, with their keys' high bits, for a sequential inner loop.
  scratch.sorted.resize(5 * edges);
  double* sorted = scratch.sorted.data();
  std::uint64_t* keys = scratch.keys.data();
  for (std::size_t p = 0; p < edges; ++p) {
    const std::size_t a = keys[p] & edge_mask;
    for (int c = 0; c < 4; ++c) sorted[5 * p + c] = box[4 * a + c];
    sorted[5 * p + 4] = static_cast<double>(a);
    keys[p] >>= shift;
  }
  // Adjacent edges (index gap 1, or n - 1 through a closed polygon's seam) never cross: they
  // are skipped with the box test, so that its one branch is rarely taken.
  const double seam_gap = closed ? static_cast<double>(n - 1) : -1.0;
  for (std::size_t p = 0; p < edges; ++p) {
    const double* ba = sorted + 5 * p;
    const std::uint64_t limit = Ordered(ba[1]) >> shift;
    for (std::size_t q = p + 1; q < edges && keys[q] <= limit; ++q) {
      const double* bb = sorted + 5 * q;
      const double gap = std::abs(ba[4] - bb[4]);
      if ((bb[0] <= ba[1]) & (ba[0] <= bb[1]) & (bb[2] <= ba[3]) & (ba[2] <= bb[3]) & (gap != 1.0) &
          (gap != seam_gap)) {
        const auto a = static_cast<std::size_t>(ba[4]), b = static_cast<std::size_t>(bb[4]);
        if (crosses(std::min(a, b), std::max(a, b))) return true;
      }
    }
  }
  return false;
}

}  // namespace wirerig
