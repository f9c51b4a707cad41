// A watertight stand-in for meshes the curve skeleton cannot take as they are (open borders,
// non-manifold seams, many loose pieces: most game assets): CGAL's 3D alpha wrapping of the
// welded triangles, their holes first fanned shut (so the wrap does not creep into an open end
// and wrap a wall from both sides), a closed, oriented 2-manifold that encloses them (at
// `offset` outside), with no cavity or gap narrower than `alpha`.
#pragma once

#include <span>
#include <string>

#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"

namespace wirerig {

// Empty when the triangles form a closed, consistently oriented 2-manifold, else its first
// problem in words (vertex out of range, degenerate or non-finite, boundary edges, edges in three
// or more triangles, inconsistent orientation).
std::string ClosedManifoldProblem(std::span<const Vec3> positions,
                                  std::span<const Triangle> triangles);

// Why the welded mesh cannot be skeletonised as it is ("" when it is one closed, oriented
// 2-manifold piece): its first problem, in words, e.g. "the mesh is not closed: 80 boundary
// edges (...)" or "the mesh is in 18 separate pieces".
std::string WatertightProblem(const Mesh& mesh);

struct WrapOptions {
  // m; 0: the bounding box diagonal / kWrapRelativeAlpha (a limb thinner than the wrap's alpha
  // merges with its neighbour; a smaller alpha costs more time).
  double alpha = 0.0;
};
inline constexpr double kWrapRelativeAlpha = 60.0;
// The smallest alpha allowed: diagonal / this. The wrap's work grows as (diagonal / alpha)^2 to
// ^3: Wuson.off takes 1 s at the default, 14 s at diagonal / 185, and at diagonal / 740 ran over
// two minutes and half a gigabyte without finishing (a new user's trial, 2026-12-07).
inline constexpr double kWrapMostRelativeAlpha = 200.0;
inline constexpr double kWrapOffsetFraction = 1.0 / 30.0;  // offset = alpha x this

struct WatertightProxy {
  Mesh mesh;  // welded positions and triangles (and the same as unwelded), +Y up like the input
  double alpha = 0.0, offset = 0.0;  // m, as used
  std::size_t holes_closed = 0;      // border loops fanned shut before wrapping
};

// Errors name why (no triangles, a non-positive or non-finite alpha, an alpha below
// diagonal / kWrapMostRelativeAlpha, CGAL failing).
Result<WatertightProxy> WrapWatertight(const Mesh& mesh, const WrapOptions& options = {});

}  // namespace wirerig
