// Mesh: wirerig's own triangle mesh, as imported from any format Assimp reads or made
// procedurally. Metres, glTF axes (+Y up), counter-clockwise triangles facing outwards.
//
// Two vertex sets. Render vertices (#V) are what the source file had: a vertex per distinct
// (position, normal, uv), so texture seams split vertices; exporters write these back.
// Welded vertices (#W) merge render vertices at the same position, so seams are not holes;
// topology, ray casting, volumes and rig building use these.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "wirerig/runtime/conventions.h"

namespace wirerig {

using Vec2 = Eigen::Vector2d;
using Vec4 = Eigen::Vector4d;
using Mat4 = Eigen::Matrix4d;

// A named piece of the mesh (one Assimp mesh instance): a contiguous range of triangles.
struct MeshPart {
  std::string name;
  std::uint32_t first_triangle = 0;
  std::uint32_t triangle_count = 0;
  int material = -1;  // index into Mesh::materials, or -1
};

struct MeshMaterial {
  std::string name;
  Vec4 base_color = Vec4::Ones();  // linear RGBA
  std::string base_color_texture;  // path relative to the source file, or empty
  // The texture's PNG or JPEG bytes when the source holds them itself (an entry of a .zae
  // archive, a texture embedded in the file); then base_color_texture only names it.
  std::vector<unsigned char> base_color_image;
};

// A joint of the source skeleton. Parents come before their children.
struct Joint {
  std::string name;
  int parent = -1;  // index into Mesh::joints, or -1 for a root
  // Joint-to-world transform at the bind pose: rigid (rotation and translation; any scale the
  // source puts on its nodes is left out).
  Mat4 bind_global = Mat4::Identity();
};

struct Mesh {
  // Render vertices, #V each (normals and uvs may be empty). UVs follow glTF: origin at the
  // top-left of the image, v pointing down (ImportMesh flips Assimp's bottom-left origin).
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<Vec2> uvs;
  // #F triangles over render vertices; parts cover them in order, without gaps.
  std::vector<Triangle> triangles;
  std::vector<MeshPart> parts;
  std::vector<MeshMaterial> materials;

  // Skeleton and skin, empty when the source has none. Up to 4 influences per render vertex:
  // joint index or -1 for an unused slot; weights sum to 1 (a vertex that no joint influences
  // has all slots -1 and zero weights).
  std::vector<Joint> joints;
  std::vector<std::array<int, 4>> skin_joints;
  std::vector<Vec4> skin_weights;

  // Welding (WeldByPosition fills these): render vertex -> welded vertex (#V), the welded
  // positions (#W), and the #F triangles over welded vertices, in the same order.
  std::vector<std::uint32_t> weld_map;
  std::vector<Vec3> welded_positions;
  std::vector<Triangle> welded_triangles;
};

// Makes every name in `mesh` (parts, materials, joints) valid UTF-8 (ValidUtf8): names from
// mesh files may hold any bytes, and what writes them (JSON, glTF) takes UTF-8 only.
void MakeNamesUtf8(Mesh& mesh);

// Merges render vertices whose positions are within `tolerance` metres (exactly equal when 0)
// and fills the weld fields. Deterministic: a welded vertex takes the position of its first
// render vertex, and with a tolerance a render vertex joins the lowest-numbered welded vertex
// within reach of that position (merging does not chain along a row of close vertices).
void WeldByPosition(Mesh& mesh, double tolerance = 0.0);

// Axis-aligned bounds of the welded positions (render positions if not welded).
struct Bounds {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
  double Diagonal() const { return (max - min).norm(); }
};
Bounds ComputeBounds(const Mesh& mesh);

}  // namespace wirerig
