#include "gltf_mesh.h"

#include "gltf_buffers.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

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

Mat4d PositionQuantization::Dequantization() const {
  Mat4d m = Mat4d::Identity();
  if (!enabled) return m;
  m.topLeftCorner<3, 3>() *= scale;
  m.topRightCorner<3, 1>() = offset;
  return m;
}

namespace {

// The stored short of rest coordinate `value` along axis c.
std::int16_t StoredShort(const PositionQuantization& q, float value, int c) {
  const double stored = (double(value) - q.offset[c]) / q.scale * kShortScale;
  return static_cast<std::int16_t>(std::lround(std::clamp(stored, -kShortScale, kShortScale)));
}

// POSITION as normalized shorts, 8 bytes a vertex (4-byte aligned); min/max in shorts.
int AddQuantizedPositions(tinygltf::Model& model, const BaseVertices& base,
                          const PositionQuantization& q, int target) {
  const std::size_t count = base.Count();
  std::vector<std::int16_t> padded(4 * count, 0);
  std::vector<double> low(3, kShortScale), high(3, -kShortScale);
  for (std::size_t v = 0; v < count; ++v)
    for (int c = 0; c < 3; ++c) {
      const std::int16_t s = StoredShort(q, base.positions[3 * v + std::size_t(c)], c);
      padded[4 * v + std::size_t(c)] = s;
      low[std::size_t(c)] = std::min(low[std::size_t(c)], double(s));
      high[std::size_t(c)] = std::max(high[std::size_t(c)], double(s));
    }
  const int view =
      AddBufferView(model, padded.data(), padded.size() * sizeof(std::int16_t), target);
  model.bufferViews[static_cast<std::size_t>(view)].byteStride = 4 * sizeof(std::int16_t);
  RequireExtension(model, kMeshQuantization);
  const int index =
      AddAccessor(model, view, TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC3, count, true);
  if (count > 0) {
    model.accessors[static_cast<std::size_t>(index)].minValues = std::move(low);
    model.accessors[static_cast<std::size_t>(index)].maxValues = std::move(high);
  }
  return index;
}

}  // namespace

PositionQuantization QuantizePositions(BaseVertices* base) {
  PositionQuantization q;
  const std::size_t count = base->Count();
  if (count == 0) return q;
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::max()), high = -low;
  for (std::size_t v = 0; v < count; ++v)
    for (int c = 0; c < 3; ++c) {
      low[c] = std::min(low[c], double(base->positions[3 * v + std::size_t(c)]));
      high[c] = std::max(high[c], double(base->positions[3 * v + std::size_t(c)]));
    }
  q.offset = 0.5 * (low + high);
  q.scale = 0.5 * (high - low).maxCoeff();
  if (!(q.scale > 0.0) || !std::isfinite(q.scale)) return PositionQuantization{};
  q.enabled = true;
  for (std::size_t v = 0; v < count; ++v)
    for (int c = 0; c < 3; ++c) {
      float& value = base->positions[3 * v + std::size_t(c)];
      value = static_cast<float>(q.offset[c] +
                                 q.scale * double(StoredShort(q, value, c)) / kShortScale);
    }
  return q;
}

std::vector<PrimitiveTriangles> MakePrimitives(const Mesh& mesh, bool reorder_triangles) {
  std::vector<MeshPart> parts = mesh.parts;
  if (parts.empty()) {
    parts.push_back(MeshPart{"", 0, static_cast<std::uint32_t>(mesh.triangles.size()), -1});
  }
  // One primitive per material, its parts' triangles in part order: a reader draws (and, in
  // three.js, uploads morph targets for) each primitive apart.
  std::vector<PrimitiveTriangles> primitives;
  for (const MeshPart& part : parts) {
    if (part.triangle_count == 0) continue;
    auto primitive = std::find_if(primitives.begin(), primitives.end(),
                                  [&](const auto& p) { return p.material == part.material; });
    if (primitive == primitives.end()) {
      primitives.push_back({part.material, {}});
      primitive = primitives.end() - 1;
    }
    for (std::uint32_t f = 0; f < part.triangle_count; ++f) {
      const Triangle& t = mesh.triangles[part.first_triangle + f];
      primitive->indices.insert(primitive->indices.end(), t.begin(), t.end());
    }
  }
  if (reorder_triangles) {
    for (PrimitiveTriangles& primitive : primitives) {
      std::vector<std::uint32_t> reordered(primitive.indices.size());
      meshopt_optimizeVertexCache(reordered.data(), primitive.indices.data(),
                                  primitive.indices.size(), mesh.positions.size());
      primitive.indices.swap(reordered);
    }
  }
  return primitives;
}

int AddBaseMesh(tinygltf::Model& model, const Mesh& mesh, const BaseVertices& base,
                const std::vector<int>& materials, const std::string& name,
                const BaseMeshStorage& storage) {
  const int target = TINYGLTF_TARGET_ARRAY_BUFFER;
  std::map<std::string, int> attributes;
  attributes["POSITION"] =
      storage.positions.enabled
          ? AddQuantizedPositions(model, base, storage.positions, target)
          : AddFloatAccessor(model, base.positions, TINYGLTF_TYPE_VEC3, target, /*min_max=*/true);
  if (!base.normals.empty()) {
    attributes["NORMAL"] =
        storage.byte_normals
            ? AddNormalizedByteVec3Accessor(model, base.normals, target)
            : AddFloatAccessor(model, base.normals, TINYGLTF_TYPE_VEC3, target, false);
  }
  if (!base.uvs.empty()) {
    const bool unit = std::all_of(base.uvs.begin(), base.uvs.end(),
                                  [](float c) { return c >= 0.0f && c <= 1.0f; });
    if (storage.short_uvs && unit) {
      std::vector<std::uint16_t> shorts(base.uvs.size());
      std::transform(base.uvs.begin(), base.uvs.end(), shorts.begin(), [](float c) {
        return static_cast<std::uint16_t>(std::lround(double(c) * kUnsignedShortScale));
      });
      attributes["TEXCOORD_0"] =
          AddNormalizedShortAccessor(model, shorts, TINYGLTF_TYPE_VEC2, target);
    } else {
      attributes["TEXCOORD_0"] =
          AddFloatAccessor(model, base.uvs, TINYGLTF_TYPE_VEC2, target, false);
    }
  }

  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = name;
  const auto vertex_count = static_cast<std::uint32_t>(base.Count());
  for (PrimitiveTriangles& triangles : MakePrimitives(mesh, storage.reorder_triangles)) {
    tinygltf::Primitive primitive;
    primitive.attributes = attributes;
    primitive.indices = AddIndexAccessor(model, triangles.indices, vertex_count);
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    if (triangles.material >= 0)
      primitive.material = materials[static_cast<std::size_t>(triangles.material)];
    gltf_mesh.primitives.push_back(std::move(primitive));
  }
  model.meshes.push_back(std::move(gltf_mesh));
  return static_cast<int>(model.meshes.size()) - 1;
}

}  // namespace wirerig::gltf
