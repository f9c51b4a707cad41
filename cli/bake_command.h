// `wirerig bake SCENE -o OUT.glb [--mode skin|morph] [--fps N] [--clip NAME]`: plays a clip of a
// scene, bakes it and exports animated glTF 2.0 (.glb, or .gltf + .bin). A progress bar on a
// terminal, quiet otherwise; on any failure a message naming the file and field, exit 1, and no
// output file.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>

#include <CLI/App.hpp>

#include "import_limits.h"

namespace wirerig::cli {

struct BakeCommandOptions {
  std::string scene;
  std::string output;
  std::string mode = "skin";  // the default: a game skeleton and a few shapes, small
  double fps = 30.0;
  std::string clip;  // empty: the scene's first clip
  bool residual = false;
  bool quantize = false;
  std::size_t max_joints = 64;       // skin mode: GltfExportOptions::max_joints
  std::size_t joints_per_part = 8;   // skin mode: GltfExportOptions::max_joints_per_part
  std::size_t max_correctives = 16;  // skin mode: GltfExportOptions::max_correctives
  double corrective_error = 1e-3;    // skin mode: GltfExportOptions::corrective_error, m
  double key_tolerance = 0.0;        // skin mode: GltfExportOptions::key_tolerance, m
  bool compress = false;             // skin mode: GltfExportOptions::compress
  bool keep_vertex_order = false;    // with compress: GltfExportOptions::keep_vertex_order
  int max_texture_size = 0;          // GltfExportOptions::max_texture_size
  bool jpeg_textures = false;        // GltfExportOptions::jpeg_textures
  std::size_t influences = 4;        // skin mode: GltfExportOptions::influences
  bool no_flesh_joints = false;      // skin mode: !GltfExportOptions::flesh_joints
  bool progress = false;             // set by main when stderr is a terminal
  ImportLimitOptions import_limits;
};

CLI::App* AddBakeCommand(CLI::App& app, BakeCommandOptions& options);

int RunBakeCommand(const BakeCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace wirerig::cli
