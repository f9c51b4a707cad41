// `wirerig bake SCENE -o OUT.glb [--mode morph|skin] [--fps N] [--clip NAME]`: plays a clip of a
// scene, bakes it and exports animated glTF 2.0 (.glb, or .gltf + .bin). A progress bar on a
// terminal, quiet otherwise; on any failure a message naming the file and field, exit 1, and no
// output file.
#pragma once

#include <iosfwd>
#include <string>

#include <CLI/App.hpp>

#include "import_limits.h"

namespace wirerig::cli {

struct BakeCommandOptions {
  std::string scene;
  std::string output;
  std::string mode = "morph";
  double fps = 30.0;
  std::string clip;  // empty: the scene's first clip
  bool residual = false;
  bool quantize = false;
  bool progress = false;  // set by main when stderr is a terminal
  ImportLimitOptions import_limits;
};

CLI::App* AddBakeCommand(CLI::App& app, BakeCommandOptions& options);

int RunBakeCommand(const BakeCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace wirerig::cli
