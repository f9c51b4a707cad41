#include "gltf_input.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "float_finite.h"

namespace wirerig::gltf {
namespace {

using Message = std::optional<std::string>;

std::string Indexed(const std::string& field, std::size_t i) {
  std::string s = field;
  s.append("[").append(std::to_string(i)).append("]");
  return s;
}

std::string SizeMismatch(const std::string& field, std::size_t expected, std::size_t got) {
  std::string s = field;
  s.append(": expected ")
      .append(std::to_string(expected))
      .append(" entries, got ")
      .append(std::to_string(got));
  return s;
}

// Component by component with std::isfinite: Eigen's allFinite computes x - x, which raises
// FE_INVALID on an infinity.
template <typename V>
bool AllFinite(const V& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}
bool AllFinite(const Quat& q) { return AllFinite(q.coeffs()); }

template <typename V>
Message CheckFinite(const std::vector<V>& values, const std::string& field) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!AllFinite(values[i])) return Indexed(field, i).append(": not finite");
  }
  return std::nullopt;
}

// The bake's float vectors (#K x #V, up to ~10^7 values): the check Playback::Evaluate makes
// on every frame it outputs (float_finite.h).
Message CheckFinite(const std::vector<Vec3f>& values, const std::string& field) {
  static_assert(sizeof(Vec3f) == 3 * sizeof(float));
  const std::size_t bad = detail::FirstNonFiniteFloat3(
      {values.empty() ? nullptr : values.data()->data(), 3 * values.size()}, values.size());
  if (bad == detail::kAllFinite) return std::nullopt;
  return Indexed(field, bad).append(": not finite");
}

Message CheckMesh(const Mesh& mesh) {
  const std::size_t v = mesh.positions.size();
  if (v == 0) return "mesh.positions: empty";
  if (mesh.triangles.empty()) return "mesh.triangles: empty";
  if (Message m = CheckFinite(mesh.positions, "mesh.positions")) return m;
  if (!mesh.normals.empty() && mesh.normals.size() != v) {
    return SizeMismatch("mesh.normals", v, mesh.normals.size());
  }
  if (Message m = CheckFinite(mesh.normals, "mesh.normals")) return m;
  if (!mesh.uvs.empty() && mesh.uvs.size() != v) {
    return SizeMismatch("mesh.uvs", v, mesh.uvs.size());
  }
  if (Message m = CheckFinite(mesh.uvs, "mesh.uvs")) return m;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (std::uint32_t i : mesh.triangles[f]) {
      if (i >= v) return Indexed("mesh.triangles", f).append(": vertex index out of range");
    }
  }
  for (std::size_t p = 0; p < mesh.parts.size(); ++p) {
    const MeshPart& part = mesh.parts[p];
    if (std::size_t{part.first_triangle} + part.triangle_count > mesh.triangles.size()) {
      return Indexed("mesh.parts", p).append(": triangle range beyond mesh.triangles");
    }
    if (part.material >= static_cast<int>(mesh.materials.size())) {
      return Indexed("mesh.parts", p).append(".material: out of range");
    }
  }
  for (std::size_t m = 0; m < mesh.materials.size(); ++m) {
    if (!AllFinite(mesh.materials[m].base_color)) {
      return Indexed("mesh.materials", m).append(".base_color: not finite");
    }
  }
  return std::nullopt;
}

Message CheckKeys(const Mesh& mesh, const BakedAnimation& bake) {
  const std::size_t k = bake.KeyCount();
  const std::size_t v = mesh.positions.size();
  if (k == 0) return "bake.times: no keys";
  for (std::size_t i = 0; i < k; ++i) {
    if (!std::isfinite(bake.times[i])) return Indexed("bake.times", i).append(": not finite");
    if (i > 0 && !(static_cast<float>(bake.times[i]) > static_cast<float>(bake.times[i - 1]))) {
      return Indexed("bake.times", i).append(": not increasing (as float seconds)");
    }
  }
  if (bake.times[0] < 0.0) return "bake.times[0]: negative";
  if (bake.vertex_count != v) {
    std::string message = "bake.vertex_count: ";
    message.append(std::to_string(bake.vertex_count))
        .append(" but the mesh has ")
        .append(std::to_string(v))
        .append(" render vertices");
    return message;
  }
  if (bake.positions.size() != k * v)
    return SizeMismatch("bake.positions", k * v, bake.positions.size());
  if (Message m = CheckFinite(bake.positions, "bake.positions")) return m;
  if (!bake.normals.empty() && bake.normals.size() != k * v) {
    return SizeMismatch("bake.normals", k * v, bake.normals.size());
  }
  return CheckFinite(bake.normals, "bake.normals");
}

Message CheckSpines(const BakedAnimation& bake) {
  const std::size_t k = bake.KeyCount();
  if (bake.spines.empty()) return "bake.spines: empty (skin mode needs the spines)";
  for (std::size_t i = 0; i < bake.spines.size(); ++i) {
    const BakedSpine& spine = bake.spines[i];
    const std::string field = Indexed("bake.spines", i);
    const std::size_t s = spine.SampleCount();
    if (s == 0) return field + ".rest_points: empty";
    if (spine.rest_rotations.size() != s) {
      return SizeMismatch(field + ".rest_rotations", s, spine.rest_rotations.size());
    }
    if (spine.points.size() != k * s)
      return SizeMismatch(field + ".points", k * s, spine.points.size());
    if (spine.rotations.size() != k * s) {
      return SizeMismatch(field + ".rotations", k * s, spine.rotations.size());
    }
    if (Message m = CheckFinite(spine.rest_points, field + ".rest_points")) return m;
    if (Message m = CheckFinite(spine.points, field + ".points")) return m;
    for (std::size_t j = 0; j < s; ++j) {
      if (!AllFinite(spine.rest_rotations[j]) || spine.rest_rotations[j].norm() < 1e-6) {
        return Indexed(field + ".rest_rotations", j).append(": not a finite rotation");
      }
    }
    for (std::size_t j = 0; j < k * s; ++j) {
      if (!AllFinite(spine.rotations[j]) || spine.rotations[j].norm() < 1e-6) {
        return Indexed(field + ".rotations", j).append(": not a finite rotation");
      }
    }
    if (spine.parent < -1 || spine.parent >= static_cast<int>(i)) {
      return field + ".parent: must be -1 or name an earlier spine";
    }
    if (spine.parent >= 0) {
      const BakedSpine& parent = bake.spines[static_cast<std::size_t>(spine.parent)];
      if (spine.parent_joint < 0 ||
          static_cast<std::size_t>(spine.parent_joint) >= parent.SampleCount()) {
        return field + ".parent_joint: out of range of the parent's samples";
      }
    }
  }
  return std::nullopt;
}

Message CheckSkinWeights(const BakedAnimation& bake) {
  const std::size_t v = bake.vertex_count;
  std::size_t joints = 0;
  for (const BakedSpine& spine : bake.spines) joints += spine.SampleCount();
  if (joints > 65536) return "bake.spines: more than 65536 joints in all";
  if (bake.skin_joints.size() != v)
    return SizeMismatch("bake.skin_joints", v, bake.skin_joints.size());
  if (bake.skin_weights.size() != v) {
    return SizeMismatch("bake.skin_weights", v, bake.skin_weights.size());
  }
  for (std::size_t i = 0; i < v; ++i) {
    const Vec4f& w = bake.skin_weights[i];
    if (!AllFinite(w) || (w.array() < 0.0f).any()) {
      return Indexed("bake.skin_weights", i).append(": negative or not finite");
    }
    if (!(w.sum() > 0.0f)) return Indexed("bake.skin_weights", i).append(": all zero");
    for (int c = 0; c < 4; ++c) {
      if (w[c] > 0.0f && bake.skin_joints[i][static_cast<std::size_t>(c)] >= joints) {
        return Indexed("bake.skin_joints", i).append(": joint index out of range");
      }
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> CheckExportInput(const Mesh& mesh, const BakedAnimation& bake,
                                            GltfAnimationMode mode) {
  if (Message m = CheckMesh(mesh)) return m;
  if (Message m = CheckKeys(mesh, bake)) return m;
  if (mode != GltfAnimationMode::kSkin) return std::nullopt;
  if (Message m = CheckSpines(bake)) return m;
  return CheckSkinWeights(bake);
}

}  // namespace wirerig::gltf
