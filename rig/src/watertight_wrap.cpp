// The watertight proxy's wrap: CGAL's 3D alpha wrapping (CGAL::alpha_wrap_3, GPL like the rest
// of CGAL's mesh packages). Built only with WIRERIG_WITH_CGAL (without_cgal.cpp stands in).
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <map>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/alpha_wrap_3.h>

#include "wirerig/io/finite.h"
#include "wirerig/io/floating_point_hold.h"
#include "wirerig/rig/watertight_proxy.h"

namespace wirerig {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalPoint = Kernel::Point_3;
using CgalMesh = CGAL::Surface_mesh<CgalPoint>;

// Closes every hole of the soup with a fan of triangles from the centroid of its border loop
// (border edges: used by one triangle, followed in their triangle's direction), so the wrap
// does not enter an open end (a tube's, a neck's) and wrap its wall from inside. Returns the
// holes closed.
std::size_t CloseHoles(std::vector<CgalPoint>& points,
                       std::vector<std::array<std::size_t, 3>>& faces) {
  std::map<std::pair<std::size_t, std::size_t>, int> uses;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) {
      const std::size_t a = f[k], b = f[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  std::multimap<std::size_t, std::size_t> next;  // border edge a -> b
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) {
      const std::size_t a = f[k], b = f[(k + 1) % 3];
      if (uses[{std::min(a, b), std::max(a, b)}] == 1) next.emplace(a, b);
    }
  std::size_t holes = 0;
  while (!next.empty()) {
    std::vector<std::size_t> loop = {next.begin()->first};
    std::size_t at = next.begin()->second;
    next.erase(next.begin());
    while (at != loop.front()) {
      loop.push_back(at);
      const auto step = next.find(at);
      if (step == next.end()) break;  // an open chain (non-manifold border): fan it anyway
      at = step->second;
      next.erase(step);
    }
    if (loop.size() < 3) continue;
    double x = 0.0, y = 0.0, z = 0.0;
    for (std::size_t v : loop) x += points[v].x(), y += points[v].y(), z += points[v].z();
    const double n = double(loop.size());
    const std::size_t centre = points.size();
    points.emplace_back(x / n, y / n, z / n);
    for (std::size_t i = 0; i < loop.size(); ++i)  // reversed: the fan faces out of the hole
      faces.push_back({loop[(i + 1) % loop.size()], loop[i], centre});
    ++holes;
  }
  return holes;
}

}  // namespace

Result<WatertightProxy> WrapWatertight(const Mesh& mesh, const WrapOptions& options) {
  const std::vector<Vec3>& positions = mesh.welded_positions;
  std::vector<CgalPoint> points;
  points.reserve(positions.size());
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (const Vec3& p : positions) {
    points.emplace_back(p.x(), p.y(), p.z());
    if (IsFinite(p)) low = low.cwiseMin(p), high = high.cwiseMax(p);
  }
  std::vector<std::array<std::size_t, 3>> faces;
  faces.reserve(mesh.welded_triangles.size());
  for (const Triangle& t : mesh.welded_triangles) {
    if (t[0] >= positions.size() || t[1] >= positions.size() || t[2] >= positions.size())
      return Error{"alpha wrap: a triangle uses a vertex the mesh does not have"};
    if (!IsFinite(positions[t[0]]) || !IsFinite(positions[t[1]]) || !IsFinite(positions[t[2]]))
      return Error{"alpha wrap: a triangle has a vertex that is not finite"};
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;  // degenerate: nothing to wrap
    faces.push_back({t[0], t[1], t[2]});
  }
  if (faces.empty()) return Error{"alpha wrap: the mesh has no triangles"};
  const double diagonal = (high - low).norm();
  if (!(diagonal > 0.0)) return Error{"alpha wrap: the mesh has no extent"};
  WatertightProxy out;
  out.alpha = options.alpha > 0.0 ? options.alpha : diagonal / kWrapRelativeAlpha;
  if (!std::isfinite(out.alpha) || !(out.alpha > 0.0))
    return Error{"alpha wrap: alpha must be a positive length (m)"};
  if (const double least = diagonal / kWrapMostRelativeAlpha; out.alpha < least) {
    char message[200];
    std::snprintf(message, sizeof message,
                  "alpha wrap: alpha %g m is below the mesh's diagonal / %g (%g m), where the "
                  "wrap would take minutes and gigabytes; give at least %g m",
                  out.alpha, kWrapMostRelativeAlpha, least, least);
    return Error{message};
  }
  out.offset = out.alpha * kWrapOffsetFraction;
  out.holes_closed = CloseHoles(points, faces);
  CgalMesh wrap;
  try {
    ScopedFloatingPointHold hold;
    CGAL::alpha_wrap_3(points, faces, out.alpha, out.offset, wrap);
  } catch (const std::exception& e) {
    return Error{std::string("alpha wrap: CGAL failed: ") + e.what()};
  }
  if (wrap.number_of_faces() == 0) return Error{"alpha wrap: CGAL returned an empty wrap"};
  std::vector<std::uint32_t> index(wrap.number_of_vertices());
  for (CgalMesh::Vertex_index v : wrap.vertices()) {
    const CgalPoint& p = wrap.point(v);
    index[v] = std::uint32_t(out.mesh.positions.size());
    out.mesh.positions.emplace_back(p.x(), p.y(), p.z());
  }
  for (CgalMesh::Face_index f : wrap.faces()) {
    Triangle t{};
    int k = 0;
    for (CgalMesh::Vertex_index v : CGAL::vertices_around_face(wrap.halfedge(f), wrap))
      if (k < 3) t[std::size_t(k++)] = index[v];
    out.mesh.triangles.push_back(t);
  }
  out.mesh.parts.push_back({"alpha wrap", 0, std::uint32_t(out.mesh.triangles.size()), -1});
  WeldByPosition(out.mesh);
  return out;
}

}  // namespace wirerig
