// Scenes for the viewer tests: procedural meshes converted to render meshes, and a guard that
// turns floating-point traps off around OpenGL calls.
#pragma once

#include <vector>

#include "support/no_fp_traps.h"
#include "wirerig/procedural/shapes.h"
#include "wirerig/viewer/render_frame.h"

namespace wirerig::testing {

// Every test that calls OpenGL turns the floating-point traps off for its duration
// (ScopedNoFpTraps, support/no_fp_traps.h): Mesa computes with Inf and NaN on purpose.

// A mesh owning its float buffers; View() is the RenderMesh over them.
struct OwnedMesh {
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;
  std::vector<Triangle> triangles;
  std::vector<float> scalars;
  Vec3f color{0.80f, 0.30f, 0.10f};

  RenderMesh View() const {
    RenderMesh mesh;
    mesh.positions = positions;
    mesh.normals = normals;
    mesh.triangles = triangles;
    mesh.scalars = scalars;
    mesh.base_color = color;
    return mesh;
  }
  void UpdateNormals() { ComputeVertexNormals(positions, triangles, normals); }
};

inline OwnedMesh ToOwnedMesh(const Mesh& mesh) {
  OwnedMesh out;
  out.positions.reserve(mesh.positions.size());
  for (const Vec3& p : mesh.positions) out.positions.push_back(p.cast<float>());
  out.triangles = mesh.triangles;
  out.normals.resize(out.positions.size());
  out.UpdateNormals();
  return out;
}

// A capsule of radius 0.2 m and cylinder height 1 m lying along +X, centred at x = 0, its axis
// `lift` metres above y = 0.
inline OwnedMesh LyingCapsule(float lift) {
  OwnedMesh mesh = ToOwnedMesh(MakeCapsule(0.2, 1.0, 48, 16, 8));
  // A rotation (not a mirror) keeps the triangles counter-clockwise seen from outside.
  for (Vec3f& p : mesh.positions) p = Vec3f(p.y() - 0.5f, lift - p.x(), p.z());
  mesh.UpdateNormals();
  return mesh;
}

}  // namespace wirerig::testing
