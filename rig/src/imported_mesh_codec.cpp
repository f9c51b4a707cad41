#include "imported_mesh_codec.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>
#include <vector>

namespace wirerig {
namespace {

class Writer {
 public:
  template <typename T>
  void Put(const T& value) {
    static_assert(std::is_arithmetic_v<T>);
    Bytes(&value, sizeof(T));
  }
  void Put(const std::string& s) {
    Put<std::uint64_t>(s.size());
    Bytes(s.data(), s.size());
  }
  // Scalars, and fixed-size Eigen vectors and std::arrays of scalars (stored as their
  // coefficients; the layouts are asserted below).
  template <typename T>
  void PutList(const std::vector<T>& items) {
    Put<std::uint64_t>(items.size());
    Bytes(items.data(), items.size() * sizeof(T));
  }
  std::string Take() { return std::move(out_); }

 private:
  void Bytes(const void* data, std::size_t size) {
    out_.append(static_cast<const char*>(data), size);
  }
  std::string out_;
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}

  template <typename T>
  bool Get(T& value) {
    static_assert(std::is_arithmetic_v<T>);
    return Bytes(&value, sizeof(T));
  }
  bool Get(std::string& s) {
    std::uint64_t size = 0;
    if (!Get(size) || size > Left()) return false;
    s.assign(bytes_.substr(pos_, size));
    pos_ += size;
    return true;
  }
  template <typename T>
  bool GetList(std::vector<T>& items) {
    std::uint64_t size = 0;
    if (!Get(size) || size > Left() / sizeof(T)) return false;
    items.resize(size);
    return Bytes(items.data(), size * sizeof(T));
  }
  bool AtEnd() const { return pos_ == bytes_.size(); }

 private:
  std::size_t Left() const { return bytes_.size() - pos_; }
  bool Bytes(void* data, std::size_t size) {
    if (size > Left()) return false;
    if (size > 0) std::memcpy(data, bytes_.data() + pos_, size);
    pos_ += size;
    return true;
  }
  std::string_view bytes_;
  std::size_t pos_ = 0;
};

// Vec2/Vec3/Vec4/Mat4 and Triangle/skin joints are plain coefficient arrays.
static_assert(sizeof(Vec2) == 2 * sizeof(double) && sizeof(Vec3) == 3 * sizeof(double) &&
              sizeof(Vec4) == 4 * sizeof(double) && sizeof(Mat4) == 16 * sizeof(double));
static_assert(sizeof(Triangle) == 3 * sizeof(std::uint32_t) &&
              sizeof(std::array<int, 4>) == 4 * sizeof(int));

Error Damaged(const char* what) {
  return Error{std::string("truncated or damaged mesh message (") + what + ")"};
}

bool TrianglesWithin(const std::vector<Triangle>& triangles, std::size_t vertices) {
  return std::all_of(triangles.begin(), triangles.end(), [&](const Triangle& t) {
    return t[0] < vertices && t[1] < vertices && t[2] < vertices;
  });
}

// What the parent relies on of a mesh the child sent (indexes it without checks): every index
// within its array, parts over the triangles in order, joints' parents before them. The child
// ran Assimp on an untrusted file and may have been corrupted without crashing.
const char* Inconsistency(const Mesh& mesh) {
  const std::size_t vertices = mesh.positions.size();
  if ((!mesh.normals.empty() && mesh.normals.size() != vertices) ||
      (!mesh.uvs.empty() && mesh.uvs.size() != vertices))
    return "normals or uvs";
  if (!TrianglesWithin(mesh.triangles, vertices)) return "triangles";
  std::uint64_t next = 0;
  for (const MeshPart& part : mesh.parts) {
    if (part.first_triangle != next ||
        (part.material != -1 &&
         (part.material < 0 || std::size_t(part.material) >= mesh.materials.size())))
      return "parts";
    next += part.triangle_count;
  }
  if (!mesh.parts.empty() && next != mesh.triangles.size()) return "parts";
  for (std::size_t j = 0; j < mesh.joints.size(); ++j)
    if (mesh.joints[j].parent < -1 || mesh.joints[j].parent >= int(j)) return "joints";
  if (!mesh.skin_joints.empty() &&
      (mesh.skin_joints.size() != vertices || mesh.skin_weights.size() != vertices))
    return "skin";
  for (const std::array<int, 4>& slots : mesh.skin_joints)
    for (const int joint : slots)
      if (joint < -1 || joint >= int(mesh.joints.size())) return "skin";
  if (!mesh.weld_map.empty() &&
      (mesh.weld_map.size() != vertices || mesh.welded_triangles.size() != mesh.triangles.size()))
    return "welding";
  for (const std::uint32_t w : mesh.weld_map)
    if (w >= mesh.welded_positions.size()) return "welding";
  if (!TrianglesWithin(mesh.welded_triangles, mesh.welded_positions.size())) return "welding";
  return nullptr;
}

}  // namespace

std::string EncodeImportedMesh(const ImportedMesh& imported) {
  const Mesh& mesh = imported.mesh;
  Writer w;
  w.PutList(mesh.positions);
  w.PutList(mesh.normals);
  w.PutList(mesh.uvs);
  w.PutList(mesh.triangles);
  w.Put<std::uint64_t>(mesh.parts.size());
  for (const MeshPart& part : mesh.parts) {
    w.Put(part.name);
    w.Put(part.first_triangle);
    w.Put(part.triangle_count);
    w.Put(part.material);
  }
  w.Put<std::uint64_t>(mesh.materials.size());
  for (const MeshMaterial& material : mesh.materials) {
    w.Put(material.name);
    for (int i = 0; i < 4; ++i) w.Put(material.base_color[i]);
    w.Put(material.base_color_texture);
    w.PutList(material.base_color_image);
  }
  w.Put<std::uint64_t>(mesh.joints.size());
  for (const Joint& joint : mesh.joints) {
    w.Put(joint.name);
    w.Put(joint.parent);
    for (int i = 0; i < 16; ++i) w.Put(joint.bind_global.data()[i]);
  }
  w.PutList(mesh.skin_joints);
  w.PutList(mesh.skin_weights);
  w.PutList(mesh.weld_map);
  w.PutList(mesh.welded_positions);
  w.PutList(mesh.welded_triangles);

  const ImportReport& report = imported.report;
  w.Put(report.format);
  w.Put(static_cast<int>(report.source_up));
  w.Put(report.up_source);
  w.Put(report.unit_scale);
  w.Put(report.unit_source);
  w.Put<std::uint64_t>(report.source_vertices);
  return w.Take();
}

Result<ImportedMesh> DecodeImportedMesh(std::string_view bytes) {
  ImportedMesh imported;
  Mesh& mesh = imported.mesh;
  Reader r(bytes);
  if (!r.GetList(mesh.positions) || !r.GetList(mesh.normals) || !r.GetList(mesh.uvs) ||
      !r.GetList(mesh.triangles)) {
    return Damaged("vertices");
  }
  std::uint64_t count = 0;
  if (!r.Get(count)) return Damaged("parts");
  for (std::uint64_t i = 0; i < count; ++i) {
    MeshPart part;
    if (!r.Get(part.name) || !r.Get(part.first_triangle) || !r.Get(part.triangle_count) ||
        !r.Get(part.material)) {
      return Damaged("parts");
    }
    mesh.parts.push_back(std::move(part));
  }
  if (!r.Get(count)) return Damaged("materials");
  for (std::uint64_t i = 0; i < count; ++i) {
    MeshMaterial material;
    bool ok = r.Get(material.name);
    for (int k = 0; k < 4 && ok; ++k) ok = r.Get(material.base_color[k]);
    if (!ok || !r.Get(material.base_color_texture) || !r.GetList(material.base_color_image))
      return Damaged("materials");
    mesh.materials.push_back(std::move(material));
  }
  if (!r.Get(count)) return Damaged("joints");
  for (std::uint64_t i = 0; i < count; ++i) {
    Joint joint;
    bool ok = r.Get(joint.name) && r.Get(joint.parent);
    for (int k = 0; k < 16 && ok; ++k) ok = r.Get(joint.bind_global.data()[k]);
    if (!ok) return Damaged("joints");
    mesh.joints.push_back(std::move(joint));
  }
  if (!r.GetList(mesh.skin_joints) || !r.GetList(mesh.skin_weights) || !r.GetList(mesh.weld_map) ||
      !r.GetList(mesh.welded_positions) || !r.GetList(mesh.welded_triangles)) {
    return Damaged("skin and welding");
  }
  ImportReport& report = imported.report;
  int up = 0;
  if (!r.Get(report.format) || !r.Get(up) || !r.Get(report.up_source) ||
      !r.Get(report.unit_scale) || !r.Get(report.unit_source)) {
    return Damaged("report");
  }
  std::uint64_t source_vertices = 0;
  if (!r.Get(source_vertices) || !r.AtEnd()) return Damaged("report");
  if (up < 0 || up > 2) return Damaged("up axis");
  if (const char* what = Inconsistency(mesh)) return Damaged(what);
  MakeNamesUtf8(mesh);  // a child corrupted without crashing may have sent any bytes
  report.source_up = static_cast<UpAxis>(up);
  report.source_vertices = static_cast<std::size_t>(source_vertices);
  return imported;
}

}  // namespace wirerig
