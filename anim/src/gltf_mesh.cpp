#include "gltf_mesh.h"

#include "gltf_buffers.h"

#include <algorithm>

#include <meshoptimizer.h>

namespace wirerig::gltf {

BaseVertices MakeBaseVertices(const Mesh& mesh) {
  BaseVertices base;
  for (const Vec3& p : mesh.positions) {
    for (int c = 0; c < 3; ++c) base.positions.push_back(static_cast<float>(p[c]));
  }
  for (const Vec3& n : mesh.normals) {
    const double length = n.norm();
    Vec3 unit = Vec3::UnitY();
    if (length > 1e-12) {
      unit = n / length;
    } else {
      ++base.zero_normals;
    }
    for (int c = 0; c < 3; ++c) base.normals.push_back(static_cast<float>(unit[c]));
  }
  for (const Vec2& uv : mesh.uvs) {
    for (int c = 0; c < 2; ++c) base.uvs.push_back(static_cast<float>(uv[c]));
  }
  return base;
}

int AddBaseMesh(tinygltf::Model& model, const Mesh& mesh, const BaseVertices& base,
                const std::vector<int>& materials, const std::string& name, bool reorder_triangles,
                bool byte_normals) {
  const int target = TINYGLTF_TARGET_ARRAY_BUFFER;
  std::map<std::string, int> attributes;
  attributes["POSITION"] =
      AddFloatAccessor(model, base.positions, TINYGLTF_TYPE_VEC3, target, /*min_max=*/true);
  if (!base.normals.empty()) {
    attributes["NORMAL"] =
        byte_normals ? AddNormalizedByteVec3Accessor(model, base.normals, target)
                     : AddFloatAccessor(model, base.normals, TINYGLTF_TYPE_VEC3, target, false);
  }
  if (!base.uvs.empty()) {
    attributes["TEXCOORD_0"] = AddFloatAccessor(model, base.uvs, TINYGLTF_TYPE_VEC2, target, false);
  }

  std::vector<MeshPart> parts = mesh.parts;
  if (parts.empty()) {
    parts.push_back(MeshPart{name, 0, static_cast<std::uint32_t>(mesh.triangles.size()), -1});
  }
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = name;
  const auto vertex_count = static_cast<std::uint32_t>(base.Count());
  // One primitive per material, its parts' triangles in part order: a reader draws (and, in
  // three.js, uploads morph targets for) each primitive apart.
  std::vector<int> part_materials;
  for (const MeshPart& part : parts)
    if (part.triangle_count > 0 && std::find(part_materials.begin(), part_materials.end(),
                                             part.material) == part_materials.end())
      part_materials.push_back(part.material);
  for (const int material : part_materials) {
    std::vector<std::uint32_t> indices;
    for (const MeshPart& part : parts) {
      if (part.material != material) continue;
      for (std::uint32_t f = 0; f < part.triangle_count; ++f) {
        const Triangle& t = mesh.triangles[part.first_triangle + f];
        indices.insert(indices.end(), t.begin(), t.end());
      }
    }
    if (reorder_triangles) {
      std::vector<std::uint32_t> reordered(indices.size());
      meshopt_optimizeVertexCache(reordered.data(), indices.data(), indices.size(), vertex_count);
      indices.swap(reordered);
    }
    tinygltf::Primitive primitive;
    primitive.attributes = attributes;
    primitive.indices = AddIndexAccessor(model, indices, vertex_count);
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    if (material >= 0) primitive.material = materials[static_cast<std::size_t>(material)];
    gltf_mesh.primitives.push_back(std::move(primitive));
  }
  model.meshes.push_back(std::move(gltf_mesh));
  return static_cast<int>(model.meshes.size()) - 1;
}

}  // namespace wirerig::gltf
