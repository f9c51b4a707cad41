// `wirerig render SCENE [--time T] -o OUT.png [--size WxH] [--clip NAME] [--sheet N]`: draws a
// scene at a time of its clip to PNG without a display (EGL surfaceless on Mesa). With --sheet N
// it draws N times spread over the clip into one contact sheet instead.
#pragma once

#include <iosfwd>
#include <string>

#include <CLI/App.hpp>

#include "import_limits.h"

namespace wirerig::cli {

struct RenderCommandOptions {
  std::string scene;
  std::string output;
  double time = 0.0;  // s
  std::string size = "1280x720";
  std::string clip;
  int sheet = 0;  // 0: one picture; N > 0: a contact sheet of N times
  bool wires = true;
  std::string color = "base";  // base, moment or strain
  ImportLimitOptions import_limits;
};

CLI::App* AddRenderCommand(CLI::App& app, RenderCommandOptions& options);

int RunRenderCommand(const RenderCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace wirerig::cli
