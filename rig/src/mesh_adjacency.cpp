#include "mesh_adjacency.h"

#include <algorithm>

namespace wirerig {

Adjacency MakeAdjacency(std::span<const Vec3> rest, const std::vector<Triangle>& triangles) {
  // Bucketed by vertex, then each bucket deduplicated.
  const std::size_t n = rest.size();
  std::vector<std::uint32_t> count(n + 1, 0);
  for (const Triangle& t : triangles)
    for (std::uint32_t v : t) count[v + 1] += 2;
  for (std::size_t v = 0; v < n; ++v) count[v + 1] += count[v];
  std::vector<std::uint32_t> others(count[n]);
  std::vector<std::uint32_t> fill(count.begin(), count.end() - 1);
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k) {
      others[fill[t[k]]++] = t[(k + 1) % 3];
      others[fill[t[k]]++] = t[(k + 2) % 3];
    }
  Adjacency out;
  out.offsets.assign(n + 1, 0);
  out.list.reserve(count[n] / 2);
  for (std::uint32_t a = 0; a < n; ++a) {
    const auto first = others.begin() + count[a], last = others.begin() + count[a + 1];
    std::sort(first, last);
    const auto unique_end = std::unique(first, last);
    for (auto b = first; b != unique_end; ++b) {
      const double length = std::max((rest[a] - rest[*b]).norm(), 1e-12);
      out.list.push_back({*b, 1.0 / length, length});
    }
    out.offsets[a + 1] = std::uint32_t(out.list.size());
  }
  return out;
}

}  // namespace wirerig
