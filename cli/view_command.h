// `wirerig view SCENE [--clip NAME] [--size WxH] [--frames N] [--input SCRIPT]
//  [--screenshot PNG] [--no-window]`: the game-like viewer on a scene (viewer/scene_viewer.h).
// The picker lists the samples of the catalog. --frames, --input and --no-window let scripts
// and CI drive it (input scripts: viewer/input_script.h).
#pragma once

#include <iosfwd>
#include <string>

#include <CLI/App.hpp>

#include "import_limits.h"

namespace wirerig::cli {

struct ViewCommandOptions {
  std::string scene;
  std::string clip;
  std::string size = "1280x720";
  int frames = 0;
  std::string input;
  std::string screenshot;
  bool no_window = false;
  ImportLimitOptions import_limits;
};

CLI::App* AddViewCommand(CLI::App& app, ViewCommandOptions& options);

// Errors go to standard error, once, after "wirerig view: " (the viewer prints them).
int RunViewCommand(const ViewCommandOptions& options);

}  // namespace wirerig::cli
