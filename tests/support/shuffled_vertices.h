// A mesh and its bake with the render vertices in a random order (the same triangles, renumbered):
// the input a scanned or hand-made asset gives, whose vertex order carries no locality.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "wirerig/anim/baked_animation.h"
#include "wirerig/rig/mesh.h"

namespace wirerig::testing {

// Moves source vertex order[i] to vertex i in every per-vertex array of `mesh` and `bake` (each
// key's positions and normals, the skin) and renumbers the triangles; returns `order`, a random
// permutation drawn from `seed`.
inline std::vector<std::uint32_t> ShuffleVertices(Mesh* mesh, BakedAnimation* bake, unsigned seed) {
  const std::size_t count = mesh->positions.size();
  std::vector<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  std::mt19937 random(seed);
  std::shuffle(order.begin(), order.end(), random);
  const auto gather = [&](auto& values, std::size_t blocks) {
    if (values.empty()) return;
    EXPECT_EQ(values.size(), blocks * count) << "a per-vertex array of another length";
    if (values.size() != blocks * count) return;
    auto source = values;
    for (std::size_t b = 0; b < blocks; ++b)
      for (std::size_t i = 0; i < count; ++i) values[b * count + i] = source[b * count + order[i]];
  };
  gather(mesh->positions, 1);
  gather(mesh->normals, 1);
  gather(mesh->uvs, 1);
  gather(mesh->skin_joints, 1);
  gather(mesh->skin_weights, 1);
  gather(mesh->weld_map, 1);
  std::vector<std::uint32_t> new_index(count);
  for (std::uint32_t i = 0; i < count; ++i) new_index[order[i]] = i;
  for (Triangle& triangle : mesh->triangles)
    for (auto& corner : triangle) corner = new_index[corner];
  gather(bake->positions, bake->KeyCount());
  gather(bake->normals, bake->KeyCount());
  gather(bake->skin_joints, 1);
  gather(bake->skin_weights, 1);
  return order;
}

}  // namespace wirerig::testing
