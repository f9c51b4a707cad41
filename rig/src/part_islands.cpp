#include "wirerig/rig/part_assignment.h"

#include <algorithm>
#include <map>
#include <utility>

#include "disjoint_sets.h"
#include "part_tree.h"

namespace wirerig {

std::size_t MergePartIslands(const std::vector<Triangle>& triangles, const std::vector<int>& parent,
                             const std::vector<bool>& fixed, const std::vector<bool>& restricted,
                             std::vector<int>* vertex_part) {
  std::vector<int>& part = *vertex_part;
  const std::size_t n = part.size();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(3 * triangles.size());
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k) edges.emplace_back(t[k], t[(k + 1) % 3]);
  DisjointSets surface(n);
  for (const auto& [a, b] : edges) surface.Union(a, b);

  std::size_t moved = 0;
  constexpr int kMaxRounds = 8;  // a merge can join islands; a few rounds settle it
  for (int round = 0; round < kMaxRounds; ++round) {
    DisjointSets regions(n);
    for (const auto& [a, b] : edges)
      if (part[a] == part[b]) regions.Union(a, b);
    // The largest region of each (part, surface piece).
    std::map<std::pair<int, std::uint32_t>, std::uint32_t> largest;
    for (std::uint32_t v = 0; v < n; ++v) {
      const std::uint32_t r = regions.Find(v);
      auto [it, added] = largest.try_emplace({part[v], surface.Find(v)}, r);
      if (!added && regions.Size(r) > regions.Size(it->second)) it->second = r;
    }
    std::vector<std::uint8_t> island(n, 0);
    for (std::uint32_t v = 0; v < n; ++v) {
      const std::uint32_t r = regions.Find(v), main = largest.at({part[v], surface.Find(v)});
      island[r] = r != main && regions.Size(r) <= kIslandFraction * regions.Size(main);
    }
    for (std::uint32_t v = 0; v < n; ++v)
      if (fixed[v]) island[regions.Find(v)] = 0;
    // Edges leaving each island, by the part they reach.
    std::map<std::pair<std::uint32_t, int>, std::size_t> reach;
    for (const auto& [a, b] : edges) {
      if (part[a] == part[b]) continue;
      for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, a}}) {
        const std::uint32_t r = regions.Find(from);
        if (island[r] && !restricted[std::size_t(part[to])] &&
            !AtOrBelow(parent, part[to], part[from]))
          ++reach[{r, part[to]}];
      }
    }
    std::map<std::uint32_t, std::pair<std::size_t, int>> best;  // island -> (edges, part)
    for (const auto& [key, count] : reach) {
      auto& b = best[key.first];
      if (count > b.first) b = {count, key.second};
    }
    std::size_t moved_now = 0;
    for (std::uint32_t v = 0; v < n; ++v) {
      const auto it = best.find(regions.Find(v));
      if (it == best.end()) continue;
      part[v] = it->second.second;
      ++moved_now;
    }
    moved += moved_now;
    if (moved_now == 0) break;
  }
  return moved;
}

}  // namespace wirerig
