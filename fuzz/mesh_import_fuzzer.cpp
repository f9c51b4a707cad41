// libFuzzer target: mesh import through the child-process isolation (rig/mesh_import.h,
// ImportOptions::isolation), as the wirerig command imports every mesh. The first byte of the
// input picks the file's extension (Assimp picks its importer by it), the rest is the file.
//
// What runs where: the cheap header checks (OFF, PLY, binary STL counts; the PLY header's end)
// and the decoding of the child's answer run in this process, instrumented, with coverage; Assimp
// and the conversion of its scene run in a forked child whose coverage libFuzzer does not see.
// The property: whatever the file, this process gets a mesh whose indices are all in range, or
// an error naming the file ("the importer crashed / timed out on this file" included), never a
// crash or a hang. A memory error AddressSanitizer reports inside the child still leaves a crash
// file (libFuzzer's handler is inherited) although this process goes on.
#include <pthread.h>
#include <sanitizer/asan_interface.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "wirerig/rig/mesh_import.h"

namespace {

// How a forked child ends on a report the isolation contains (any status but 0: "no answer").
constexpr int kChildContainedReport = 99;

constexpr const char* kExtensions[] = {"off", "ply", "obj", "stl", "dae",   "x",   "gltf", "glb",
                                       "fbx", "3ds", "ac",  "lwo", "ms3d",  "md2", "nff",  "ase",
                                       "smd", "b3d", "xgl", "bvh", "blend", "zae", "raw",  "ter"};

void CheckMesh(const wirerig::Mesh& mesh) {
  const std::size_t v = mesh.positions.size(), w = mesh.welded_positions.size();
  FUZZ_CHECK(!mesh.triangles.empty(), "an imported mesh has no triangles");
  FUZZ_CHECK(mesh.welded_triangles.size() == mesh.triangles.size(), "welded triangle count");
  FUZZ_CHECK(mesh.weld_map.size() == v, "one weld entry per vertex");
  FUZZ_CHECK(mesh.normals.empty() || mesh.normals.size() == v, "one normal per vertex");
  FUZZ_CHECK(mesh.uvs.empty() || mesh.uvs.size() == v, "one uv per vertex");
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      FUZZ_CHECK(mesh.triangles[f][c] < v, "triangle corner out of range");
      FUZZ_CHECK(mesh.welded_triangles[f][c] < w, "welded triangle corner out of range");
    }
  }
  for (std::uint32_t i : mesh.weld_map) FUZZ_CHECK(i < w, "weld map entry out of range");
  for (const wirerig::Vec3& p : mesh.positions)
    FUZZ_CHECK(p.allFinite(), "an imported position is not finite");
  std::size_t covered = 0;
  for (const wirerig::MeshPart& part : mesh.parts) {
    FUZZ_CHECK(part.first_triangle == covered, "parts cover the triangles in order");
    covered += part.triangle_count;
    FUZZ_CHECK(part.material < static_cast<int>(mesh.materials.size()), "part material index");
  }
  FUZZ_CHECK(covered == mesh.triangles.size(), "parts cover every triangle");
}

}  // namespace

// Reports the forked child makes that are the isolation doing its job, not findings. libFuzzer's
// death callback, inherited through fork, would save the input as a crash for any report the
// child makes, although this process goes on and gets its error. Two kinds end the child
// quietly (the parent still hears "the importer crashed"):
// - memory over the child's limit: under AddressSanitizer malloc then returns null, as without
//   it, but a failed `new` does not throw: it reports "out of memory" (the CLI's child, without
//   a sanitizer, answers "out of memory");
// - a memory error in Assimp's own code (it is not instrumented: AddressSanitizer sees it only
//   through its interceptors, as a bad free(), a memcpy out of bounds): the faulting frame, #0 or
//   #1 below an interceptor, is in libassimp. Such errors are why Assimp runs in a child.
// Every other report (a memory error in the conversion code, which is ours) still ends the child
// through libFuzzer, as a crash.
extern "C" const char* __asan_default_options() { return "allocator_may_return_null=1"; }

namespace {

// Line `#n ` of a report's first stack, or empty.
std::string_view Frame(std::string_view report, const char* tag) {
  const std::size_t at = report.find(tag);
  if (at == std::string_view::npos) return {};
  const std::size_t end = report.find('\n', at);
  return report.substr(at, end == std::string_view::npos ? end : end - at);
}

bool FaultsInAssimp(std::string_view report) {
  const std::string_view first = Frame(report, "#0 "), second = Frame(report, "#1 ");
  if (first.find("libassimp") != std::string_view::npos) return true;
  constexpr std::string_view kInterceptors[] = {
      "in operator new", "in operator delete", "in __interceptor_", "in __asan_", "in malloc",
      "in free",         "in calloc",          "in realloc",        "in memcpy",  "in memmove",
      "in memset",       "in strlen"};
  for (std::string_view interceptor : kInterceptors)
    if (first.find(interceptor) != std::string_view::npos)
      return second.find("libassimp") != std::string_view::npos;
  return false;
}

void EndChildOnContainedReport(const char* report) {
  for (const char* limit : {"out of memory", "allocation-size-too-big", "failed to allocate"})
    if (std::strstr(report, limit) != nullptr) ::_exit(kChildContainedReport);
  if (FaultsInAssimp(report)) ::_exit(kChildContainedReport);
}

const bool kChildReportsWatched = [] {
  ::pthread_atfork(nullptr, nullptr,
                   [] { __asan_set_error_report_callback(EndChildOnContainedReport); });
  return true;
}();

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const char* extension = kExtensions[data[0] % std::size(kExtensions)];
  const std::filesystem::path path =
      wirerig::fuzz::WriteInput(data + 1, size - 1, std::string("mesh.") + extension);
  wirerig::ImportOptions options;
  options.isolation = wirerig::ImportIsolation{};
  options.isolation->time_limit_seconds = 5.0;
  options.isolation->memory_limit_bytes = std::uint64_t{1} << 30;
  const wirerig::Result<wirerig::ImportedMesh> imported = wirerig::ImportMesh(path, options);
  if (!imported) {
    wirerig::fuzz::CheckNamesFile(imported.error(), path);
    return 0;
  }
  CheckMesh(imported.value().mesh);
  return 0;
}
