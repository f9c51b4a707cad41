// The exported mesh at rest: its vertex attributes as stored in the file (float) and the glTF
// mesh with one triangle primitive per material (its mesh parts' triangles, in part order).
#pragma once

#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "wirerig/rig/mesh.h"

namespace wirerig::gltf {

using Mat4d = Eigen::Matrix4d;

// The rest mesh's render vertices as written: #V x 3 positions, #V x 3 unit normals (empty when
// the mesh has none; a zero normal becomes +Y), #V x 2 uvs (or empty).
struct BaseVertices {
  std::vector<float> positions;
  std::vector<float> normals;
  std::vector<float> uvs;
  std::size_t zero_normals = 0;  // normals replaced by +Y
  std::size_t Count() const { return positions.size() / 3; }
};
BaseVertices MakeBaseVertices(const Mesh& mesh);

// POSITION stored as normalized signed shorts (KHR_mesh_quantization), as gltfpack stores it:
// p = offset + scale * max(q / 32767, -1). A skinned mesh's node transform is ignored by
// readers, so the dequantization goes into the inverse bind matrices (Dequantization()) and the
// morph targets' deltas into stored units (1 / scale: their animated weights).
struct PositionQuantization {
  bool enabled = false;
  Vec3 offset = Vec3::Zero();  // m: the rest box's centre
  double scale = 1.0;          // m per stored unit: half the rest box's largest side
  // The map from stored to rest positions (identity when not enabled).
  Mat4d Dequantization() const;
};
// Quantization for `base`'s positions, which are rounded onto the grid the shorts hold (so
// that whatever is fitted to them and measured sees what the file stores).
PositionQuantization QuantizePositions(BaseVertices* base);

// How AddBaseMesh stores the rest mesh (the defaults: float attributes, triangles in order).
struct BaseMeshStorage {
  // Each primitive's triangles reordered for the GPU's vertex cache (meshoptimizer's
  // optimizeVertexCache: the same triangles, corners in the same order), which also lets the
  // index codec of EXT_meshopt_compression store them in fewer bytes.
  bool reorder_triangles = false;
  // NORMAL as normalized signed bytes (KHR_mesh_quantization, required).
  bool byte_normals = false;
  // TEXCOORD_0 as normalized unsigned shorts (core glTF) when every uv lies in [0, 1]: within
  // 0.5 / 65535 of the float (0.03 texel of a 4096 texture).
  bool short_uvs = false;
  PositionQuantization positions;  // enabled: POSITION as its shorts
};

// One triangle primitive's corners: the triangles of the parts with `material` (a
// Mesh::materials index, or -1), in part order.
struct PrimitiveTriangles {
  int material = -1;
  std::vector<std::uint32_t> indices;
};
// The mesh's primitives, one per material of the parts with triangles (in the order the parts
// first name it; one for all triangles when the mesh has no parts), each reordered for the
// vertex cache when `reorder_triangles` (BaseMeshStorage).
std::vector<PrimitiveTriangles> MakePrimitives(const Mesh& mesh, bool reorder_triangles);

// Adds the mesh named `name`: POSITION (with min/max), NORMAL and TEXCOORD_0 when present,
// shared by one primitive per material of the parts with triangles (their triangles in part
// order; one primitive for all triangles when the mesh has no parts), each with that material
// (`materials`: glTF index per Mesh::materials entry), stored as `storage` says. Returns the
// mesh index.
int AddBaseMesh(tinygltf::Model& model, const Mesh& mesh, const BaseVertices& base,
                const std::vector<int>& materials, const std::string& name,
                const BaseMeshStorage& storage = {});

}  // namespace wirerig::gltf
