#include "view_command.h"
#include "option_checks.h"

#include <iostream>
#include <ostream>

#include <CLI/CLI.hpp>

#include "samples_command.h"
#include "wirerig/io/output_file.h"
#include "wirerig/viewer/scene_viewer.h"

#ifndef WIRERIG_SAMPLES_DIR
#define WIRERIG_SAMPLES_DIR "samples"
#endif

namespace wirerig::cli {

CLI::App* AddViewCommand(CLI::App& app, ViewCommandOptions& options) {
  CLI::App* view = app.add_subcommand("view", "Open a scene in the viewer (GLFW + OpenGL 3.3)");
  view->add_option("scene", options.scene, "Scene file (JSON)")->required();
  view->add_option("--clip", options.clip, "Clip to play (default: the scene's first)");
  view->add_option("--size", options.size, "Window size, WIDTHxHEIGHT")
      ->check(ImageSize())
      ->capture_default_str();
  view->add_option("--frames", options.frames, "Stop after this many frames (0: run until closed)")
      ->check(InRange(0, 1e9));
  view->add_option("--input", options.input, "Replay an input script (mouse and keys per frame)");
  view->add_option("--screenshot", options.screenshot, "Write the last frame to this PNG");
  view->add_flag("--no-window", options.no_window,
                 "Run headless (EGL), for scripts and tests; needs --frames");
  // Headless, nothing can close the view: it must be told when to stop.
  view->callback([view, &options] {
    if (options.no_window && options.frames == 0)
      throw CLI::ValidationError("--no-window", "needs --frames N (N >= 1): nothing can close it");
  });
  AddImportLimitOptions(view, options.import_limits);
  return view;
}

int RunViewCommand(const ViewCommandOptions& options) {
  // Where the screenshot goes is checked before the scene is loaded.
  if (!options.screenshot.empty()) {
    if (Result<bool> writable = CheckOutputFile(options.screenshot, {".png"}); !writable) {
      std::cerr << "wirerig view: " << writable.error() << "\n";
      return 1;
    }
  }
  SceneViewerOptions viewer;
  viewer.scene = options.scene;
  viewer.clip = options.clip;
  viewer.import_isolation =
      options.import_limits.Isolation();  // a crash or hang of Assimp must not end the view
  // The picker: the catalog's scenes, when the catalog is there.
  Result<std::vector<CatalogEntry>> catalog =
      LoadCatalog(std::string(WIRERIG_SAMPLES_DIR) + "/catalog.json");
  if (catalog)
    for (const CatalogEntry& entry : catalog.value())
      if (!entry.scene.empty())
        viewer.samples.push_back(
            {entry.name, std::filesystem::path(WIRERIG_SAMPLES_DIR) / entry.scene});
  // The application parses its own options; hand them over in its syntax.
  // The application prints its one error after its name.
  std::vector<std::string> args = {"wirerig view", "--size", options.size, "--frames",
                                   std::to_string(options.frames)};
  if (!options.input.empty()) args.insert(args.end(), {"--input", options.input});
  if (!options.screenshot.empty()) args.insert(args.end(), {"--screenshot", options.screenshot});
  if (options.no_window) args.push_back("--no-window");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  SceneViewer app(std::move(viewer));
  return app.Run(int(argv.size()), argv.data());
}

}  // namespace wirerig::cli
