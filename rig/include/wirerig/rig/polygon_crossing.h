// Whether a polygon in the plane crosses itself: the profile curves' self-intersection
// diagnostic (profile_curves.h), on the profile's points in its plane's coordinates.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace wirerig {

// Buffers reused from call to call (one per thread).
struct PolygonCrossingScratch {
  std::vector<double> x, y;                 // vertices, the first repeated at the end
  std::vector<double> box, sorted;          // edge boxes, by edge and in sweep order
  std::vector<std::uint64_t> keys, buffer;  // edges by their boxes' lower x
  std::vector<std::size_t> runs;
};

// Whether two non-adjacent edges of the polygon with vertices (x[i], y[i]) properly cross:
// each edge's endpoints strictly on opposite sides of the other's line (orientations as
// computed in double precision). Edge i joins vertices i and i + 1; a closed polygon also has
// edge n - 1 back to vertex 0 (adjacent to edge 0). Only edges whose bounding boxes overlap,
// padded by 1e-9 of the largest |coordinate|, are compared (a sweep over the boxes sorted by
// lower x): O(n log n + pairs). A polygon that turns strictly one way around (0, 0), each step
// by less than a half-turn, and goes round it once (the profile's rays, in order, from their
// origin) is star-shaped and cannot cross itself: false in O(n), with no sweep, also where
// collinear edges (a flat side) would leave the rounded orientations to chance. Fewer than 4
// vertices: false. x and y have the same size.
bool PolygonCrossesItself(std::span<const double> x, std::span<const double> y, bool closed,
                          PolygonCrossingScratch& scratch);

}  // namespace wirerig
