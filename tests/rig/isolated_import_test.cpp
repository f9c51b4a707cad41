// Tests for importing in a child process (ImportOptions::isolation): the same mesh as an
// import in this process, and corrupted files that crash or hang Assimp 5.2.5 coming back as
// errors naming the file while this process goes on. Files are written by the tests.
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "wirerig/rig/mesh_import.h"

#ifndef WIRERIG_ASSET_DIR
#error "the tests need WIRERIG_ASSET_DIR (set by CMake)"
#endif

// AddressSanitizer: GCC defines __SANITIZE_ADDRESS__, clang (before 16) only answers
// __has_feature(address_sanitizer).
#if defined(__SANITIZE_ADDRESS__)
#define WIRERIG_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define WIRERIG_TEST_ASAN 1
#endif
#endif

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

fs::path WriteFile(const std::string& name, const std::string& contents) {
  const fs::path path = fs::path(::testing::TempDir()) /
                        ("wirerig_isolated_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << contents;
  return path;
}

ImportOptions Isolated(double seconds = 30.0) {
  ImportOptions options;
  options.isolation = ImportIsolation{};
  options.isolation->time_limit_seconds = seconds;
  return options;
}

void ExpectSameMesh(const ImportedMesh& a, const ImportedMesh& b) {
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.mesh.normals, b.mesh.normals);
  EXPECT_EQ(a.mesh.uvs, b.mesh.uvs);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  ASSERT_EQ(a.mesh.parts.size(), b.mesh.parts.size());
  for (std::size_t i = 0; i < a.mesh.parts.size(); ++i) {
    EXPECT_EQ(a.mesh.parts[i].name, b.mesh.parts[i].name);
    EXPECT_EQ(a.mesh.parts[i].first_triangle, b.mesh.parts[i].first_triangle);
    EXPECT_EQ(a.mesh.parts[i].triangle_count, b.mesh.parts[i].triangle_count);
    EXPECT_EQ(a.mesh.parts[i].material, b.mesh.parts[i].material);
  }
  ASSERT_EQ(a.mesh.materials.size(), b.mesh.materials.size());
  for (std::size_t i = 0; i < a.mesh.materials.size(); ++i) {
    EXPECT_EQ(a.mesh.materials[i].name, b.mesh.materials[i].name);
    EXPECT_EQ(a.mesh.materials[i].base_color, b.mesh.materials[i].base_color);
    EXPECT_EQ(a.mesh.materials[i].base_color_texture, b.mesh.materials[i].base_color_texture);
  }
  ASSERT_EQ(a.mesh.joints.size(), b.mesh.joints.size());
  for (std::size_t i = 0; i < a.mesh.joints.size(); ++i) {
    EXPECT_EQ(a.mesh.joints[i].name, b.mesh.joints[i].name);
    EXPECT_EQ(a.mesh.joints[i].parent, b.mesh.joints[i].parent);
    EXPECT_EQ(a.mesh.joints[i].bind_global, b.mesh.joints[i].bind_global);
  }
  EXPECT_EQ(a.mesh.skin_joints, b.mesh.skin_joints);
  EXPECT_EQ(a.mesh.skin_weights, b.mesh.skin_weights);
  EXPECT_EQ(a.mesh.weld_map, b.mesh.weld_map);
  EXPECT_EQ(a.mesh.welded_positions, b.mesh.welded_positions);
  EXPECT_EQ(a.mesh.welded_triangles, b.mesh.welded_triangles);
  EXPECT_EQ(a.report.format, b.report.format);
  EXPECT_EQ(a.report.source_up, b.report.source_up);
  EXPECT_EQ(a.report.up_source, b.report.up_source);
  EXPECT_EQ(a.report.unit_scale, b.report.unit_scale);
  EXPECT_EQ(a.report.unit_source, b.report.unit_source);
  EXPECT_EQ(a.report.source_vertices, b.report.source_vertices);
}

void ExpectError(const Result<ImportedMesh>& imported, const fs::path& path,
                 const std::string& problem) {
  ASSERT_FALSE(imported.ok());
  EXPECT_EQ(imported.error().rfind(path.string() + ": ", 0), 0u) << imported.error();
  EXPECT_NE(imported.error().find(problem), std::string::npos) << imported.error();
}

// ---------------------------------------------------------------------------------------------
// The same mesh either way.

TEST(IsolatedImport, ProceduralObjGivesTheSameMeshAsInProcess) {
  std::string obj = "o ring\n";
  const int n = 24;
  for (int i = 0; i < n; ++i) {
    const double a = 6.283185307179586 * i / n;
    obj += "v " + std::to_string(std::cos(a)) + " 0 " + std::to_string(std::sin(a)) + "\n";
    obj += "v " + std::to_string(std::cos(a)) + " 1 " + std::to_string(std::sin(a)) + "\n";
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i + 1, b = 2 * i + 2, c = 2 * ((i + 1) % n) + 1, d = c + 1;
    obj += "f " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + " " +
           std::to_string(b) + "\n";
  }
  const fs::path path = WriteFile("ring.obj", obj);
  const Result<ImportedMesh> here = ImportMesh(path);
  const Result<ImportedMesh> there = ImportMesh(path, Isolated());
  ASSERT_TRUE(here.ok()) << here.error();
  ASSERT_TRUE(there.ok()) << there.error();
  EXPECT_EQ(there.value().mesh.triangles.size(), 2u * n);
  ExpectSameMesh(here.value(), there.value());
}

TEST(IsolatedImport, HumanZaeGivesTheSameMeshAsInProcess) {
  const fs::path path = fs::path(WIRERIG_ASSET_DIR) / "assimp/Collada/human.zae";
  if (!fs::exists(path)) FAIL() << "asset missing: " << path << " (run scripts/setup.sh)";
  const Result<ImportedMesh> here = ImportMesh(path);
  const Result<ImportedMesh> there = ImportMesh(path, Isolated());
  ASSERT_TRUE(here.ok()) << here.error();
  ASSERT_TRUE(there.ok()) << there.error();
  ExpectSameMesh(here.value(), there.value());
}

TEST(IsolatedImport, ErrorsOfTheChildComeBackAsTheyAre) {
  const fs::path path = WriteFile("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n");
  const Result<ImportedMesh> here = ImportMesh(path);
  const Result<ImportedMesh> there = ImportMesh(path, Isolated());
  ASSERT_FALSE(here.ok());
  ASSERT_FALSE(there.ok());
  EXPECT_EQ(here.error(), there.error());
}

// ---------------------------------------------------------------------------------------------
// Limits.

TEST(IsolatedImport, TimeLimitStopsTheChild) {
  const fs::path path = fs::path(WIRERIG_ASSET_DIR) / "assimp/Collada/human.zae";
  if (!fs::exists(path)) FAIL() << "asset missing: " << path << " (run scripts/setup.sh)";
  const auto start = std::chrono::steady_clock::now();
  const Result<ImportedMesh> imported = ImportMesh(path, Isolated(0.001));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  ExpectError(imported, path, "the importer timed out on this file (still running after 0.001 s");
}

TEST(IsolatedImport, RefusesANonPositiveTimeLimit) {
  const fs::path path = WriteFile("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  ExpectError(ImportMesh(path, Isolated(0.0)), path, "time_limit_seconds must be a number > 0");
}

// ---------------------------------------------------------------------------------------------
// Corrupted files that crash or hang Assimp 5.2.5 in this process. Each must end as an error
// naming the file, within the limits, while this process goes on.

// A small Collada triangle whose <p> list is `indices`.
std::string Collada(const std::string& indices) {
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Y_UP</up_axis></asset>
  <library_geometries><geometry id="g"><mesh>
    <source id="g-pos"><float_array id="g-pos-array" count="9">0 0 0 1 0 0 0 1 0</float_array>
      <technique_common><accessor source="#g-pos-array" count="3" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="g-vtx"><input semantic="POSITION" source="#g-pos"/></vertices>
    <triangles count="1"><input semantic="VERTEX" source="#g-vtx" offset="0"/><p>)" +
         indices + R"(</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";
}

// Short limits, so that a runaway import ends quickly either way.
ImportOptions Tight() {
  ImportOptions options = Isolated(5.0);
  options.isolation->memory_limit_bytes = std::uint64_t{512} << 20;
  return options;
}

void ExpectStoppedCleanly(const Result<ImportedMesh>& imported, const fs::path& path) {
  ASSERT_FALSE(imported.ok());
  EXPECT_EQ(imported.error().rfind(path.string() + ": ", 0), 0u) << imported.error();
  const bool stopped = imported.error().find("the importer crashed") != std::string::npos ||
                       imported.error().find("the importer timed out") != std::string::npos ||
                       imported.error().find("out of memory (limit 512 MiB") != std::string::npos;
  EXPECT_TRUE(stopped) << imported.error();
}

// Refused before any import, isolated or not: Assimp reads such a header forever.
TEST(IsolatedImport, PlyHeaderWithoutEndHeaderIsRefusedUpFront) {
  const fs::path path = WriteFile("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  for (const ImportOptions& options : {ImportOptions{}, Isolated()}) {
    ExpectError(ImportMesh(path, options), path,
                "its PLY header has no \"end_header\" line in its first 38 bytes");
  }
}

// Letters inside a Collada <p> list: Assimp allocates without end, until the memory limit.
TEST(IsolatedImport, MemoryLimitStopsARunawayImport) {
  const fs::path path = WriteFile("runaway.dae", Collada("abc"));
  ImportOptions options = Isolated(60.0);
  options.isolation->memory_limit_bytes = std::uint64_t{64} << 20;
  const Result<ImportedMesh> imported = ImportMesh(path, options);
#if defined(WIRERIG_TEST_ASAN)
  // AddressSanitizer's allocator ends the child itself when memory runs out.
  ExpectStoppedCleanly(imported, path);
#else
  ExpectError(imported, path,
              "cannot import: out of memory (limit 64 MiB, ImportIsolation::memory_limit_bytes)");
#endif
}

TEST(IsolatedImport, GarbageInAColladaIndexListIsStopped) {
  for (const char* indices : {"abc", "0 1 2 .", "0 1 2 abc", "0 1 2 1e99"}) {
    SCOPED_TRACE(indices);
    const fs::path path = WriteFile("garbage.dae", Collada(indices));
    ExpectStoppedCleanly(ImportMesh(path, Tight()), path);
  }
}

// "end_header" glued to the line before it is no header end for Assimp either.
TEST(IsolatedImport, PlyEndHeaderNotOnItsOwnLineIsRefusedUpFront) {
  const fs::path path = WriteFile("glued.ply",
                                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                  "property float y\nproperty float z\xbe"
                                  "end_header\n0 0 0\n1 0 0\n0 1 0\n");
  ExpectError(ImportMesh(path), path, "its PLY header has no \"end_header\" line");
}

// One byte of Assimp's own binary X test cube changed: Assimp reads through a bad pointer.
TEST(IsolatedImport, CorruptedBinaryXFileCrashesOnlyTheChild) {
  const fs::path source = fs::path(WIRERIG_ASSET_DIR) / "assimp/X/test_cube_binary.x";
  if (!fs::exists(source)) FAIL() << "asset missing: " << source << " (run scripts/setup.sh)";
  std::ifstream in(source, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 2816u);
  bytes[2609] = static_cast<char>(0xb2);
  const fs::path path = WriteFile("corrupted.x", bytes);
  const Result<ImportedMesh> imported = ImportMesh(path, Tight());
  ExpectError(imported, path, "the importer crashed on this file (");
}

// A binary PLY the mesh_import fuzzer made (fuzz/corpus/mesh_import/finding-assimp-ply-bad-free,
// its first byte the fuzzer's extension choice): Assimp frees a pointer it did not allocate
// while destroying its scene (a segmentation fault without a sanitizer, a bad-free report
// under AddressSanitizer). Only the child dies. Whether Assimp gets that far depends on the heap
// the child inherits: run after other imports in one process, its validation may refuse the
// file first (an index out of range). Either way the caller gets an error naming the file.
TEST(IsolatedImport, PlyOnWhichAssimpFreesABadPointerCrashesOnlyTheChild) {
  const fs::path finding =
      fs::path(WIRERIG_FUZZ_CORPUS_DIR) / "mesh_import/finding-assimp-ply-bad-free";
  std::ifstream in(finding, std::ios::binary);
  ASSERT_TRUE(in) << finding;
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 1u);
  const fs::path path = WriteFile("bad_free.ply", bytes.substr(1));
  const Result<ImportedMesh> imported = ImportMesh(path, Tight());
  ASSERT_FALSE(imported.ok());
  EXPECT_EQ(imported.error().rfind(path.string() + ": ", 0), 0u) << imported.error();
  const bool crashed =
      imported.error().find("the importer crashed on this file (") != std::string::npos;
  const bool refused =
      imported.error().find("cannot import: Validation failed") != std::string::npos;
  EXPECT_TRUE(crashed || refused) << imported.error();
}

// The caller's crash handler (a crash reporter, a sanitizer's, libFuzzer's) is not the child's:
// the child dies by the signal itself, and the parent names it.
TEST(IsolatedImport, CallersCrashHandlerDoesNotRunInTheChild) {
  const fs::path source = fs::path(WIRERIG_ASSET_DIR) / "assimp/X/test_cube_binary.x";
  if (!fs::exists(source)) FAIL() << "asset missing: " << source << " (run scripts/setup.sh)";
  std::ifstream in(source, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 2816u);
  bytes[2609] = static_cast<char>(0xb2);
  const fs::path path = WriteFile("corrupted_handled.x", bytes);

  struct sigaction handler = {};
  handler.sa_handler = [](int) { ::_exit(42); };
  struct sigaction previous = {};
  ASSERT_EQ(::sigaction(SIGSEGV, &handler, &previous), 0);
  const Result<ImportedMesh> imported = ImportMesh(path, Tight());
  ::sigaction(SIGSEGV, &previous, nullptr);
  ExpectError(imported, path, "the importer crashed on this file (Segmentation fault, signal 11)");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
