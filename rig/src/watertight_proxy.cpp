// Whether a mesh is watertight; the wrap itself is in watertight_wrap.cpp (CGAL).
#include "wirerig/rig/watertight_proxy.h"

#include "wirerig/io/finite.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <map>
#include <numeric>
#include <vector>

namespace wirerig {
namespace {

std::string Count(std::size_t n, const char* what) { return std::to_string(n) + " " + what; }

// Connected pieces of the triangles (sharing a vertex joins), by union-find.
std::size_t CountPieces(std::size_t vertex_count, std::span<const Triangle> triangles) {
  std::vector<std::uint32_t> root(vertex_count);
  std::iota(root.begin(), root.end(), 0u);
  auto find = [&](std::uint32_t v) {
    while (root[v] != v) v = root[v] = root[root[v]];
    return v;
  };
  std::vector<bool> used(vertex_count, false);
  for (const Triangle& t : triangles) {
    for (std::uint32_t v : t) used[v] = true;
    root[find(t[1])] = find(t[0]);
    root[find(t[2])] = find(t[0]);
  }
  std::size_t pieces = 0;
  for (std::uint32_t v = 0; v < vertex_count; ++v) pieces += used[v] && find(v) == v;
  return pieces;
}

}  // namespace

std::string ClosedManifoldProblem(std::span<const Vec3> positions,
                                  std::span<const Triangle> triangles) {
  const std::size_t vertex_count = positions.size();
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    for (std::uint32_t v : t) {
      if (v >= vertex_count) {
        return "triangle " + std::to_string(f) + " uses vertex " + std::to_string(v) +
               " but there are only " + Count(vertex_count, "welded vertices");
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      return "triangle " + std::to_string(f) + " repeats a vertex (degenerate)";
    }
  }
  for (std::size_t v = 0; v < vertex_count; ++v) {
    if (!IsFinite(positions[v])) {
      return "welded vertex " + std::to_string(v) + " is not finite";
    }
  }

  // Directed edges (a -> b in a triangle's winding), sorted: a closed, consistently oriented
  // 2-manifold uses every undirected edge exactly twice, once in each direction.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> directed;
  directed.reserve(triangles.size() * 3);
  for (const Triangle& t : triangles) {
    for (int k = 0; k < 3; ++k) directed.emplace_back(t[k], t[(k + 1) % 3]);
  }
  std::sort(directed.begin(), directed.end());
  std::size_t repeated_directed = 0;
  for (std::size_t i = 1; i < directed.size(); ++i) {
    if (directed[i] == directed[i - 1]) ++repeated_directed;
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> undirected;
  undirected.reserve(directed.size());
  for (const auto& [a, b] : directed) undirected.emplace_back(std::min(a, b), std::max(a, b));
  std::sort(undirected.begin(), undirected.end());
  std::size_t boundary = 0, non_manifold = 0;
  for (std::size_t i = 0; i < undirected.size();) {
    std::size_t j = i;
    while (j < undirected.size() && undirected[j] == undirected[i]) ++j;
    if (j - i == 1) ++boundary;
    if (j - i > 2) ++non_manifold;
    i = j;
  }
  if (boundary > 0) {
    return "the mesh is not closed: " + Count(boundary, "boundary edges") +
           " (holes or open borders)";
  }
  if (non_manifold > 0) {
    return "the mesh is not 2-manifold: " + Count(non_manifold, "edges") +
           " shared by three or more triangles";
  }
  if (repeated_directed > 0) {
    return "the mesh is not consistently oriented: " + Count(repeated_directed, "edges") +
           " run the same way in both of their triangles";
  }

  return {};
}

std::string WatertightProblem(const Mesh& mesh) {
  if (mesh.welded_triangles.empty()) return "the mesh has no (welded) triangles";
  if (std::string why = ClosedManifoldProblem(mesh.welded_positions, mesh.welded_triangles);
      !why.empty())
    return why;
  const std::size_t pieces = CountPieces(mesh.welded_positions.size(), mesh.welded_triangles);
  if (pieces > 1) return "the mesh is in " + Count(pieces, "separate pieces");
  return {};
}

}  // namespace wirerig
