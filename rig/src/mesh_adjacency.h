// The mesh's edges per vertex with their rest lengths: the graph the joint skin spreads walk
// and solve on (joint_skin_spread.h, skinless_spread.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "wirerig/runtime/conventions.h"

namespace wirerig {

struct Neighbour {
  std::uint32_t vertex = 0;
  double weight = 0.0;  // 1 / rest length
  double length = 0.0;
};
// The mesh's edges, per vertex: neighbours of v are list[offsets[v] .. offsets[v + 1]).
struct Adjacency {
  std::vector<std::uint32_t> offsets;
  std::vector<Neighbour> list;
  std::span<const Neighbour> operator[](std::uint32_t v) const {
    return {list.data() + offsets[v], list.data() + offsets[v + 1]};
  }
};

// Every triangle edge both ways, deduplicated; weights 1 / rest length.
Adjacency MakeAdjacency(std::span<const Vec3> rest, const std::vector<Triangle>& triangles);

}  // namespace wirerig
