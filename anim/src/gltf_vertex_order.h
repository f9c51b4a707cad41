// The vertex order of compressed files: vertices in the order the (cache-ordered) triangles
// first use them, as gltfpack stores them, so that EXT_meshopt_compression's vertex codec sees
// neighbours next to each other (positions, normals, uvs, skin and shapes all shrink).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "wirerig/anim/baked_animation.h"
#include "wirerig/rig/mesh.h"

namespace wirerig::gltf {

// File vertex -> source render vertex: meshoptimizer's optimizeVertexFetch order over the
// primitives MakePrimitives(mesh, true) draws, then the vertices no triangle uses, in order.
// A permutation of 0..#V-1.
std::vector<std::uint32_t> FetchOrder(const Mesh& mesh);

// The order of the two, the mesh's own (0..#V-1) or FetchOrder's, in which meshoptimizer's
// codecs store the smaller part of the file that the fit does not choose: the triangles, the
// rest positions and normals, the bake's own skin and its displacements at three keys. A grid
// in ring order (the octopus's tentacles) keeps its own order, whose rows the codec predicts
// better than the strips the fetch order zigzags along; a scanned mesh takes the fetch order.
std::vector<std::uint32_t> SmallerVertexOrder(const Mesh& mesh, const BakedAnimation& bake);

// `mesh` with its render vertices in `order` (file vertex -> source vertex): positions,
// normals, uvs, source skin and weld map moved, triangles renumbered (same triangles, same
// order, so parts hold). Welded data is unchanged.
Mesh ReorderVertices(const Mesh& mesh, std::span<const std::uint32_t> order);
// `bake` with every key's positions and normals, and the skin, in `order`.
BakedAnimation ReorderVertices(const BakedAnimation& bake, std::span<const std::uint32_t> order);

}  // namespace wirerig::gltf
