// Importing meshes with Assimp: bad-input checks before Assimp runs, node transforms, up axis
// and units, materials, skeleton and skin, then welding.
#include "wirerig/rig/mesh_import.h"
#include "wirerig/io/path_messages.h"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <minizip/unzip.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cfenv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "isolated_import.h"
#include "wirerig/io/input_file.h"
#include "wirerig/runtime/cofactors.h"

namespace wirerig {
namespace {

namespace fs = std::filesystem;

// Coordinates beyond this many metres from the origin are refused as absurd (wrong units).
constexpr double kMaxCoordinate = 1e7;
// Entries of composed node transforms beyond this are treated as absurd.
constexpr double kMaxTransformEntry = 1e15;
constexpr std::string_view kNoMeshes =
    "no triangle meshes (the file holds no surface: only points or lines, or a skeleton or "
    "animation alone)";
// How much of a file is read to check the sizes its header claims.
constexpr std::size_t kHeadBytes = 64 * 1024;

using detail::Lowercase;
using detail::PathError;

std::string FormatDouble(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.3g", x);
  return buffer;
}

std::uint64_t SaturatingMul(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) {
    return std::numeric_limits<std::uint64_t>::max();
  }
  return a * b;
}

std::uint64_t SaturatingAdd(std::uint64_t a, std::uint64_t b) {
  return a > std::numeric_limits<std::uint64_t>::max() - b
             ? std::numeric_limits<std::uint64_t>::max()
             : a + b;
}

// Assimp is not written for trapped floating-point exceptions (its smooth normals divide by a
// zero length on degenerate faces, its parsers overflow on huge literals): they are masked
// while it runs, and the caller's environment (traps and flags) is restored afterwards.
class FloatingPointShield {
 public:
  FloatingPointShield() { std::feholdexcept(&saved_); }
  ~FloatingPointShield() { std::fesetenv(&saved_); }
  FloatingPointShield(const FloatingPointShield&) = delete;
  FloatingPointShield& operator=(const FloatingPointShield&) = delete;

 private:
  std::fenv_t saved_;
};

// ---------------------------------------------------------------------------------------------
// Claimed sizes: formats whose header states element counts are checked against
// ImportOptions::max_elements and against the file size before Assimp allocates for them.

// Whitespace-separated tokens of a text header; '#' starts a comment up to the line end.
class HeaderTokens {
 public:
  explicit HeaderTokens(std::string_view text) : text_(text) {}
  std::optional<std::string_view> Next() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') {
        ++pos_;
      } else {
        break;
      }
    }
    if (pos_ >= text_.size()) return std::nullopt;
    const std::size_t begin = pos_;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v' || c == '#') {
        break;
      }
      ++pos_;
    }
    // A token cut by the end of the head may be incomplete.
    if (pos_ >= text_.size()) return std::nullopt;
    return text_.substr(begin, pos_ - begin);
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
};

// A decimal count, saturating at 2^64-1; nullopt when `token` is not one.
std::optional<std::uint64_t> ParseCount(std::string_view token) {
  if (token.empty()) return std::nullopt;
  std::uint64_t value = 0;
  for (const char c : token) {
    if (c < '0' || c > '9') return std::nullopt;
    value = SaturatingAdd(SaturatingMul(value, 10), static_cast<std::uint64_t>(c - '0'));
  }
  return value;
}

std::string ClaimTooLarge(std::uint64_t count, std::string_view what, std::uint64_t limit) {
  return "claims " + std::to_string(count) + " " + std::string(what) + " (" +
         FormatDouble(static_cast<double>(count)) + "), more than the limit of " +
         std::to_string(limit) + " (ImportOptions::max_elements); refused before loading";
}

// OFF: "[ST][C][N][4][n]OFF", then (for nOFF) the dimension, then #vertices #faces [#edges].
std::optional<std::string> CheckOffHeader(std::string_view head, std::uint64_t file_size,
                                          std::uint64_t max_elements) {
  HeaderTokens tokens(head);
  const auto keyword = tokens.Next();
  if (!keyword || keyword->size() < 3 || keyword->size() > 8 ||
      keyword->substr(keyword->size() - 3) != "OFF") {
    return std::nullopt;
  }
  for (const char c : *keyword) {
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == 'n')) return std::nullopt;
  }
  if (keyword->front() == 'n' && !tokens.Next()) return std::nullopt;  // the dimension
  const auto vertices_token = tokens.Next();
  const auto faces_token = tokens.Next();
  if (!vertices_token || !faces_token) return std::nullopt;
  const auto vertices = ParseCount(*vertices_token);
  const auto faces = ParseCount(*faces_token);
  if (!vertices || !faces) return std::nullopt;  // binary or malformed: Assimp decides
  if (*vertices > max_elements) return ClaimTooLarge(*vertices, "vertices", max_elements);
  if (*faces > max_elements) return ClaimTooLarge(*faces, "faces", max_elements);
  // A text vertex takes at least 5 bytes ("0 0 0"), a face at least 1.
  const std::uint64_t needed = SaturatingAdd(SaturatingMul(*vertices, 5), *faces);
  if (needed > file_size) {
    return "claims " + std::to_string(*vertices) + " vertices and " + std::to_string(*faces) +
           " faces, more than its " + std::to_string(file_size) + " bytes can hold";
  }
  return std::nullopt;
}

std::uint64_t PlyScalarSize(std::string_view type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32") {
    return 4;
  }
  if (type == "double" || type == "float64") return 8;
  return 1;
}

// PLY: "element <name> <count>" lines, each followed by its properties.
std::optional<std::string> CheckPlyHeader(std::string_view head, std::uint64_t file_size,
                                          std::uint64_t max_elements) {
  // Assimp 5.2.5 reads a header without an "end_header" line forever.
  std::size_t end = std::string_view::npos;
  for (std::size_t at = head.find("end_header"); at != std::string_view::npos;
       at = head.find("end_header", at + 1)) {
    if (head[at - 1] == '\n' || head[at - 1] == '\r') {
      end = at;
      break;
    }
  }
  if (end == std::string_view::npos) {
    return "its PLY header has no \"end_header\" line in its first " + std::to_string(head.size()) +
           " bytes (truncated or corrupted header)";
  }
  bool ascii = true;
  std::uint64_t needed = 0;
  std::uint64_t count = 0;  // of the current element
  // Line by line, so that "comment" and "obj_info" lines are skipped whatever they say.
  // Sizes below are the least bytes an element can take: 2 per ASCII number ("0 "), the
  // scalar size in binary files, and the count alone for lists.
  std::string_view rest = head.substr(0, end);
  while (!rest.empty()) {
    const std::size_t newline = rest.find('\n');
    const std::string line =
        std::string(rest.substr(0, newline)) + "\n";  // ends every token for HeaderTokens
    rest.remove_prefix(newline == std::string_view::npos ? rest.size() : newline + 1);
    HeaderTokens tokens(line);
    const auto keyword = tokens.Next();
    if (!keyword) continue;
    if (*keyword == "format") {
      const auto format = tokens.Next();
      if (format && format->starts_with("binary")) ascii = false;
    } else if (*keyword == "element") {
      const auto name = tokens.Next();
      const auto count_token = tokens.Next();
      if (!name || !count_token) return std::nullopt;
      const auto parsed = ParseCount(*count_token);
      if (!parsed) return std::nullopt;
      count = *parsed;
      if (count > max_elements) {
        return ClaimTooLarge(count, std::string(*name) + " elements", max_elements);
      }
    } else if (*keyword == "property") {
      auto type = tokens.Next();
      if (!type) return std::nullopt;
      if (*type == "list") {
        type = tokens.Next();  // the count type; the item type and name follow
        if (!type) return std::nullopt;
      }
      needed = SaturatingAdd(needed, SaturatingMul(count, ascii ? 2 : PlyScalarSize(*type)));
    }
  }
  if (needed > file_size) {
    return "its header claims elements needing at least " + std::to_string(needed) +
           " bytes, more than its " + std::to_string(file_size) + " bytes";
  }
  return std::nullopt;
}

// Binary STL (Assimp's rule: the size is exactly 84 + 50 * #triangles).
std::optional<std::string> CheckStlHeader(std::string_view head, std::uint64_t file_size,
                                          std::uint64_t max_elements) {
  if (head.size() < 84) return std::nullopt;
  std::uint64_t triangles = 0;  // little-endian uint32 at byte 80
  for (int i = 3; i >= 0; --i)
    triangles = (triangles << 8) | static_cast<unsigned char>(head[80 + i]);
  if (file_size != 84 + 50 * triangles) return std::nullopt;
  if (triangles > max_elements) return ClaimTooLarge(triangles, "triangles", max_elements);
  return std::nullopt;
}

std::optional<std::string> CheckClaimedSizes(std::string_view head, std::string_view extension,
                                             std::uint64_t file_size, std::uint64_t max_elements) {
  if (head.starts_with("ply\n") || head.starts_with("ply\r")) {
    return CheckPlyHeader(head, file_size, max_elements);
  }
  if (extension == ".stl") return CheckStlHeader(head, file_size, max_elements);
  return CheckOffHeader(head, file_size, max_elements);
}

// ---------------------------------------------------------------------------------------------
// Conversions.

bool IsFinite(const aiVector3D& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

double MaxAbs(const Mat4& m) {
  double result = 0.0;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) result = std::max(result, std::abs(m(r, c)));
  }
  return result;
}

// Assimp's matrices are row-major (a1..a4 is the first row); nullopt if an entry is not
// finite.
std::optional<Mat4> ToMat4(const aiMatrix4x4& a) {
  Mat4 m;
  for (unsigned r = 0; r < 4; ++r) {
    for (unsigned c = 0; c < 4; ++c) {
      const float x = a[r][c];
      if (!std::isfinite(x)) return std::nullopt;
      m(r, c) = x;
    }
  }
  return m;
}

// Inverse of an affine transform, or nullopt when its linear part is (nearly) singular.
std::optional<Mat4> AffineInverse(const Mat4& m) {
  const Mat3 l = m.topLeftCorner<3, 3>();
  const double size = l.cwiseAbs().maxCoeff();
  if (!(size > 1e-30 && size < kMaxTransformEntry)) return std::nullopt;
  const Mat3 cof = Cofactors(l);
  const double det = l.col(0).dot(cof.col(0));
  if (!(std::abs(det) > 1e-12 * size * size * size)) return std::nullopt;
  const Mat3 inverse = cof.transpose() / det;
  Mat4 out = Mat4::Identity();
  out.topLeftCorner<3, 3>() = inverse;
  out.topRightCorner<3, 1>() = -(inverse * m.topRightCorner<3, 1>());
  return out;
}

// The rotation nearest to a transform's linear part (polar decomposition, determinant +1) and
// its translation: joint frames stay rigid whatever scale the source puts on its nodes
// (Blender's FBX files, for one, scale armatures by 100).
Mat4 Rigid(const Mat4& m) {
  Mat4 out = Mat4::Identity();
  out.topRightCorner<3, 1>() = m.topRightCorner<3, 1>();
  const Mat3 l = m.topLeftCorner<3, 3>();
  const double size = l.cwiseAbs().maxCoeff();
  if (!(size > 1e-30)) return out;
  const Eigen::JacobiSVD<Mat3> svd(l / size, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 u = svd.matrixU();
  if ((u * svd.matrixV().transpose()).determinant() < 0.0) u.col(2) = -u.col(2);
  out.topLeftCorner<3, 3>() = u * svd.matrixV().transpose();
  return out;
}

// Rotation taking the source up direction (`axis` times `sign`) to +Y, right-handed.
Mat3 UpRotation(UpAxis axis, int sign) {
  Mat3 r = Mat3::Identity();
  if (axis == UpAxis::kZ) {
    r << 1, 0, 0, 0, 0, 1, 0, -1, 0;  // (x, y, z) -> (x, z, -y)
  } else if (axis == UpAxis::kX) {
    r << 0, -1, 0, 1, 0, 0, 0, 0, 1;  // (x, y, z) -> (-y, x, z)
  }
  if (sign < 0) {
    // First turn half a revolution about an axis perpendicular to the up axis.
    const Vec3 flip = axis == UpAxis::kX ? Vec3(-1, -1, 1) : Vec3(1, -1, -1);
    r = r * flip.asDiagonal();
  }
  return r;
}

std::optional<double> MetadataNumber(const aiMetadata* metadata, const char* key) {
  if (metadata == nullptr) return std::nullopt;
  for (unsigned i = 0; i < metadata->mNumProperties; ++i) {
    if (std::strcmp(metadata->mKeys[i].C_Str(), key) != 0) continue;
    const aiMetadataEntry& entry = metadata->mValues[i];
    if (entry.mData == nullptr) return std::nullopt;
    double value = 0.0;
    switch (entry.mType) {
      case AI_BOOL:
        value = *static_cast<const bool*>(entry.mData) ? 1.0 : 0.0;
        break;
      case AI_INT32:
        value = *static_cast<const std::int32_t*>(entry.mData);
        break;
      case AI_UINT64:
        value = static_cast<double>(*static_cast<const std::uint64_t*>(entry.mData));
        break;
      case AI_FLOAT:
        value = *static_cast<const float*>(entry.mData);
        break;
      case AI_DOUBLE:
        value = *static_cast<const double*>(entry.mData);
        break;
      default:
        return std::nullopt;
    }
    if (!std::isfinite(value)) return std::nullopt;
    return value;
  }
  return std::nullopt;
}

std::string MetadataString(const aiMetadata* metadata, const char* key) {
  if (metadata == nullptr) return {};
  for (unsigned i = 0; i < metadata->mNumProperties; ++i) {
    if (std::strcmp(metadata->mKeys[i].C_Str(), key) != 0) continue;
    const aiMetadataEntry& entry = metadata->mValues[i];
    if (entry.mType != AI_AISTRING || entry.mData == nullptr) return {};
    return static_cast<const aiString*>(entry.mData)->C_Str();
  }
  return {};
}

// Names Assimp makes up ("<OFFRoot>", "$dummy_root") say nothing about the source.
bool IsSyntheticName(std::string_view name) {
  return name.empty() || name.front() == '<' || name.front() == '$';
}

// ---------------------------------------------------------------------------------------------
// The scene walk.

struct NodeRecord {
  const aiNode* node = nullptr;
  int parent = -1;
  int depth = 0;
  Mat4 local = Mat4::Identity();
  Mat4 global = Mat4::Identity();  // in the source frame, after Assimp's own conversions
  bool sane = true;                // finite, moderate transforms up to the root
};

// Pre-order, parents before children; iterative so deep trees cannot overflow the stack.
std::vector<NodeRecord> FlattenNodes(const aiNode* root) {
  std::vector<NodeRecord> nodes;
  std::vector<std::pair<const aiNode*, int>> stack{{root, -1}};
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    if (node == nullptr) continue;
    NodeRecord record;
    record.node = node;
    record.parent = parent;
    record.depth = parent < 0 ? 0 : nodes[parent].depth + 1;
    const std::optional<Mat4> local = ToMat4(node->mTransformation);
    const bool parent_sane = parent < 0 || nodes[parent].sane;
    if (local && parent_sane && MaxAbs(*local) <= kMaxTransformEntry) {
      record.local = *local;
      record.global = parent < 0 ? *local : Mat4(nodes[parent].global * *local);
      record.sane = MaxAbs(record.global) <= kMaxTransformEntry;
    } else {
      record.sane = false;
    }
    const int index = static_cast<int>(nodes.size());
    nodes.push_back(record);
    for (unsigned i = node->mNumChildren; i-- > 0;) stack.emplace_back(node->mChildren[i], index);
  }
  return nodes;
}

struct Instance {
  int node = -1;  // index into the flattened nodes
  const aiMesh* mesh = nullptr;
  // Mesh space -> source world at the bind pose: the node transform for a rigid mesh; for a
  // skinned mesh, bone node transform * bone offset of its bone nearest the root (as skinning
  // computes it; the mesh node's own transform does not apply to skinned vertices).
  Mat4 placement = Mat4::Identity();
  bool placement_sane = true;
  std::vector<std::int64_t> remap;  // source vertex -> render vertex, or -1 if unused
};

struct FrameChoice {
  Mat3 rotation = Mat3::Identity();  // applied by wirerig after Assimp
  double scale = 1.0;                // applied by wirerig after Assimp
};

Vec4 ReadBaseColor(const aiMaterial& material) {
  aiColor4D color;
  if (material.Get(AI_MATKEY_BASE_COLOR, color) == aiReturn_SUCCESS ||
      material.Get(AI_MATKEY_COLOR_DIFFUSE, color) == aiReturn_SUCCESS) {
    Vec4 out(color.r, color.g, color.b, color.a);
    float opacity = 1.0f;
    if (material.Get(AI_MATKEY_OPACITY, opacity) == aiReturn_SUCCESS && std::isfinite(opacity) &&
        opacity >= 0.0f && opacity < 1.0f) {
      out.w() = std::min(out.w(), static_cast<double>(opacity));
    }
    for (int i = 0; i < 4; ++i) {
      if (!std::isfinite(out[i])) return Vec4::Ones();
    }
    return out;
  }
  return Vec4::Ones();
}

// The base colour texture's path as the file gives it ("*N" for an embedded one), or empty.
std::string ReadBaseColorTexture(const aiMaterial& material) {
  aiString path;
  if (material.GetTexture(aiTextureType_BASE_COLOR, 0, &path) != aiReturn_SUCCESS &&
      material.GetTexture(aiTextureType_DIFFUSE, 0, &path) != aiReturn_SUCCESS) {
    return {};
  }
  std::string out = path.C_Str();
  std::replace(out.begin(), out.end(), '\\', '/');
  return out;
}

// A texture larger than this is left to its file (a decompression bomb in an archive).
constexpr std::size_t kMaxTextureBytes = std::size_t{256} << 20;

// The bytes of `entry` in the zip archive `archive` (a .zae), or empty when it has none.
std::vector<unsigned char> ReadArchiveEntry(const fs::path& archive, std::string entry) {
  while (entry.starts_with("./")) entry.erase(0, 2);
  unzFile zip = unzOpen64(archive.c_str());
  if (zip == nullptr) return {};
  std::vector<unsigned char> bytes;
  unz_file_info64 info{};
  if (unzLocateFile(zip, entry.c_str(), /*case sensitive=*/1) == UNZ_OK &&
      unzGetCurrentFileInfo64(zip, &info, nullptr, 0, nullptr, 0, nullptr, 0) == UNZ_OK &&
      info.uncompressed_size > 0 && info.uncompressed_size <= kMaxTextureBytes &&
      unzOpenCurrentFile(zip) == UNZ_OK) {
    bytes.resize(static_cast<std::size_t>(info.uncompressed_size));
    const int read = unzReadCurrentFile(zip, bytes.data(), static_cast<unsigned>(bytes.size()));
    if (unzCloseCurrentFile(zip) != UNZ_OK || read != static_cast<int>(bytes.size())) bytes.clear();
  }
  unzClose(zip);
  return bytes;
}

class SceneConverter {
 public:
  SceneConverter(const fs::path& path, const aiScene& scene, const ImportOptions& options,
                 const FrameChoice& frame)
      : path_(path), scene_(scene), options_(options) {
    conversion_ = Mat4::Identity();
    conversion_.topLeftCorner<3, 3>() = frame.scale * frame.rotation;
    conversion_inverse_ = Mat4::Identity();
    conversion_inverse_.topLeftCorner<3, 3>() = frame.rotation.transpose() / frame.scale;
  }

  Result<Mesh> Convert() {
    nodes_ = FlattenNodes(scene_.mRootNode);
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      node_by_name_.try_emplace(nodes_[n].node->mName.C_Str(), static_cast<int>(n));
    }
    if (auto error = CollectInstances()) return *error;
    if (auto error = BuildGeometry()) return *error;
    ReadMaterials();
    if (auto error = BuildSkeleton()) return *error;
    BuildSkin();
    return std::move(mesh_);
  }

 private:
  std::optional<Error> CollectInstances() {
    std::uint64_t vertices = 0;
    std::uint64_t triangles = 0;
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      const aiNode* node = nodes_[n].node;
      for (unsigned k = 0; k < node->mNumMeshes; ++k) {
        const unsigned m = node->mMeshes[k];
        if (m >= scene_.mNumMeshes || scene_.mMeshes[m] == nullptr) continue;
        const aiMesh* mesh = scene_.mMeshes[m];
        if (mesh->mVertices == nullptr || mesh->mFaces == nullptr) continue;
        vertices = SaturatingAdd(vertices, mesh->mNumVertices);
        triangles = SaturatingAdd(triangles, mesh->mNumFaces);
        if (vertices > options_.max_elements || triangles > options_.max_elements) {
          return PathError(path_, "its mesh instances hold more than the limit of " +
                                      std::to_string(options_.max_elements) +
                                      " vertices or triangles (ImportOptions::max_elements)");
        }
        Instance instance;
        instance.node = static_cast<int>(n);
        instance.mesh = mesh;
        instance.placement = nodes_[n].global;
        instance.placement_sane = nodes_[n].sane;
        PlaceSkinnedInstance(instance);
        instances_.push_back(std::move(instance));
      }
    }
    return std::nullopt;
  }

  void PlaceSkinnedInstance(Instance& instance) const {
    int best_depth = std::numeric_limits<int>::max();
    for (unsigned b = 0; b < instance.mesh->mNumBones; ++b) {
      const aiBone* bone = instance.mesh->mBones[b];
      if (bone == nullptr) continue;
      const int node = FindNode(bone->mName.C_Str());
      if (node < 0 || !nodes_[node].sane || nodes_[node].depth >= best_depth) continue;
      const std::optional<Mat4> offset = ToMat4(bone->mOffsetMatrix);
      if (!offset || MaxAbs(*offset) > kMaxTransformEntry) continue;
      const Mat4 skinning = nodes_[node].global * *offset;
      if (MaxAbs(skinning) > kMaxTransformEntry) continue;
      best_depth = nodes_[node].depth;
      instance.placement = skinning;
      instance.placement_sane = true;
    }
  }

  std::string PartName(const Instance& instance) {
    const aiNode* node = nodes_[instance.node].node;
    const std::string node_name = node->mName.C_Str();
    const std::string mesh_name = instance.mesh->mName.C_Str();
    std::string base;
    if (node->mNumMeshes == 1 && !IsSyntheticName(node_name)) {
      base = node_name;
    } else if (!IsSyntheticName(mesh_name)) {
      base = mesh_name;
    } else if (!IsSyntheticName(node_name)) {
      base = node_name;
    } else {
      base = path_.stem().string();
      if (base.empty()) base = "part";
    }
    std::string name = base;
    for (int k = 2; part_names_.contains(name); ++k) name = base + "_" + std::to_string(k);
    part_names_.insert(name);
    return name;
  }

  std::optional<Error> BuildGeometry() {
    std::uint64_t faces_seen = 0;
    bool any_uvs = false;
    for (const Instance& instance : instances_) {
      any_uvs = any_uvs || instance.mesh->mTextureCoords[0] != nullptr;
    }
    for (Instance& instance : instances_) {
      const aiMesh& mesh = *instance.mesh;
      const NodeRecord& node = nodes_[instance.node];
      const std::string mesh_label = "mesh '" + std::string(mesh.mName.C_Str()) + "'";
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        if (!IsFinite(mesh.mVertices[v])) {
          return PathError(path_, "vertex " + std::to_string(v) + " of " + mesh_label +
                                      " has a non-finite position");
        }
      }
      // Triangles whose corners are three distinct positions; points, lines and collapsed
      // faces are dropped.
      std::vector<Triangle> kept;
      kept.reserve(mesh.mNumFaces);
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        ++faces_seen;
        if (face.mNumIndices != 3 || face.mIndices == nullptr) continue;
        const unsigned a = face.mIndices[0];
        const unsigned b = face.mIndices[1];
        const unsigned c = face.mIndices[2];
        if (a >= mesh.mNumVertices || b >= mesh.mNumVertices || c >= mesh.mNumVertices) continue;
        const aiVector3D& pa = mesh.mVertices[a];
        const aiVector3D& pb = mesh.mVertices[b];
        const aiVector3D& pc = mesh.mVertices[c];
        if (pa == pb || pb == pc || pc == pa) continue;
        kept.push_back({a, b, c});
      }
      if (kept.empty()) continue;
      if (!instance.placement_sane) {
        return PathError(path_, "the transform of node '" + std::string(node.node->mName.C_Str()) +
                                    "' is not finite or absurdly large");
      }

      const Mat4 transform = conversion_ * instance.placement;
      const Mat3 linear = transform.topLeftCorner<3, 3>();
      const Vec3 translation = transform.topRightCorner<3, 1>();
      const Mat3 cofactors = Cofactors(linear);
      const double det = linear.col(0).dot(cofactors.col(0));
      const Mat3 normal_matrix = det < 0.0 ? Mat3(-cofactors) : cofactors;

      instance.remap.assign(mesh.mNumVertices, -1);
      for (const Triangle& t : kept) {
        for (const std::uint32_t v : t) instance.remap[v] = 0;
      }
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        if (instance.remap[v] < 0) continue;
        instance.remap[v] = static_cast<std::int64_t>(mesh_.positions.size());
        const aiVector3D& source = mesh.mVertices[v];
        const Vec3 p = linear * Vec3(source.x, source.y, source.z) + translation;
        const double extent = p.cwiseAbs().maxCoeff();
        if (!(extent <= kMaxCoordinate)) {
          return PathError(path_, "vertex " + std::to_string(v) + " of " + mesh_label + " lies " +
                                      FormatDouble(extent) +
                                      " m from the origin, beyond the limit of 1e7 m (wrong unit "
                                      "scale?)");
        }
        mesh_.positions.push_back(p);

        bool normal_ok = false;
        Vec3 n = Vec3::Zero();
        if (mesh.mNormals != nullptr && IsFinite(mesh.mNormals[v])) {
          const aiVector3D& sn = mesh.mNormals[v];
          n = normal_matrix * Vec3(sn.x, sn.y, sn.z);
          const double length = n.norm();
          if (length > 1e-30 && std::isfinite(length)) {
            n /= length;
            normal_ok = true;
          }
        }
        mesh_.normals.push_back(normal_ok ? n : Vec3::Zero());
        needs_normal_.push_back(!normal_ok);

        if (any_uvs) {
          Vec2 uv = Vec2::Zero();
          if (mesh.mTextureCoords[0] != nullptr) {
            const aiVector3D& t = mesh.mTextureCoords[0][v];
            if (std::isfinite(t.x) && std::isfinite(t.y)) uv = Vec2(t.x, t.y);
          }
          mesh_.uvs.push_back(uv);
        }
      }

      MeshPart part;
      part.name = PartName(instance);
      part.first_triangle = static_cast<std::uint32_t>(mesh_.triangles.size());
      part.triangle_count = static_cast<std::uint32_t>(kept.size());
      part.material =
          mesh.mMaterialIndex < scene_.mNumMaterials ? static_cast<int>(mesh.mMaterialIndex) : -1;
      for (const Triangle& t : kept) {
        Triangle r{static_cast<std::uint32_t>(instance.remap[t[0]]),
                   static_cast<std::uint32_t>(instance.remap[t[1]]),
                   static_cast<std::uint32_t>(instance.remap[t[2]])};
        if (det < 0.0) std::swap(r[1], r[2]);  // a mirroring transform flips the winding
        mesh_.triangles.push_back(r);
      }
      mesh_.parts.push_back(std::move(part));
    }
    if (mesh_.triangles.empty()) {
      if (faces_seen == 0) return PathError(path_, "no triangles (the file holds no faces)");
      return PathError(path_, "no usable triangles: all " + std::to_string(faces_seen) +
                                  " faces are degenerate (repeated or coincident corners)");
    }
    RepairNormals();
    return std::nullopt;
  }

  // Normals the file lacked or that were invalid: area-weighted face normals, else +Y.
  void RepairNormals() {
    if (std::find(needs_normal_.begin(), needs_normal_.end(), true) == needs_normal_.end()) {
      return;
    }
    std::vector<Vec3> sums(mesh_.positions.size(), Vec3::Zero());
    for (const Triangle& t : mesh_.triangles) {
      const Vec3& a = mesh_.positions[t[0]];
      const Vec3 face = (mesh_.positions[t[1]] - a).cross(mesh_.positions[t[2]] - a);
      for (const std::uint32_t v : t) {
        if (needs_normal_[v]) sums[v] += face;
      }
    }
    for (std::size_t v = 0; v < sums.size(); ++v) {
      if (!needs_normal_[v]) continue;
      const double length = sums[v].norm();
      mesh_.normals[v] = length > 1e-300 ? Vec3(sums[v] / length) : Vec3::UnitY();
    }
  }

  void ReadMaterials() {
    for (unsigned i = 0; i < scene_.mNumMaterials; ++i) {
      MeshMaterial material;
      if (scene_.mMaterials[i] != nullptr) {
        const aiMaterial& source = *scene_.mMaterials[i];
        aiString name;
        if (source.Get(AI_MATKEY_NAME, name) == aiReturn_SUCCESS) material.name = name.C_Str();
        material.base_color = ReadBaseColor(source);
        material.base_color_texture = ReadBaseColorTexture(source);
        material.base_color_image = ReadHeldImage(material.base_color_texture);
      }
      mesh_.materials.push_back(std::move(material));
    }
  }

  // The bytes of a texture the source holds itself: embedded in the file (compressed, as PNG or
  // JPEG), or an entry of the .zae archive it was read from. Empty otherwise: the texture is a
  // file next to the source (or missing).
  std::vector<unsigned char> ReadHeldImage(const std::string& texture) const {
    if (texture.empty()) return {};
    if (const aiTexture* embedded = scene_.GetEmbeddedTexture(texture.c_str())) {
      if (embedded->mHeight != 0 || embedded->mWidth > kMaxTextureBytes) return {};  // raw texels
      const auto* bytes = reinterpret_cast<const unsigned char*>(embedded->pcData);
      return {bytes, bytes + embedded->mWidth};
    }
    const std::string extension = Lowercase(path_.extension().string());
    std::error_code error;
    if (extension != ".zae" || fs::exists(path_.parent_path() / texture, error)) return {};
    return ReadArchiveEntry(path_, texture);
  }

  // The first node (in pre-order) with this name, or -1.
  int FindNode(const std::string& name) const {
    const auto it = node_by_name_.find(name);
    return it == node_by_name_.end() ? -1 : it->second;
  }

  // Joints: a joint per bone node, plus the nodes between them and their lowest common
  // ancestor (the scene root excepted) so that the bones form connected trees.
  std::optional<Error> BuildSkeleton() {
    struct BoneSource {
      const aiBone* bone = nullptr;
      int instance = -1;
    };
    std::unordered_map<int, BoneSource> bone_of_node;         // node index -> first bone naming it
    std::vector<std::pair<std::string, BoneSource>> orphans;  // bones without a node
    std::unordered_set<std::string> orphan_names;
    for (std::size_t i = 0; i < instances_.size(); ++i) {
      const aiMesh& mesh = *instances_[i].mesh;
      if (instances_[i].remap.empty()) continue;  // no triangles kept
      for (unsigned b = 0; b < mesh.mNumBones; ++b) {
        const aiBone* bone = mesh.mBones[b];
        if (bone == nullptr) continue;
        const std::string name = bone->mName.C_Str();
        const int node = FindNode(name);
        const BoneSource source{bone, static_cast<int>(i)};
        if (node >= 0) {
          bone_of_node.try_emplace(node, source);
        } else if (orphan_names.insert(name).second) {
          orphans.emplace_back(name, source);
        }
      }
    }
    if (bone_of_node.empty() && orphans.empty()) return std::nullopt;

    int ancestor = -1;  // lowest common ancestor of the bone nodes
    for (const auto& [node, source] : bone_of_node) {
      if (ancestor < 0) {
        ancestor = node;
        continue;
      }
      int a = ancestor;
      int b = node;
      while (nodes_[a].depth > nodes_[b].depth) a = nodes_[a].parent;
      while (nodes_[b].depth > nodes_[a].depth) b = nodes_[b].parent;
      while (a != b) {
        a = nodes_[a].parent;
        b = nodes_[b].parent;
      }
      ancestor = a;
    }
    std::vector<bool> selected(nodes_.size(), false);
    for (const auto& [node, source] : bone_of_node) {
      for (int n = node; n >= 0 && !selected[n]; n = n == ancestor ? -1 : nodes_[n].parent) {
        selected[n] = true;
      }
    }
    if (ancestor == 0 && !bone_of_node.contains(0)) selected[0] = false;  // the scene root

    std::vector<int> joint_of_node(nodes_.size(), -1);
    std::vector<int> node_of_joint;
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      if (!selected[n]) continue;
      Joint joint;
      joint.name = nodes_[n].node->mName.C_Str();
      if (joint.name.empty()) joint.name = "joint" + std::to_string(mesh_.joints.size());
      const int parent = nodes_[n].parent;
      joint.parent = parent >= 0 ? joint_of_node[parent] : -1;
      joint_of_node[n] = static_cast<int>(mesh_.joints.size());
      node_of_joint.push_back(static_cast<int>(n));
      mesh_.joints.push_back(std::move(joint));
    }

    // Bind poses: a bone's from its offset matrix (mesh space -> bone space at bind time)
    // and the instance's placement; other joints from a child joint and the node hierarchy,
    // or their node transforms. All in the converted frame: C * T * C^-1.
    std::vector<bool> known(mesh_.joints.size(), false);
    auto bind_from_bone = [&](const BoneSource& source) -> std::optional<Mat4> {
      const Instance& instance = instances_[source.instance];
      const std::optional<Mat4> offset = ToMat4(source.bone->mOffsetMatrix);
      if (!offset || !instance.placement_sane) return std::nullopt;
      const std::optional<Mat4> bone_to_mesh = AffineInverse(*offset);
      if (!bone_to_mesh) return std::nullopt;
      return Mat4(conversion_ * instance.placement * *bone_to_mesh * conversion_inverse_);
    };
    for (std::size_t j = 0; j < mesh_.joints.size(); ++j) {
      const auto it = bone_of_node.find(node_of_joint[j]);
      if (it == bone_of_node.end()) continue;
      if (const auto bind = bind_from_bone(it->second)) {
        mesh_.joints[j].bind_global = *bind;
        known[j] = true;
      }
    }
    for (std::size_t j = mesh_.joints.size(); j-- > 0;) {
      if (known[j]) continue;
      const NodeRecord& node = nodes_[node_of_joint[j]];
      std::optional<Mat4> bind;
      for (std::size_t c = j + 1; c < mesh_.joints.size() && !bind; ++c) {
        if (mesh_.joints[c].parent != static_cast<int>(j) || !known[c]) continue;
        const std::optional<Mat4> local_inverse = AffineInverse(nodes_[node_of_joint[c]].local);
        if (!local_inverse) continue;
        bind =
            Mat4(mesh_.joints[c].bind_global * conversion_ * *local_inverse * conversion_inverse_);
      }
      if (!bind && node.sane) bind = Mat4(conversion_ * node.global * conversion_inverse_);
      if (bind) {
        mesh_.joints[j].bind_global = *bind;
        known[j] = true;
      }
    }
    for (const auto& [name, source] : orphans) {
      Joint joint;
      joint.name = name;
      if (const auto bind = bind_from_bone(source)) {
        joint.bind_global = *bind;
        known.push_back(true);
      } else {
        known.push_back(false);
      }
      mesh_.joints.push_back(std::move(joint));
    }
    for (std::size_t j = 0; j < mesh_.joints.size(); ++j) {
      Mat4& bind = mesh_.joints[j].bind_global;
      if (!known[j] || !(MaxAbs(bind) <= kMaxTransformEntry) ||
          !(bind.topRightCorner<3, 1>().cwiseAbs().maxCoeff() <= kMaxCoordinate)) {
        return PathError(path_, "joint '" + mesh_.joints[j].name +
                                    "' has no usable bind pose (singular or absurd transforms)");
      }
      bind = Rigid(bind);
    }
    joint_of_node_ = std::move(joint_of_node);
    return std::nullopt;
  }

  // Nearest joint at or above a node, for rigid parts of a skinned model.
  int NearestJoint(int node) const {
    for (int n = node; n >= 0; n = nodes_[n].parent) {
      if (joint_of_node_[n] >= 0) return joint_of_node_[n];
    }
    return -1;
  }

  void BuildSkin() {
    if (mesh_.joints.empty()) return;
    mesh_.skin_joints.assign(mesh_.positions.size(), {-1, -1, -1, -1});
    mesh_.skin_weights.assign(mesh_.positions.size(), Vec4::Zero());
    std::unordered_map<std::string, int> joint_of_name;
    for (std::size_t j = mesh_.joints.size(); j-- > 0;) {
      joint_of_name[mesh_.joints[j].name] = static_cast<int>(j);  // the first one wins
    }
    for (const Instance& instance : instances_) {
      if (instance.remap.empty()) continue;
      const aiMesh& mesh = *instance.mesh;
      std::vector<std::vector<std::pair<double, int>>> influences(mesh.mNumVertices);
      for (unsigned b = 0; b < mesh.mNumBones; ++b) {
        const aiBone* bone = mesh.mBones[b];
        if (bone == nullptr || bone->mWeights == nullptr) continue;
        const auto it = joint_of_name.find(bone->mName.C_Str());
        if (it == joint_of_name.end()) continue;
        for (unsigned w = 0; w < bone->mNumWeights; ++w) {
          const aiVertexWeight& weight = bone->mWeights[w];
          if (weight.mVertexId >= mesh.mNumVertices || !std::isfinite(weight.mWeight) ||
              !(weight.mWeight > 0.0f)) {
            continue;
          }
          auto& list = influences[weight.mVertexId];
          const auto same = std::find_if(list.begin(), list.end(),
                                         [&](const auto& e) { return e.second == it->second; });
          if (same != list.end()) {
            same->first += weight.mWeight;
          } else {
            list.emplace_back(weight.mWeight, it->second);
          }
        }
      }
      const int rigid_joint = NearestJoint(instance.node);
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        if (instance.remap[v] < 0) continue;
        const auto r = static_cast<std::size_t>(instance.remap[v]);
        auto& list = influences[v];
        // Heaviest first; ties by joint index, so the choice is deterministic.
        std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) {
          return a.first != b.first ? a.first > b.first : a.second < b.second;
        });
        if (list.size() > 4) list.resize(4);
        double sum = 0.0;
        for (const auto& [weight, joint] : list) sum += weight;
        if (sum > 0.0 && std::isfinite(sum)) {
          for (std::size_t k = 0; k < list.size(); ++k) {
            mesh_.skin_joints[r][k] = list[k].second;
            mesh_.skin_weights[r][static_cast<Eigen::Index>(k)] = list[k].first / sum;
          }
        } else if (rigid_joint >= 0) {
          mesh_.skin_joints[r][0] = rigid_joint;
          mesh_.skin_weights[r][0] = 1.0;
        }
      }
    }
  }

  const fs::path& path_;
  const aiScene& scene_;
  const ImportOptions& options_;
  Mat4 conversion_;
  Mat4 conversion_inverse_;
  std::vector<NodeRecord> nodes_;
  std::unordered_map<std::string, int> node_by_name_;
  std::vector<Instance> instances_;
  std::vector<bool> needs_normal_;
  std::unordered_set<std::string> part_names_;
  std::vector<int> joint_of_node_;
  Mesh mesh_;
};

// "Collada Importer" -> "Collada".
std::string FormatName(const aiScene& scene, const fs::path& path) {
  std::string name = MetadataString(scene.mMetaData, "SourceAsset_Format");
  const std::size_t importer = name.find(" Importer");
  if (importer != std::string::npos) name.resize(importer);
  if (name.empty()) {
    name = path.extension().string();
    if (!name.empty()) name.erase(0, 1);
    for (char& c : name) {
      if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
    }
  }
  return name;
}

// Whether a mesh the file gives no up axis for is a figure standing along +Z (the other common
// convention: Blender, 3ds Max, CAD): its extent along Z at least kTallOverWide times the
// others (a standing person is 2-4 times as tall as wide) and its width (X) at least
// kWideOverDeep times its depth (Y: shoulders against chest), facing -Y or +Y as Blender's
// figures do. Bounding boxes cannot tell more: a quadruped modelled +Y up along Z (taller than
// wide: the Wuson bison, 2.1 times as long as tall) and a spider lying flat (1.3 times as long
// as wide) keep +Y; so do figures in a T-pose or facing X. Measured over the test assets in
// docs/rig-formats.md: HUMAN.blend, man.off and XGL's BCN_Epileptic stand along Z; nothing else.
constexpr double kTallOverWide = 1.8;
constexpr double kWideOverDeep = 1.3;
bool StandsAlongZ(const Mesh& mesh) {
  const Bounds bounds = ComputeBounds(mesh);
  const Vec3 extent = bounds.max - bounds.min;
  return extent.z() > kTallOverWide * std::max(extent.x(), extent.y()) &&
         extent.x() > kWideOverDeep * extent.y();
}

// Up axis and units: the option, else what the file says, else +Y and metres. Assimp's
// Collada loader already applies <up_axis> and <unit> with a transform on the root node
// (unless told to ignore the up axis), so for Collada that transform is read back.
Result<FrameChoice> ChooseFrame(const fs::path& path, const aiScene& scene,
                                const ImportOptions& options, const std::string& format,
                                ImportReport& report) {
  FrameChoice frame;
  const bool collada = format.find("Collada") != std::string::npos;
  const bool fbx = format.find("FBX") != std::string::npos;

  double collada_scale = 1.0;
  UpAxis collada_up = UpAxis::kY;
  if (collada) {
    const std::optional<Mat4> root = ToMat4(scene.mRootNode->mTransformation);
    if (root) {
      const Mat3 l = root->topLeftCorner<3, 3>();
      const double s = l.col(0).norm();
      if (s > 0.0 && std::isfinite(s)) {
        collada_scale = s;
        const Mat3 r = l / s;
        if ((r - UpRotation(UpAxis::kZ, 1)).cwiseAbs().maxCoeff() < 1e-6) {
          collada_up = UpAxis::kZ;
        } else if ((r - UpRotation(UpAxis::kX, 1)).cwiseAbs().maxCoeff() < 1e-6) {
          collada_up = UpAxis::kX;
        }
      }
    }
  }

  if (options.up_axis) {
    // For Collada, Assimp was told to ignore the file's up axis.
    report.source_up = *options.up_axis;
    report.up_source = "option";
    frame.rotation = UpRotation(*options.up_axis, 1);
  } else if (collada) {
    report.source_up = collada_up;
    report.up_source = "file metadata";  // applied by Assimp
  } else if (const auto axis = MetadataNumber(scene.mMetaData, "UpAxis");
             axis && (*axis == 0.0 || *axis == 1.0 || *axis == 2.0)) {
    const UpAxis up = *axis == 0.0 ? UpAxis::kX : *axis == 2.0 ? UpAxis::kZ : UpAxis::kY;
    const auto sign = MetadataNumber(scene.mMetaData, "UpAxisSign");
    report.source_up = up;
    report.up_source = "file metadata";
    frame.rotation = UpRotation(up, sign && *sign < 0.0 ? -1 : 1);
  } else {
    report.source_up = UpAxis::kY;
    report.up_source = "assumed";
  }

  if (options.unit_scale) {
    const double scale = *options.unit_scale;
    if (!std::isfinite(scale) || !(scale >= 1e-12 && scale <= 1e12)) {
      return PathError(path,
                       "the unit_scale option must be a finite number in [1e-12, 1e12] (got " +
                           FormatDouble(scale) + ")");
    }
    report.unit_scale = scale;
    report.unit_source = "option";
    frame.scale = collada ? scale / collada_scale : scale;  // undo Assimp's Collada scaling
  } else if (collada) {
    report.unit_scale = collada_scale;
    report.unit_source = "file metadata";  // applied by Assimp
  } else if (const auto factor = MetadataNumber(scene.mMetaData, "UnitScaleFactor");
             fbx && factor && *factor > 0.0) {
    // FBX states centimetres per file unit.
    frame.scale = *factor * 0.01;
    report.unit_scale = frame.scale;
    report.unit_source = "file metadata";
  } else {
    report.unit_scale = 1.0;
    report.unit_source = "assumed";
  }
  if (!(frame.scale >= 1e-12 && frame.scale <= 1e12)) {
    return PathError(path, "unit scale " + FormatDouble(frame.scale) + " is absurd");
  }
  return frame;
}

}  // namespace

std::string_view ToString(UpAxis axis) {
  switch (axis) {
    case UpAxis::kX:
      return "x";
    case UpAxis::kY:
      return "y";
    case UpAxis::kZ:
      return "z";
  }
  return "?";
}

bool ParseUpAxis(std::string_view name, UpAxis* out) {
  if (name.starts_with('+')) name.remove_prefix(1);
  const std::string lower = Lowercase(name);
  UpAxis axis;
  if (lower == "x") {
    axis = UpAxis::kX;
  } else if (lower == "y") {
    axis = UpAxis::kY;
  } else if (lower == "z") {
    axis = UpAxis::kZ;
  } else {
    return false;
  }
  if (out != nullptr) *out = axis;
  return true;
}

Result<ImportedMesh> ImportMesh(const fs::path& path, const ImportOptions& options) {
  // The file itself: exists, is a regular file (input_file.h), can be read, is not empty.
  Result<std::uintmax_t> checked = CheckInputFile(path, "mesh file", options.max_file_bytes);
  if (!checked) return Error{checked.error()};
  const std::uintmax_t file_size = checked.value();

  std::string head;
  {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) {
      const int error = errno;
      return PathError(path, "cannot open (" + std::string(std::strerror(error)) + ")");
    }
    head.resize(static_cast<std::size_t>(std::min<std::uintmax_t>(file_size, kHeadBytes)));
    const std::size_t read = std::fread(head.data(), 1, head.size(), file);
    const bool failed = std::ferror(file) != 0;
    std::fclose(file);
    if (failed) return PathError(path, "cannot read (I/O error)");
    head.resize(read);
  }
  if (file_size == 0) return PathError(path, "file is empty (0 bytes)");

  const std::string extension = Lowercase(path.extension().string());
  if (const auto problem = CheckClaimedSizes(head, extension, file_size, options.max_elements)) {
    return PathError(path, *problem);
  }
  // What was cheap to check is checked here; the rest runs in a child when asked.
  if (options.isolation) return ImportMeshIsolated(path, options);

  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  importer.SetPropertyInteger(AI_CONFIG_PP_LBW_MAX_WEIGHTS, 4);
  // Skeleton-only files (BVH) get no made-up pyramid mesh: they hold no surface.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  if (options.up_axis) importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // UVs with glTF's origin (top-left of the image); normals are only generated when missing.
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_SortByPType | aiProcess_GenSmoothNormals |
                         aiProcess_LimitBoneWeights | aiProcess_ValidateDataStructure |
                         aiProcess_FlipUVs;
  const aiScene* scene = nullptr;
  std::string assimp_error;
  try {
    const FloatingPointShield shield;
    scene = importer.ReadFile(path.string(), flags);
    if (scene == nullptr) assimp_error = importer.GetErrorString();
  } catch (const std::bad_alloc&) {
    return PathError(path, "cannot import: out of memory");
  } catch (const std::exception& e) {
    return PathError(path, std::string("cannot import: ") + e.what());
  }
  if (scene == nullptr) {
    if (assimp_error.find("No suitable reader") != std::string::npos) {
      return PathError(
          path, "unknown or unsupported file format" +
                    (extension.empty() ? std::string() : " (extension '" + extension + "')"));
    }
    if (assimp_error.find("mNumMeshes is 0") != std::string::npos ||
        assimp_error.find("No meshes remaining") != std::string::npos) {
      return PathError(path, kNoMeshes);
    }
    // Assimp catches its own allocation failures and reports their what().
    if (assimp_error.find("bad_alloc") != std::string::npos) {
      return PathError(path, "cannot import: out of memory");
    }
    if (assimp_error.empty()) assimp_error = "unknown Assimp error";
    return PathError(path, "cannot import: " + assimp_error);
  }
  if (scene->mRootNode == nullptr || scene->mNumMeshes == 0 ||
      (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    return PathError(path, kNoMeshes);
  }

  ImportedMesh imported;
  ImportReport& report = imported.report;
  report.format = FormatName(*scene, path);
  Result<FrameChoice> frame = ChooseFrame(path, *scene, options, report.format, report);
  if (!frame) return Error{frame.error()};

  Result<Mesh> mesh = SceneConverter(path, *scene, options, frame.value()).Convert();
  if (!mesh) return Error{mesh.error()};
  if (report.up_source == "assumed" && StandsAlongZ(mesh.value())) {
    report.source_up = UpAxis::kZ;
    report.up_source = "shape: a standing figure's long axis";
    frame.value().rotation = UpRotation(UpAxis::kZ, 1);
    mesh = SceneConverter(path, *scene, options, frame.value()).Convert();
    if (!mesh) return Error{mesh.error()};
  }
  imported.mesh = std::move(mesh).value();
  MakeNamesUtf8(imported.mesh);  // Assimp hands names over as the file's bytes
  report.source_vertices = imported.mesh.positions.size();
  WeldByPosition(imported.mesh, 0.0);
  return imported;
}

}  // namespace wirerig
