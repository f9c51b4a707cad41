// Importing meshes with Assimp (glTF/GLB, OBJ, FBX, Collada/ZAE, OFF, PLY, STL, X, BLEND, ...).
// Node transforms are applied, units and up axis are converted to wirerig's conventions
// (metres, +Y up) and reported, vertices are welded by position.
//
// Each mesh instance in the node tree becomes a MeshPart (named after its node, or its mesh
// when the node holds several; made unique); points and lines are dropped, and so are
// triangles with coincident corners. A skinned mesh is placed as skinning places it at the
// bind pose (bone node transform * bone offset), not by its own node. Joints are the bone
// nodes plus the nodes that connect them below their lowest common ancestor.
//
// Up axis and units (Assimp 5.2.5): Collada's <up_axis> and <unit> are applied by Assimp
// itself and reported as "file metadata" (the up_axis option switches Assimp's rotation off;
// the unit_scale option replaces the file's unit); FBX states "UpAxis"/"UpAxisSign" and
// "UnitScaleFactor" (centimetres per unit) in metadata, which Assimp does not apply, so
// wirerig does. Other formats carry no such metadata: +Y and metres are assumed (BLEND files
// and CGAL's man.off, for example, are Z-up and need the option).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"

namespace wirerig {

enum class UpAxis : int { kY = 0, kZ = 1, kX = 2 };

// Importing in a child process. Assimp 5.2.5 crashes (segfaults, assertions) or loops forever
// on some corrupted files; with isolation, a forked child runs the import and sends the mesh
// back over a pipe, so a crash or a hang ends the child only and comes back as an error
// ("<path>: the importer crashed on this file (Segmentation fault)", "... timed out ..."). The
// fork copies the caller: call it while no other thread of the caller holds a lock the import
// needs (glibc's malloc is fork-safe); the child never returns into the caller's code.
struct ImportIsolation {
  // Wall-clock seconds the child may take before it is killed; must be > 0.
  double time_limit_seconds = 60.0;
  // Address space the child may add to what it inherits (RLIMIT_AS); 0: no limit.
  std::uint64_t memory_limit_bytes = std::uint64_t{8} << 30;
};

struct ImportOptions {
  // Source up axis; when unset, taken from the file's metadata, else +Z for a figure standing
  // along Z (far taller along Z than across, wider along X than deep along Y), else assumed +Y.
  std::optional<UpAxis> up_axis;
  // Metres per source unit; when unset, taken from the file's metadata, else 1.
  std::optional<double> unit_scale;
  // Files claiming more than this many vertices or triangles are refused before any large
  // allocation happens.
  std::uint64_t max_elements = 20'000'000;
  // Files larger than this are refused before they are read (a 10 GB file ran until the
  // import's time limit); the largest real assets are a few hundred MB.
  std::uintmax_t max_file_bytes = std::uintmax_t{2} << 30;
  // When set, Assimp runs in a child process (see ImportIsolation); the wirerig command sets
  // it for every mesh it imports. Never read from or written to files.
  std::optional<ImportIsolation> isolation;
};

// What the importer found and did, for the user to see.
struct ImportReport {
  std::string format;  // e.g. "Collada", "OFF": Assimp's importer, else the extension
  UpAxis source_up = UpAxis::kY;
  std::string up_source;            // "option", "file metadata", "shape: ..." or "assumed"
  double unit_scale = 1.0;          // metres per source unit that was applied
  std::string unit_source;          // "option", "file metadata" or "assumed"
  std::size_t source_vertices = 0;  // render vertices before welding
};

struct ImportedMesh {
  Mesh mesh;
  ImportReport report;
};

// Errors name the file and the problem ("<path>: no triangles", "<path>: claims 3.5e11
// vertices, more than the limit of 2e7", "<path>: cannot read (...)"). Refused: missing,
// unreadable, empty or unknown files, headers (OFF, PLY, binary STL) claiming more elements
// than max_elements or than the file can hold, non-finite coordinates, coordinates beyond
// 1e7 m, files without a usable triangle, PLY headers without "end_header" in their first 64 KB.
// Floating-point traps are masked while Assimp runs.
Result<ImportedMesh> ImportMesh(const std::filesystem::path& path,
                                const ImportOptions& options = {});

std::string_view ToString(UpAxis axis);
bool ParseUpAxis(std::string_view name, UpAxis* out);  // "x", "y", "z"

}  // namespace wirerig
