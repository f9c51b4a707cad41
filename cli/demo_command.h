// `wirerig demo [-o DIR]`: the octopus demo (paper Fig. 13), with no display. Writes the sample
// scene DIR/octopus.scene.json (a copy built into the binary), bakes its 10 s swim to
// DIR/octopus.glb (skin mode: fitted joints and corrective shapes) and draws DIR/octopus.png,
// a contact sheet of six times.
#pragma once

#include <iosfwd>
#include <string>

#include <CLI/App.hpp>

namespace wirerig::cli {

struct DemoCommandOptions {
  std::string output = "out";  // folder, created if missing
  // The samples folder holding walk/walk.scene.json (the human's walk, baked beside the
  // octopus); empty: no walk. The command line's default is the source tree's samples folder.
  std::string samples;
  bool progress = false;  // set by main when stderr is a terminal
};

CLI::App* AddDemoCommand(CLI::App& app, DemoCommandOptions& options);

int RunDemoCommand(const DemoCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace wirerig::cli
