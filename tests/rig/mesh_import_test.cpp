// Tests for ImportMesh on real meshes (Assimp's test models and CGAL's demo meshes, see
// ASSETS.md) and on bad input: every file of Assimp's invalid/ folder, files that claim
// absurd sizes, non-finite or absurd coordinates, missing, unreadable and unknown files.
// Counts are what Assimp 5.2.5 reports after triangulation and joining identical vertices.
#include "wirerig/rig/mesh_import.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "wirerig/rig/mesh_statistics.h"

#ifndef WIRERIG_ASSET_DIR
#error "the tests need WIRERIG_ASSET_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

fs::path Asset(const std::string& relative) { return fs::path(WIRERIG_ASSET_DIR) / relative; }

// Fails the test when an asset is missing (scripts/setup.sh fetches them): a missing asset
// must never pass unnoticed.
#define REQUIRE_ASSET(path)                                                        \
  do {                                                                             \
    if (!fs::exists(path)) {                                                       \
      FAIL() << "asset missing: " << (path).string() << " (run scripts/setup.sh)"; \
    }                                                                              \
  } while (false)

// A scratch file in the test's temporary folder.
fs::path WriteFile(const std::string& name, const std::string& contents) {
  const fs::path path = fs::path(::testing::TempDir()) / ("wirerig_mesh_import_" + name);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << contents;
  return path;
}

bool IsFinite(const Vec3& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

// The triangles of one part over the mesh's render positions, welded on their own.
Mesh PartMesh(const Mesh& mesh, const MeshPart& part) {
  Mesh sub;
  sub.positions = mesh.positions;
  for (std::uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
    sub.triangles.push_back(mesh.triangles[t]);
  }
  WeldByPosition(sub);
  return sub;
}

// Signed volume enclosed by a part's triangles (positive when they face outwards).
double SignedVolume(const Mesh& mesh, const MeshPart& part) {
  double six_volume = 0.0;
  for (std::uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
    const Triangle& tri = mesh.triangles[t];
    six_volume += mesh.positions[tri[0]].dot(mesh.positions[tri[1]].cross(mesh.positions[tri[2]]));
  }
  return six_volume / 6.0;
}

// Every render-vertex array has #V entries (or none), every normal is a finite unit vector,
// every triangle names existing vertices and the parts cover the triangles in order.
void ExpectWellFormed(const Mesh& mesh) {
  const std::size_t v = mesh.positions.size();
  ASSERT_EQ(mesh.normals.size(), v);
  EXPECT_TRUE(mesh.uvs.empty() || mesh.uvs.size() == v);
  for (std::size_t i = 0; i < v; ++i) {
    ASSERT_TRUE(IsFinite(mesh.positions[i])) << i;
    ASSERT_TRUE(IsFinite(mesh.normals[i])) << i;
    ASSERT_NEAR(mesh.normals[i].norm(), 1.0, 1e-9) << i;
  }
  for (const Triangle& t : mesh.triangles) {
    for (const std::uint32_t index : t) ASSERT_LT(index, v);
  }
  std::uint32_t next = 0;
  for (const MeshPart& part : mesh.parts) {
    EXPECT_EQ(part.first_triangle, next) << part.name;
    EXPECT_GT(part.triangle_count, 0u) << part.name;
    EXPECT_LT(part.material, static_cast<int>(mesh.materials.size())) << part.name;
    next += part.triangle_count;
  }
  EXPECT_EQ(next, mesh.triangles.size());
  ASSERT_EQ(mesh.weld_map.size(), v);
  ASSERT_EQ(mesh.welded_triangles.size(), mesh.triangles.size());
  for (std::size_t i = 0; i < v; ++i) {
    ASSERT_LT(mesh.weld_map[i], mesh.welded_positions.size());
    ASSERT_EQ(mesh.welded_positions[mesh.weld_map[i]], mesh.positions[i]);
  }
}

// Skin: #V entries, at most 4 influences, weights non-negative and summing to 1, slots with
// weight 0 unused (-1), used slots name existing joints; joints list parents first.
void ExpectValidSkin(const Mesh& mesh) {
  ASSERT_EQ(mesh.skin_joints.size(), mesh.positions.size());
  ASSERT_EQ(mesh.skin_weights.size(), mesh.positions.size());
  const int joint_count = static_cast<int>(mesh.joints.size());
  for (int j = 0; j < joint_count; ++j) {
    EXPECT_LT(mesh.joints[j].parent, j) << mesh.joints[j].name;
    EXPECT_GE(mesh.joints[j].parent, -1) << mesh.joints[j].name;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(mesh.joints[j].bind_global(r, c)));
    }
  }
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) {
      const double w = mesh.skin_weights[v][k];
      const int joint = mesh.skin_joints[v][k];
      ASSERT_TRUE(std::isfinite(w));
      ASSERT_GE(w, 0.0) << v;
      if (w > 0.0) {
        ASSERT_GE(joint, 0) << v;
        ASSERT_LT(joint, joint_count) << v;
      } else {
        ASSERT_EQ(joint, -1) << v;
      }
      sum += w;
    }
    ASSERT_NEAR(sum, 1.0, 1e-9) << "vertex " << v;
  }
}

int JointIndex(const Mesh& mesh, const std::string& name) {
  for (std::size_t j = 0; j < mesh.joints.size(); ++j) {
    if (mesh.joints[j].name == name) return static_cast<int>(j);
  }
  return -1;
}

// ---------------------------------------------------------------------------------------------
// Real meshes.

TEST(MeshImport, HumanZaeIsYUpMetresWithClosedBodyAndOpenEyes) {
  const fs::path path = Asset("assimp/Collada/human.zae");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  const Mesh& mesh = imported.value().mesh;
  const ImportReport& report = imported.value().report;
  ExpectWellFormed(mesh);

  // Assimp: body 14517 vertices / 26756 triangles, eyes 1076 / 2040.
  EXPECT_EQ(mesh.positions.size(), 15593u);
  EXPECT_EQ(mesh.triangles.size(), 28796u);
  EXPECT_EQ(mesh.welded_positions.size(), 14444u);  // UV seams merged
  EXPECT_EQ(report.source_vertices, 15593u);
  EXPECT_EQ(report.format, "Collada");
  EXPECT_EQ(report.source_up, UpAxis::kY);
  EXPECT_EQ(report.up_source, "file metadata");  // <up_axis>Y_UP, applied by Assimp
  EXPECT_DOUBLE_EQ(report.unit_scale, 1.0);
  EXPECT_EQ(report.unit_source, "file metadata");  // <unit meter="1.0000">

  const Bounds bounds = ComputeBounds(mesh);
  EXPECT_NEAR(bounds.max.y() - bounds.min.y(), 1.66, 0.01);  // a MakeHuman female, in metres
  EXPECT_NEAR(bounds.min.y(), 0.0, 0.01);                    // standing on y = 0
  EXPECT_NEAR(bounds.min.x(), -bounds.max.x(), 1e-3);        // symmetric about x = 0

  ASSERT_EQ(mesh.parts.size(), 2u);
  EXPECT_EQ(mesh.parts[0].name, "human-baseObject");
  EXPECT_EQ(mesh.parts[0].triangle_count, 26756u);
  EXPECT_EQ(mesh.parts[1].name, "human-highpolyeyesObject");
  EXPECT_EQ(mesh.parts[1].triangle_count, 2040u);
  ASSERT_EQ(mesh.materials.size(), 2u);
  EXPECT_EQ(mesh.materials[mesh.parts[0].material].name, "DefaultSkin");
  EXPECT_EQ(mesh.materials[mesh.parts[1].material].name, "Eye_brown");
  EXPECT_EQ(mesh.materials[mesh.parts[1].material].base_color_texture, "./textures/brown_eye.png");
  // The eye texture lives inside the .zae archive (no file next to it): its bytes are read from
  // the archive, the whole PNG (610,817 bytes, as `unzip -l` lists it). The skin has none.
  const std::vector<unsigned char>& eye = mesh.materials[mesh.parts[1].material].base_color_image;
  ASSERT_EQ(eye.size(), 610817u);
  EXPECT_EQ(std::string(eye.begin() + 1, eye.begin() + 4), "PNG");
  EXPECT_TRUE(mesh.materials[mesh.parts[0].material].base_color_image.empty());
  EXPECT_NEAR(mesh.materials[mesh.parts[0].material].base_color.x(), 0.5903, 1e-6);

  const MeshStatistics body = ComputeMeshStatistics(PartMesh(mesh, mesh.parts[0]));
  EXPECT_TRUE(body.closed());
  EXPECT_EQ(body.connected_components, 1u);
  const MeshStatistics eyes = ComputeMeshStatistics(PartMesh(mesh, mesh.parts[1]));
  EXPECT_FALSE(eyes.closed());
  EXPECT_EQ(eyes.boundary_edges, 80u);
  EXPECT_EQ(eyes.connected_components, 4u);  // two eyeballs and two corneas
  const MeshStatistics all = ComputeMeshStatistics(mesh);
  EXPECT_EQ(all.connected_components, 5u);
  EXPECT_EQ(all.non_manifold_edges, 0u);
  EXPECT_EQ(all.degenerate_triangles, 0u);
  EXPECT_TRUE(mesh.joints.empty());  // the file has no skeleton
}

TEST(MeshImport, CowOffIsClosedAndConnected) {
  const fs::path path = Asset("cow.off");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  const Mesh& mesh = imported.value().mesh;
  ExpectWellFormed(mesh);
  EXPECT_EQ(mesh.positions.size(), 2903u);
  EXPECT_EQ(mesh.welded_positions.size(), 2903u);
  EXPECT_EQ(mesh.triangles.size(), 5804u);
  EXPECT_EQ(imported.value().report.format, "OFF");
  EXPECT_EQ(imported.value().report.up_source, "assumed");
  EXPECT_EQ(imported.value().report.unit_source, "assumed");
  ASSERT_EQ(mesh.parts.size(), 1u);
  EXPECT_EQ(mesh.parts[0].name, "cow");  // Assimp's "<OFFRoot>" replaced by the file stem
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.boundary_edges, 0u);
  EXPECT_EQ(stats.non_manifold_edges, 0u);
  EXPECT_EQ(stats.connected_components, 1u);
  EXPECT_EQ(stats.degenerate_triangles, 0u);
  EXPECT_GT(SignedVolume(mesh, mesh.parts[0]), 0.0);  // faces point outwards
  // The file lists 2904 vertices, two of them (44 and 2903) at the same position; Assimp
  // joins them, which pinches the sphere-like surface at one vertex: V - E + F = 1, not 2.
  const long euler = static_cast<long>(stats.vertices) -
                     3 * static_cast<long>(stats.triangles) / 2 +
                     static_cast<long>(stats.triangles);
  EXPECT_EQ(euler, 1);
}

TEST(MeshImport, ElephantOffIsClosedAndConnected) {
  const fs::path path = Asset("elephant.off");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  const Mesh& mesh = imported.value().mesh;
  ExpectWellFormed(mesh);
  EXPECT_EQ(mesh.positions.size(), 2775u);
  EXPECT_EQ(mesh.triangles.size(), 5558u);
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_TRUE(stats.closed());
  EXPECT_EQ(stats.connected_components, 1u);
  // Closed, so E = 3F/2: V - E + F = -4, a surface of genus 3.
  const long euler = static_cast<long>(stats.vertices) -
                     3 * static_cast<long>(stats.triangles) / 2 +
                     static_cast<long>(stats.triangles);
  EXPECT_EQ(euler, -4);
}

TEST(MeshImport, UpAxisOptionRotatesZUpAndXUpToYUp) {
  const fs::path path = Asset("cow.off");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> plain = ImportMesh(path);
  ImportOptions z_up;
  z_up.up_axis = UpAxis::kZ;
  const Result<ImportedMesh> z = ImportMesh(path, z_up);
  ImportOptions x_up;
  x_up.up_axis = UpAxis::kX;
  const Result<ImportedMesh> x = ImportMesh(path, x_up);
  ASSERT_TRUE(plain.ok() && z.ok() && x.ok());
  EXPECT_EQ(z.value().report.source_up, UpAxis::kZ);
  EXPECT_EQ(z.value().report.up_source, "option");
  EXPECT_EQ(x.value().report.source_up, UpAxis::kX);

  // (x, y, z) -> (x, z, -y) for Z-up, (x, y, z) -> (-y, x, z) for X-up, exactly.
  const Bounds b = ComputeBounds(plain.value().mesh);
  const Bounds bz = ComputeBounds(z.value().mesh);
  EXPECT_EQ(bz.min, Vec3(b.min.x(), b.min.z(), -b.max.y()));
  EXPECT_EQ(bz.max, Vec3(b.max.x(), b.max.z(), -b.min.y()));
  const Bounds bx = ComputeBounds(x.value().mesh);
  EXPECT_EQ(bx.min, Vec3(-b.max.y(), b.min.x(), b.min.z()));
  EXPECT_EQ(bx.max, Vec3(-b.min.y(), b.max.x(), b.max.z()));

  const Mesh& m = plain.value().mesh;
  const Mesh& mz = z.value().mesh;
  ASSERT_EQ(mz.positions.size(), m.positions.size());
  for (std::size_t v = 0; v < m.positions.size(); v += 97) {
    const Vec3& p = m.positions[v];
    const Vec3& n = m.normals[v];
    EXPECT_EQ(mz.positions[v], Vec3(p.x(), p.z(), -p.y())) << v;
    EXPECT_NEAR((mz.normals[v] - Vec3(n.x(), n.z(), -n.y())).norm(), 0.0, 1e-12) << v;
  }
  // A rotation keeps the faces pointing outwards.
  EXPECT_GT(SignedVolume(mz, mz.parts[0]), 0.0);
}

// A closed box of the given extents with a corner at the origin, as OFF (no up axis in the file).
std::string BoxOff(const Vec3& size) {
  std::string out = "OFF\n8 12 0\n";
  for (int i = 0; i < 8; ++i)
    out += std::to_string(size.x() * (i & 1)) + " " + std::to_string(size.y() * ((i >> 1) & 1)) +
           " " + std::to_string(size.z() * ((i >> 2) & 1)) + "\n";
  for (const char* face : {"3 0 2 1", "3 1 2 3", "3 4 5 6", "3 5 7 6", "3 0 1 4", "3 1 5 4",
                           "3 2 6 3", "3 3 6 7", "3 0 4 2", "3 2 4 6", "3 1 3 5", "3 3 7 5"})
    out += std::string(face) + "\n";
  return out;
}

// With no up axis in the file, a figure standing along +Z (far taller along Z than across,
// wider along X than deep along Y) is turned +Y up and says so; shapes a bounding box cannot
// tell from a lying figure keep +Y (the Wuson bison's box, 2.1 times as long as tall; a spider
// 1.3 times as long as wide; a T-pose), and an up-axis option wins over the shape.
TEST(MeshImport, UpAxisFromTheShapeOfAFigureStandingAlongZ) {
  const fs::path standing = WriteFile("standing.off", BoxOff({0.45, 0.3, 1.7}));
  const Result<ImportedMesh> up = ImportMesh(standing);
  ASSERT_TRUE(up.ok()) << up.error();
  EXPECT_EQ(up.value().report.source_up, UpAxis::kZ);
  EXPECT_EQ(up.value().report.up_source, "shape: a standing figure's long axis");
  const Bounds b = ComputeBounds(up.value().mesh);
  EXPECT_NEAR(b.max.y() - b.min.y(), 1.7, 1e-6);  // (x, y, z) -> (x, z, -y); Assimp reads floats
  EXPECT_NEAR(b.max.z() - b.min.z(), 0.3, 1e-6);
  EXPECT_GT(SignedVolume(up.value().mesh, up.value().mesh.parts[0]), 0.0);

  for (const Vec3& size :
       {Vec3(0.92, 1.52, 3.24), Vec3(1.5, 0.8, 1.93), Vec3(1.7, 0.3, 1.75), Vec3(0.45, 1.7, 0.3)}) {
    const fs::path path = WriteFile("lying.off", BoxOff(size));
    const Result<ImportedMesh> kept = ImportMesh(path);
    ASSERT_TRUE(kept.ok()) << kept.error();
    EXPECT_EQ(kept.value().report.source_up, UpAxis::kY) << size.transpose();
    EXPECT_EQ(kept.value().report.up_source, "assumed") << size.transpose();
  }
  ImportOptions y_up;
  y_up.up_axis = UpAxis::kY;
  const Result<ImportedMesh> told = ImportMesh(standing, y_up);
  ASSERT_TRUE(told.ok());
  EXPECT_EQ(told.value().report.up_source, "option");
  EXPECT_NEAR(ComputeBounds(told.value().mesh).max.z(), 1.7, 1e-6);
}

// CGAL's man.off stands along +Z with no up axis in the file: found from its shape.
TEST(MeshImport, ManOffIsFoundStandingAlongZ) {
  const fs::path path = Asset("man.off");
  REQUIRE_ASSET(path);
  ImportOptions z_up;
  z_up.up_axis = UpAxis::kZ;
  const Result<ImportedMesh> found = ImportMesh(path), told = ImportMesh(path, z_up);
  ASSERT_TRUE(found.ok() && told.ok());
  EXPECT_EQ(found.value().report.source_up, UpAxis::kZ);
  EXPECT_EQ(found.value().mesh.positions, told.value().mesh.positions);
}

TEST(MeshImport, UnitScaleOptionScalesPositions) {
  const fs::path path = Asset("cow.off");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> plain = ImportMesh(path);
  ImportOptions options;
  options.unit_scale = 0.25;
  const Result<ImportedMesh> scaled = ImportMesh(path, options);
  ASSERT_TRUE(plain.ok() && scaled.ok());
  EXPECT_EQ(scaled.value().report.unit_scale, 0.25);
  EXPECT_EQ(scaled.value().report.unit_source, "option");
  for (std::size_t v = 0; v < plain.value().mesh.positions.size(); v += 101) {
    EXPECT_EQ(scaled.value().mesh.positions[v], 0.25 * plain.value().mesh.positions[v]);
  }
}

TEST(MeshImport, RefusesAbsurdUnitScaleOption) {
  const fs::path path = Asset("cow.off");
  REQUIRE_ASSET(path);
  ImportOptions options;
  options.unit_scale = -1.0;
  const Result<ImportedMesh> imported = ImportMesh(path, options);
  ASSERT_FALSE(imported.ok());
  EXPECT_NE(imported.error().find("unit_scale"), std::string::npos) << imported.error();
  options.unit_scale = 1e9;  // the cow would be 1e9 m long
  const Result<ImportedMesh> huge = ImportMesh(path, options);
  ASSERT_FALSE(huge.ok());
  EXPECT_NE(huge.error().find("1e7 m"), std::string::npos) << huge.error();
}

// Assimp's Collada loader applies <up_axis> and <unit> itself; the report names them, and the
// up-axis option switches Assimp's conversion off.
TEST(MeshImport, ColladaZUpInchesIsConvertedAndReported) {
  const fs::path path = Asset("assimp/Collada/cube_with_2UVs.DAE");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  const ImportReport& report = imported.value().report;
  EXPECT_EQ(report.source_up, UpAxis::kZ);
  EXPECT_EQ(report.up_source, "file metadata");
  EXPECT_NEAR(report.unit_scale, 0.0254, 1e-9);
  EXPECT_EQ(report.unit_source, "file metadata");
  // A 2-inch cube standing on z = 0 in the file: on y = 0 after conversion.
  const Bounds b = ComputeBounds(imported.value().mesh);
  EXPECT_NEAR(b.min.y(), 0.0, 1e-9);
  EXPECT_NEAR(b.max.y(), 0.0508, 1e-6);
  EXPECT_NEAR(b.max.z() - b.min.z(), 0.0508, 1e-6);

  ImportOptions y_up;
  y_up.up_axis = UpAxis::kY;  // "the file is already Y-up": no rotation at all
  const Result<ImportedMesh> raw = ImportMesh(path, y_up);
  ASSERT_TRUE(raw.ok()) << raw.error();
  EXPECT_EQ(raw.value().report.up_source, "option");
  const Bounds br = ComputeBounds(raw.value().mesh);
  EXPECT_NEAR(br.min.z(), 0.0, 1e-9);
  EXPECT_NEAR(br.max.z(), 0.0508, 1e-6);

  ImportOptions metres;
  metres.unit_scale = 1.0;  // overrides the file's inches
  const Result<ImportedMesh> big = ImportMesh(path, metres);
  ASSERT_TRUE(big.ok()) << big.error();
  EXPECT_NEAR(ComputeBounds(big.value().mesh).max.y(), 2.0, 1e-6);
}

// A mirroring node transform must flip the winding so that faces still point outwards. Part
// names: node names, or mesh names (made unique) for a node with several meshes.
TEST(MeshImport, MirroredInstanceKeepsOutwardFacesAndPartNamesAreUnique) {
  const std::string dae = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Y_UP</up_axis></asset>
  <library_geometries>
    <geometry id="tet" name="tet"><mesh>
      <source id="tet-pos">
        <float_array id="tet-pos-array" count="12">0 0 0 1 0 0 0 1 0 0 0 1</float_array>
        <technique_common><accessor source="#tet-pos-array" count="4" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common>
      </source>
      <vertices id="tet-vtx"><input semantic="POSITION" source="#tet-pos"/></vertices>
      <triangles count="4"><input semantic="VERTEX" source="#tet-vtx" offset="0"/>
        <p>0 2 1 0 1 3 0 3 2 1 2 3</p></triangles>
    </mesh></geometry>
    <geometry id="halves" name="halves"><mesh>
      <source id="halves-pos">
        <float_array id="halves-pos-array" count="12">0 0 0 1 0 0 0 1 0 0 0 1</float_array>
        <technique_common><accessor source="#halves-pos-array" count="4" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common>
      </source>
      <vertices id="halves-vtx"><input semantic="POSITION" source="#halves-pos"/></vertices>
      <triangles count="2" material="a"><input semantic="VERTEX" source="#halves-vtx" offset="0"/>
        <p>0 2 1 0 1 3</p></triangles>
      <triangles count="2" material="b"><input semantic="VERTEX" source="#halves-vtx" offset="0"/>
        <p>0 3 2 1 2 3</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="scene">
    <node id="plain" name="plain"><translate>5 0 0</translate><instance_geometry url="#tet"/></node>
    <node id="mirrored" name="mirrored"><scale>-1 1 1</scale><instance_geometry url="#tet"/></node>
    <node id="split" name="split"><translate>0 5 0</translate><instance_geometry url="#halves"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
  const Result<ImportedMesh> imported = ImportMesh(WriteFile("mirror.dae", dae));
  ASSERT_TRUE(imported.ok()) << imported.error();
  const Mesh& mesh = imported.value().mesh;
  ExpectWellFormed(mesh);
  ASSERT_EQ(mesh.parts.size(), 4u);
  EXPECT_EQ(mesh.parts[0].name, "plain");
  EXPECT_EQ(mesh.parts[1].name, "mirrored");
  EXPECT_EQ(mesh.parts[2].name, "halves");  // Assimp names both meshes "halves"
  EXPECT_EQ(mesh.parts[3].name, "halves_2");
  EXPECT_EQ(ComputeBounds(mesh).min.x(), -1.0);  // the mirrored copy reaches x = -1
  for (int p = 0; p < 2; ++p) {
    const MeshPart& part = mesh.parts[p];
    EXPECT_NEAR(SignedVolume(mesh, part), 1.0 / 6.0, 1e-6) << part.name;
    // Smooth normals (generated by Assimp) point away from the centroid.
    Vec3 centroid = Vec3::Zero();
    for (std::uint32_t t = part.first_triangle; t < part.first_triangle + 4; ++t) {
      for (const std::uint32_t v : mesh.triangles[t]) centroid += mesh.positions[v] / 12.0;
    }
    for (std::uint32_t t = part.first_triangle; t < part.first_triangle + 4; ++t) {
      for (const std::uint32_t v : mesh.triangles[t]) {
        EXPECT_GT(mesh.normals[v].dot(mesh.positions[v] - centroid), 0.0) << part.name;
      }
    }
  }
  EXPECT_NEAR(SignedVolume(mesh, mesh.parts[2]) + SignedVolume(mesh, mesh.parts[3]), 1.0 / 6.0,
              1e-6);
}

TEST(MeshImport, TestwusonSkeletonAndSkin) {
  const fs::path path = Asset("assimp/X/Testwuson.X");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  const Mesh& mesh = imported.value().mesh;
  ExpectWellFormed(mesh);
  EXPECT_EQ(mesh.positions.size(), 3205u);
  EXPECT_EQ(mesh.triangles.size(), 3732u);
  EXPECT_EQ(mesh.uvs.size(), mesh.positions.size());
  ASSERT_EQ(mesh.parts.size(), 1u);  // one X mesh, in 51 connected pieces
  EXPECT_EQ(mesh.parts[0].name, "Wuson");

  // 37 bones; their common ancestor "Root" (not a bone itself) joins them into one tree.
  ASSERT_EQ(mesh.joints.size(), 38u);
  EXPECT_EQ(mesh.joints[0].name, "Root");
  EXPECT_EQ(mesh.joints[0].parent, -1);
  EXPECT_EQ(std::count_if(mesh.joints.begin(), mesh.joints.end(),
                          [](const Joint& j) { return j.parent < 0; }),
            1);
  const int tail6 = JointIndex(mesh, "Tail06");
  const int tail5 = JointIndex(mesh, "Tail05");
  ASSERT_GE(tail6, 0);
  EXPECT_EQ(mesh.joints[tail6].parent, tail5);
  ExpectValidSkin(mesh);
  int influenced = 0;
  for (const auto& joints : mesh.skin_joints) influenced += joints[0] >= 0 ? 1 : 0;
  EXPECT_EQ(influenced, static_cast<int>(mesh.positions.size()));

  // Skinned vertices are placed by bone * offset (the mesh frame's own rotation does not
  // apply to them): the Wuson stands on y = 0 with its feet below its spine.
  const Bounds b = ComputeBounds(mesh);
  EXPECT_NEAR(b.min.y(), 0.0, 1e-3);
  EXPECT_NEAR(b.max.y(), 1.515, 1e-3);
  const double root_y = mesh.joints[0].bind_global(1, 3);
  const double foot_y = mesh.joints[JointIndex(mesh, "HindLeg_L_04")].bind_global(1, 3);
  const double spine_y = mesh.joints[JointIndex(mesh, "Spine_Back01")].bind_global(1, 3);
  EXPECT_LT(foot_y, 0.2);
  EXPECT_GT(spine_y, 1.0);
  EXPECT_LT(foot_y, root_y);
  // Bind poses are rigid here: rotation parts orthonormal.
  for (const Joint& joint : mesh.joints) {
    const Mat3 r = joint.bind_global.topLeftCorner<3, 3>();
    EXPECT_NEAR((r.transpose() * r - Mat3::Identity()).cwiseAbs().maxCoeff(), 0.0, 1e-4)
        << joint.name;
  }

  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.connected_components, 51u);
  EXPECT_EQ(stats.boundary_edges, 412u);  // open
  EXPECT_EQ(stats.non_manifold_edges, 0u);
}

TEST(MeshImport, AnimTestHasFourBones) {
  const fs::path path = Asset("assimp/X/anim_test.x");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  const Mesh& mesh = imported.value().mesh;
  ExpectWellFormed(mesh);
  EXPECT_EQ(mesh.positions.size(), 485u);
  EXPECT_EQ(mesh.triangles.size(), 840u);
  // Four bones, of which only joint1 -> joint2 are in the node hierarchy (see anim_test.txt):
  // joint3 and joint4 become roots.
  ASSERT_EQ(mesh.joints.size(), 4u);
  EXPECT_EQ(mesh.joints[0].name, "joint1");
  EXPECT_EQ(mesh.joints[0].parent, -1);
  EXPECT_EQ(mesh.joints[1].name, "joint2");
  EXPECT_EQ(mesh.joints[1].parent, 0);
  EXPECT_EQ(mesh.joints[2].parent, -1);
  EXPECT_EQ(mesh.joints[3].parent, -1);
  ExpectValidSkin(mesh);
  // The cylinder runs along y from -5 to 5; its bones lie along that axis, in order.
  const Bounds b = ComputeBounds(mesh);
  EXPECT_NEAR(b.min.y(), -5.0, 1e-4);
  EXPECT_NEAR(b.max.y(), 5.0, 1e-4);
  EXPECT_LT(mesh.joints[0].bind_global(1, 3), mesh.joints[1].bind_global(1, 3));
  EXPECT_LT(mesh.joints[1].bind_global(1, 3), mesh.joints[2].bind_global(1, 3));
  EXPECT_LT(mesh.joints[2].bind_global(1, 3), mesh.joints[3].bind_global(1, 3));
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_TRUE(stats.closed());
  EXPECT_EQ(stats.connected_components, 1u);
}

// FBX states its unit in metadata (UnitScaleFactor: centimetres per unit) and Assimp 5.2.5
// leaves the data in file units: wirerig applies it. This Blender export is in centimetres,
// with an armature scaled by 100.
TEST(MeshImport, FbxUnitScaleFactorIsAppliedAndJointsAreRigid) {
  const fs::path path = Asset("assimp/FBX/animation_with_skeleton.fbx");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  const ImportReport& report = imported.value().report;
  EXPECT_EQ(report.format, "Autodesk FBX");
  EXPECT_NEAR(report.unit_scale, 0.01, 1e-12);
  EXPECT_EQ(report.unit_source, "file metadata");
  EXPECT_EQ(report.source_up, UpAxis::kY);  // UpAxis = 1
  EXPECT_EQ(report.up_source, "file metadata");
  const Mesh& mesh = imported.value().mesh;
  ExpectWellFormed(mesh);
  ExpectValidSkin(mesh);
  EXPECT_TRUE(ComputeMeshStatistics(mesh).closed());

  ImportOptions centimetres_as_metres;
  centimetres_as_metres.unit_scale = 1.0;
  const Result<ImportedMesh> raw = ImportMesh(path, centimetres_as_metres);
  ASSERT_TRUE(raw.ok()) << raw.error();
  for (std::size_t v = 0; v < mesh.positions.size(); v += 53) {
    EXPECT_NEAR((raw.value().mesh.positions[v] - 100.0 * mesh.positions[v]).norm(), 0.0,
                1e-9 * raw.value().mesh.positions[v].norm() + 1e-9);
  }

  // Two chains of bones, Bone..Bone.006 and Bone.007..Bone.013, joined by their common
  // ancestor "Armature" (not a bone). Limiting influences to 4 leaves one bone without
  // weights (Assimp then drops it from the mesh); its node still joins its chain.
  ASSERT_EQ(mesh.joints.size(), 15u);
  EXPECT_EQ(mesh.joints[0].name, "Armature");
  EXPECT_EQ(mesh.joints[JointIndex(mesh, "Bone")].parent, 0);
  EXPECT_EQ(mesh.joints[JointIndex(mesh, "Bone.007")].parent, 0);
  EXPECT_NEAR(mesh.joints[0].bind_global(0, 3), -36.1402, 1e-3);  // -3614.02 cm
  for (const Joint& joint : mesh.joints) {
    const Mat3 r = joint.bind_global.topLeftCorner<3, 3>();
    EXPECT_NEAR((r.transpose() * r - Mat3::Identity()).cwiseAbs().maxCoeff(), 0.0, 1e-9)
        << joint.name;
    EXPECT_NEAR(r.determinant(), 1.0, 1e-9) << joint.name;
    EXPECT_EQ(joint.bind_global.row(3), Vec4(0, 0, 0, 1).transpose()) << joint.name;
  }
}

TEST(MeshImport, CesiumMilkTruckPartsMaterialsUvsAndSeams) {
  const fs::path path = Asset("assimp/glTF/CesiumMilkTruck/CesiumMilkTruck.gltf");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  const Mesh& mesh = imported.value().mesh;
  ExpectWellFormed(mesh);
  EXPECT_EQ(imported.value().report.format, "glTF");
  // 4 glTF meshes, the wheel mesh instanced twice.
  ASSERT_EQ(mesh.parts.size(), 5u);
  EXPECT_EQ(mesh.parts[0].name, "Geometry-mesh002-0");  // a node with 3 meshes: mesh names
  EXPECT_EQ(mesh.parts[3].name, "Geometry-mesh001Node");
  EXPECT_EQ(mesh.parts[4].name, "meshInst962Node");
  EXPECT_EQ(mesh.parts[3].triangle_count, mesh.parts[4].triangle_count);
  ASSERT_EQ(mesh.materials.size(), 4u);
  EXPECT_EQ(mesh.materials[mesh.parts[0].material].name, "Effect-truck");
  EXPECT_EQ(mesh.materials[mesh.parts[0].material].base_color_texture, "CesiumMilkTruck.png");
  EXPECT_EQ(mesh.materials[mesh.parts[3].material].name, "Effect-wheels");
  EXPECT_EQ(mesh.materials[2].name, "Effect-glass");
  EXPECT_TRUE(mesh.materials[2].base_color_texture.empty());
  EXPECT_NEAR(mesh.materials[2].base_color.y(), 0.0405063, 1e-6);

  EXPECT_EQ(mesh.positions.size(), 3564u);  // 586 + 586 + 1856 + 72 + 464
  EXPECT_EQ(mesh.triangles.size(), 3624u);
  ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
  for (const Vec2& uv : mesh.uvs) {
    ASSERT_TRUE(std::isfinite(uv.x()) && std::isfinite(uv.y()));
  }
  // Texture seams and hard edges split render vertices; welding merges them.
  EXPECT_EQ(mesh.welded_positions.size(), 1840u);
  EXPECT_LT(mesh.welded_positions.size(), mesh.positions.size());
  // Each wheel pair is closed once welded (render vertices alone would show the seams).
  const MeshStatistics wheels = ComputeMeshStatistics(PartMesh(mesh, mesh.parts[3]));
  EXPECT_TRUE(wheels.closed());
  EXPECT_EQ(wheels.connected_components, 2u);
  // Y-up: the truck is taller than it is wide, and longer along x.
  const Bounds b = ComputeBounds(mesh);
  EXPECT_NEAR(b.max.y() - b.min.y(), 2.842, 0.01);
  EXPECT_NEAR(b.max.z(), -b.min.z(), 1e-6);
}

TEST(MeshImport, SphereWithHoleShowsBoundaryEdges) {
  const fs::path path = Asset("assimp/STL/sphereWithHole.stl");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  const Mesh& mesh = imported.value().mesh;
  ExpectWellFormed(mesh);
  EXPECT_EQ(mesh.triangles.size(), 285u);
  EXPECT_EQ(mesh.positions.size(), 855u);  // STL: three vertices per facet
  EXPECT_EQ(mesh.welded_positions.size(), 146u);
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.boundary_edges, 9u);  // the rim of the hole
  EXPECT_EQ(stats.non_manifold_edges, 0u);
  EXPECT_EQ(stats.connected_components, 1u);
  EXPECT_FALSE(stats.closed());
}

// ---------------------------------------------------------------------------------------------
// Assimp's invalid/ folder: one test per file.

struct BadFile {
  std::string file;     // under assimp/invalid/
  std::string problem;  // expected in the message
};

void PrintTo(const BadFile& bad, std::ostream* os) { *os << bad.file; }

class MeshImportInvalidFile : public ::testing::TestWithParam<BadFile> {};

TEST_P(MeshImportInvalidFile, FailsWithClearMessage) {
  const fs::path path = Asset("assimp/invalid/" + GetParam().file);
  REQUIRE_ASSET(path);
  const auto start = std::chrono::steady_clock::now();
  const Result<ImportedMesh> imported = ImportMesh(path);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_FALSE(imported.ok());
  EXPECT_EQ(imported.error().rfind(path.string() + ": ", 0), 0u) << imported.error();
  EXPECT_NE(imported.error().find(GetParam().problem), std::string::npos) << imported.error();
  EXPECT_LT(seconds, 2.0);
}

std::string BadFileName(const ::testing::TestParamInfo<BadFile>& info) {
  std::string name = info.param.file;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(
    AssimpInvalid, MeshImportInvalidFile,
    ::testing::Values(BadFile{"empty.3ds", "file is empty"}, BadFile{"empty.ase", "file is empty"},
                      BadFile{"empty.lwo", "file is empty"},
                      BadFile{"empty.md5mesh", "file is empty"},
                      BadFile{"empty.obj", "file is empty"}, BadFile{"empty.off", "file is empty"},
                      BadFile{"empty.ply", "file is empty"}, BadFile{"empty.raw", "file is empty"},
                      BadFile{"empty.smd", "file is empty"}, BadFile{"empty.x", "file is empty"},
                      BadFile{"emptyIrrMesh.xml", "IRRMESH: Unable to read a mesh"},
                      BadFile{"malformed.obj", "Invalid face index"},
                      BadFile{"readme.txt", "unknown or unsupported file format"}),
    BadFileName);

// Claims 353535235358 vertices: refused from the header, before Assimp reserves terabytes.
// The message is wirerig's own (Assimp would report std::bad_alloc, after trying).
TEST(MeshImportInvalid, OutOfMemoryOffIsRefusedFromItsHeader) {
  const fs::path path = Asset("assimp/invalid/OutOfMemory.off");
  REQUIRE_ASSET(path);
  const auto start = std::chrono::steady_clock::now();
  const Result<ImportedMesh> imported = ImportMesh(path);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_FALSE(imported.ok());
  EXPECT_EQ(imported.error().rfind(path.string() + ": claims 353535235358 vertices", 0), 0u)
      << imported.error();
  EXPECT_NE(imported.error().find("limit of 20000000"), std::string::npos) << imported.error();
  EXPECT_LT(seconds, 0.5);
}

// A face is missing ("f" with no indices) and the material does not exist: Assimp loads the
// rest, and the hole shows as boundary edges.
TEST(MeshImportInvalid, Malformed2ObjLoadsWithAHole) {
  const fs::path path = Asset("assimp/invalid/malformed2.obj");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  const Mesh& mesh = imported.value().mesh;
  ExpectWellFormed(mesh);
  EXPECT_EQ(mesh.triangles.size(), 10u);  // 5 of the cube's 6 quads
  EXPECT_EQ(mesh.welded_positions.size(), 8u);
  const MeshStatistics stats = ComputeMeshStatistics(mesh);
  EXPECT_EQ(stats.boundary_edges, 4u);
  EXPECT_FALSE(stats.closed());
  ASSERT_EQ(mesh.parts.size(), 1u);
  EXPECT_EQ(mesh.materials[mesh.parts[0].material].name, "DefaultDoesNotExist");
}

// Every face collapses (Assimp reads 3 vertices into one and faces with 0..2 corners).
TEST(MeshImportInvalid, InvalidOffHasNoUsableTriangles) {
  const fs::path path = Asset("assimp/OFF/invalid.off");
  REQUIRE_ASSET(path);
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_FALSE(imported.ok());
  EXPECT_EQ(imported.error().rfind(path.string() + ": no usable triangles", 0), 0u)
      << imported.error();
  EXPECT_NE(imported.error().find("degenerate"), std::string::npos) << imported.error();
}

// ---------------------------------------------------------------------------------------------
// Other bad input, made here.

void ExpectError(const Result<ImportedMesh>& imported, const fs::path& path,
                 const std::string& problem) {
  ASSERT_FALSE(imported.ok());
  EXPECT_EQ(imported.error().rfind(path.string() + ": ", 0), 0u) << imported.error();
  EXPECT_NE(imported.error().find(problem), std::string::npos) << imported.error();
}

TEST(MeshImportInvalid, MissingFile) {
  const fs::path path = fs::path(::testing::TempDir()) / "wirerig_no_such_mesh.obj";
  ExpectError(ImportMesh(path), path, "no such file");
}

TEST(MeshImportInvalid, Directory) {
  const fs::path path = ::testing::TempDir();
  ExpectError(ImportMesh(path), path, "is a directory");
}

TEST(MeshImportInvalid, NotARegularFile) {
  const fs::path path = fs::path(::testing::TempDir()) / "wirerig_mesh_import_fifo.obj";
  fs::remove(path);
  ASSERT_EQ(mkfifo(path.c_str(), 0600), 0);
  ExpectError(ImportMesh(path), path, "not a regular file");  // and does not block reading it
  fs::remove(path);
}

// A 10 GB (sparse) .obj ran until the import's time limit: files over max_file_bytes are
// refused before they are read.
TEST(MeshImportInvalid, AFileTooLargeIsRefusedUnread) {
  const fs::path path = WriteFile("huge.obj", "v 0 0 0\n");
  fs::resize_file(path, (std::uintmax_t{2} << 30) + 1);  // sparse: no disk used
  ExpectError(ImportMesh(path), path, "is 2147483649 bytes, more than the 2147483648");
  fs::remove(path);
}

TEST(MeshImportInvalid, UnreadableFile) {
  const fs::path path = WriteFile("unreadable.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  fs::permissions(path, fs::perms::none);
  // Root reads any file: as root, drop the effective uid to "nobody" for the attempt (the saved
  // uid stays 0, so it can be restored).
  const bool root = geteuid() == 0;
  if (root) {
    ASSERT_EQ(seteuid(65534), 0);
  }
  const Result<ImportedMesh> result = ImportMesh(path);
  if (root) {
    ASSERT_EQ(seteuid(0), 0);
  }
  fs::permissions(path, fs::perms::owner_all);
  ExpectError(result, path, "cannot open (Permission denied)");
}

TEST(MeshImportInvalid, UnknownFormat) {
  const fs::path path = WriteFile("unknown.xyz", "hello, this is not a mesh\n");
  ExpectError(ImportMesh(path), path, "unknown or unsupported file format (extension '.xyz')");
}

TEST(MeshImportInvalid, NonFinitePosition) {
  const fs::path nan = WriteFile("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  ExpectError(ImportMesh(nan), nan, "non-finite position");
  // Assimp's parser overflows to infinity here (with FP traps masked while it runs).
  const fs::path inf = WriteFile("inf.obj", "v 1e999 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  ExpectError(ImportMesh(inf), inf, "non-finite position");
}

TEST(MeshImportInvalid, AbsurdCoordinates) {
  const fs::path path = WriteFile("far.obj", "v 3e9 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  ExpectError(ImportMesh(path), path, "lies 3e+09 m from the origin, beyond the limit of 1e7 m");
}

TEST(MeshImportInvalid, OnlyLines) {
  const fs::path path = WriteFile("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n");
  ExpectError(ImportMesh(path), path, "no triangle meshes");
}

TEST(MeshImportInvalid, PlyClaimingTooManyVertices) {
  const fs::path path = WriteFile("huge.ply",
                                  "ply\nformat ascii 1.0\nelement vertex 99999999999\n"
                                  "property float x\nproperty float y\nproperty float z\n"
                                  "element face 1\nproperty list uchar int vertex_indices\n"
                                  "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  ExpectError(ImportMesh(path), path, "claims 99999999999 vertex elements");
}

TEST(MeshImport, PlyHeaderCommentsAreNotClaims) {
  const fs::path path = WriteFile("tet.ply",
                                  "ply\nformat ascii 1.0\ncomment element vertex 99999999999\n"
                                  "element vertex 4\nproperty float x\nproperty float y\n"
                                  "property float z\nelement face 4\n"
                                  "property list uchar int vertex_indices\nend_header\n"
                                  "0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                                  "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  const Result<ImportedMesh> imported = ImportMesh(path);
  ASSERT_TRUE(imported.ok()) << imported.error();
  ExpectWellFormed(imported.value().mesh);
  EXPECT_EQ(imported.value().mesh.triangles.size(), 4u);
  EXPECT_EQ(imported.value().mesh.welded_positions.size(), 4u);
  EXPECT_TRUE(ComputeMeshStatistics(imported.value().mesh).closed());
  EXPECT_NEAR(SignedVolume(imported.value().mesh, imported.value().mesh.parts[0]), 1.0 / 6.0, 1e-7);
}

TEST(MeshImportInvalid, PlyClaimingMoreThanTheFileHolds) {
  const fs::path path = WriteFile("short.ply",
                                  "ply\nformat binary_little_endian 1.0\nelement vertex 1000000\n"
                                  "property float x\nproperty float y\nproperty float z\n"
                                  "end_header\n");
  ExpectError(ImportMesh(path), path, "needing at least 12000000 bytes");
}

TEST(MeshImportInvalid, OffClaimingMoreThanTheFileHolds) {
  // Under the element limit, but 10 million vertices cannot fit in 40 bytes.
  const fs::path path = WriteFile("short.off", "OFF\n10000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  ExpectError(ImportMesh(path), path, "claims 10000000 vertices and 1 faces, more than its");
}

TEST(MeshImportInvalid, MaxElementsOption) {
  const fs::path cow = Asset("cow.off");
  REQUIRE_ASSET(cow);
  ImportOptions options;
  options.max_elements = 1000;
  ExpectError(ImportMesh(cow, options), cow, "claims 2904 vertices");  // the file's header

  // Binary STL: 2 facets, over a limit of 1.
  std::string stl(80, ' ');
  const std::uint32_t count = 2;
  stl.append(reinterpret_cast<const char*>(&count), 4);
  stl.append(2 * 50, '\0');
  const fs::path path = WriteFile("two.stl", stl);
  options.max_elements = 1;
  ExpectError(ImportMesh(path, options), path, "claims 2 triangles");
}

TEST(MeshImportInvalid, SkeletonOnlyBvh) {
  const fs::path path = Asset("assimp/BVH/01_01.bvh");
  REQUIRE_ASSET(path);
  ExpectError(ImportMesh(path), path, "no triangle meshes");
}

TEST(UpAxis, ToStringAndParseRoundTrip) {
  for (const UpAxis axis : {UpAxis::kX, UpAxis::kY, UpAxis::kZ}) {
    UpAxis parsed = UpAxis::kY;
    ASSERT_TRUE(ParseUpAxis(ToString(axis), &parsed));
    EXPECT_EQ(parsed, axis);
  }
  UpAxis parsed = UpAxis::kX;
  EXPECT_TRUE(ParseUpAxis("Z", &parsed));
  EXPECT_EQ(parsed, UpAxis::kZ);
  EXPECT_FALSE(ParseUpAxis("w", &parsed));
  EXPECT_FALSE(ParseUpAxis("", &parsed));
  EXPECT_EQ(parsed, UpAxis::kZ);  // untouched on failure
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
