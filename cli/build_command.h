// `wirerig build SCENE -o OUT.wrig [--clips] [--fps N]`: builds a scene's rig (mesh import,
// profiles, binding) once and writes it as a runtime asset (runtime/rig_asset.h) that an engine
// loads with the runtime alone, with the source asset's vertex order so it can evaluate straight
// into its own vertex buffer. With --clips, each of the scene's clips is played offline and
// sampled at N frames per second into OUT.<clip>.wclip (runtime/clip_asset.h). On failure a
// message naming the file and field, exit 1, and no output file.
#pragma once

#include <iosfwd>
#include <string>

#include <CLI/App.hpp>

#include "import_limits.h"

namespace wirerig::cli {

struct BuildCommandOptions {
  std::string scene;
  std::string output;
  bool clips = false;
  double fps = 30.0;
  ImportLimitOptions import_limits;
};

CLI::App* AddBuildCommand(CLI::App& app, BuildCommandOptions& options);

int RunBuildCommand(const BuildCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace wirerig::cli
