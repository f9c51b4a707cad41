#include "gltf_vertex_order.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

#include <meshoptimizer.h>

#include "gltf_mesh.h"

namespace wirerig::gltf {
namespace {

// out[i] = in[order[i]] for each of `blocks` consecutive blocks of order.size() values; empty
// when `in` does not hold exactly that many (an optional array the export does not read).
template <typename T>
std::vector<T> Gather(const std::vector<T>& in, std::span<const std::uint32_t> order,
                      std::size_t blocks = 1) {
  if (in.size() != blocks * order.size()) return {};
  std::vector<T> out;
  out.reserve(in.size());
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t first = b * order.size();
    for (const std::uint32_t source : order) out.push_back(in[first + source]);
  }
  return out;
}

// Bytes of the vertex codec for `count` elements of `element` bytes.
std::size_t VertexCodecBytes(const std::vector<unsigned char>& data, std::size_t element) {
  const std::size_t count = data.size() / element;
  std::vector<unsigned char> coded(meshopt_encodeVertexBufferBound(count, element));
  return meshopt_encodeVertexBuffer(coded.data(), coded.size(), data.data(), count, element);
}

// Vectors (3 doubles or floats each, read by `at(v, c)`) as signed shorts over their largest
// magnitude, padded to 8 bytes: how the codec sees quantized positions or deltas.
template <typename At>
std::vector<unsigned char> AsShorts(std::size_t count, At at) {
  double largest = 0.0;
  for (std::size_t v = 0; v < count; ++v)
    for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(double(at(v, c))));
  const double scale = largest > 0.0 && std::isfinite(largest) ? 32767.0 / largest : 0.0;
  std::vector<std::int16_t> shorts(4 * count, 0);
  for (std::size_t v = 0; v < count; ++v)
    for (int c = 0; c < 3; ++c)
      shorts[4 * v + std::size_t(c)] = static_cast<std::int16_t>(std::lround(at(v, c) * scale));
  std::vector<unsigned char> bytes(shorts.size() * 2);
  std::memcpy(bytes.data(), shorts.data(), bytes.size());
  return bytes;
}

// The codecs' bytes for the part of the file SmallerVertexOrder compares, vertices in `order`.
std::size_t CodedBytes(const Mesh& mesh, const BakedAnimation& bake,
                       std::span<const std::uint32_t> order) {
  Mesh shape;  // what is coded: no materials (their images), skin or welding copied
  shape.positions = mesh.positions;
  shape.normals = mesh.normals;
  shape.triangles = mesh.triangles;
  shape.parts = mesh.parts;
  const Mesh ordered = ReorderVertices(shape, order);
  const std::size_t count = order.size();
  std::size_t bytes = 0;
  for (const PrimitiveTriangles& primitive : MakePrimitives(ordered, /*reorder_triangles=*/true)) {
    std::vector<unsigned char> coded(
        meshopt_encodeIndexBufferBound(primitive.indices.size(), count));
    bytes += meshopt_encodeIndexBuffer(coded.data(), coded.size(), primitive.indices.data(),
                                       primitive.indices.size());
  }
  bytes += VertexCodecBytes(
      AsShorts(count, [&](std::size_t v, int c) { return ordered.positions[v][c]; }), 8);
  if (!ordered.normals.empty()) {
    bytes += VertexCodecBytes(
        AsShorts(count, [&](std::size_t v, int c) { return ordered.normals[v][c]; }), 8);
  }
  if (bake.skin_weights.size() == count && bake.skin_joints.size() == count) {
    std::vector<unsigned char> weights(4 * count), joints(4 * count);
    for (std::size_t v = 0; v < count; ++v)
      for (int i = 0; i < 4; ++i) {
        weights[4 * v + std::size_t(i)] =
            static_cast<unsigned char>(std::lround(bake.skin_weights[order[v]][i] * 255.0f));
        joints[4 * v + std::size_t(i)] =
            static_cast<unsigned char>(bake.skin_joints[order[v]][std::size_t(i)] & 0xFF);
      }
    bytes += VertexCodecBytes(weights, 4) + VertexCodecBytes(joints, 4);
  }
  const std::size_t keys = bake.KeyCount();
  if (bake.positions.size() == keys * count && keys > 0) {
    for (const std::size_t key : {keys / 4, keys / 2, 3 * keys / 4}) {
      const Vec3f* frame = bake.positions.data() + key * count;
      bytes += VertexCodecBytes(AsShorts(count,
                                         [&](std::size_t v, int c) {
                                           return double(frame[order[v]][c]) -
                                                  mesh.positions[order[v]][c];
                                         }),
                                8);
    }
  }
  return bytes;
}

}  // namespace

std::vector<std::uint32_t> SmallerVertexOrder(const Mesh& mesh, const BakedAnimation& bake) {
  std::vector<std::uint32_t> own(mesh.positions.size());
  std::iota(own.begin(), own.end(), 0u);
  std::vector<std::uint32_t> fetch = FetchOrder(mesh);
  const std::size_t own_bytes = CodedBytes(mesh, bake, own);
  const std::size_t fetch_bytes = CodedBytes(mesh, bake, fetch);
  return fetch_bytes < own_bytes ? fetch : own;
}

std::vector<std::uint32_t> FetchOrder(const Mesh& mesh) {
  const std::size_t count = mesh.positions.size();
  std::vector<std::uint32_t> indices;
  for (const PrimitiveTriangles& primitive : MakePrimitives(mesh, /*reorder_triangles=*/true)) {
    indices.insert(indices.end(), primitive.indices.begin(), primitive.indices.end());
  }
  // remap[source] = file vertex, or ~0u for a vertex no triangle uses.
  std::vector<std::uint32_t> remap(count);
  const std::size_t used =
      meshopt_optimizeVertexFetchRemap(remap.data(), indices.data(), indices.size(), count);
  std::vector<std::uint32_t> order(count);
  std::size_t unused = used;
  for (std::uint32_t v = 0; v < count; ++v) {
    const std::uint32_t file = remap[v] != ~0u ? remap[v] : static_cast<std::uint32_t>(unused++);
    order[file] = v;
  }
  return order;
}

Mesh ReorderVertices(const Mesh& mesh, std::span<const std::uint32_t> order) {
  Mesh out = mesh;
  out.positions = Gather(mesh.positions, order);
  out.normals = Gather(mesh.normals, order);
  out.uvs = Gather(mesh.uvs, order);
  out.skin_joints = Gather(mesh.skin_joints, order);
  out.skin_weights = Gather(mesh.skin_weights, order);
  out.weld_map = Gather(mesh.weld_map, order);
  std::vector<std::uint32_t> file_of(order.size());
  for (std::uint32_t file = 0; file < order.size(); ++file) file_of[order[file]] = file;
  for (Triangle& triangle : out.triangles)
    for (auto& corner : triangle) corner = file_of[corner];
  return out;
}

BakedAnimation ReorderVertices(const BakedAnimation& bake, std::span<const std::uint32_t> order) {
  BakedAnimation out;
  out.name = bake.name;
  out.fps = bake.fps;
  out.times = bake.times;
  out.vertex_count = bake.vertex_count;
  out.positions = Gather(bake.positions, order, bake.KeyCount());
  out.normals = Gather(bake.normals, order, bake.KeyCount());
  out.spines = bake.spines;
  out.skin_joints = Gather(bake.skin_joints, order);
  out.skin_weights = Gather(bake.skin_weights, order);
  out.warnings = bake.warnings;
  return out;
}

}  // namespace wirerig::gltf
