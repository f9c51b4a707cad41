#include "demo_command.h"

#include <filesystem>
#include <ostream>

#include <CLI/CLI.hpp>

#include "bake_command.h"
#include "octopus_scene.h"
#include "render_command.h"
#include "wirerig/io/atomic_file.h"

namespace wirerig::cli {

CLI::App* AddDemoCommand(CLI::App& app, DemoCommandOptions& options) {
  CLI::App* demo = app.add_subcommand(
      "demo",
      "The demo: bake the octopus's 10 s swim and 10 s crawl and the human's 10 s walk to .glb "
      "and draw their contact sheets, headless");
  demo->add_option("-o,--output", options.output,
                   "Folder for octopus.glb, .png and .scene.json, octopus_crawl.glb and .png, "
                   "walk.glb and .png")
      ->capture_default_str();
  options.samples = WIRERIG_SAMPLES_DIR;
  demo->add_option("--samples", options.samples,
                   "Samples folder holding walk/walk.scene.json (empty: no walk)")
      ->capture_default_str();
  return demo;
}

int RunDemoCommand(const DemoCommandOptions& options, std::ostream& out, std::ostream& err) {
  namespace fs = std::filesystem;
  const fs::path folder = options.output;
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) {
    err << "wirerig demo: " << folder.string() << ": cannot create the folder (" << ec.message()
        << ")\n";
    return 1;
  }
  // Every input is checked before anything is baked.
  const fs::path walk = fs::path(options.samples) / "walk" / "walk.scene.json";
  if (!options.samples.empty() && !fs::is_regular_file(walk, ec)) {
    err << "wirerig demo: " << walk.string()
        << ": no such sample scene (--samples names the samples folder)\n";
    return 1;
  }
  const fs::path scene = folder / "octopus.scene.json";
  if (Result<fs::path> written = WriteFileAtomically(scene, kOctopusScene); !written) {
    err << "wirerig demo: " << written.error() << "\n";
    return 1;
  }
  out << "written: " << scene.string() << "\n";

  BakeCommandOptions bake;
  bake.scene = scene.string();
  bake.output = (folder / "octopus.glb").string();
  bake.progress = options.progress;
  if (int code = RunBakeCommand(bake, out, err); code != 0) return code;

  RenderCommandOptions render;
  render.scene = scene.string();
  render.output = (folder / "octopus.png").string();
  render.size = "640x400";
  render.sheet = 6;
  if (int code = RunRenderCommand(render, out, err); code != 0) return code;

  // The octopus's second clip: it crawls along the ground on its arms.
  bake.clip = render.clip = "crawl";
  bake.output = (folder / "octopus_crawl.glb").string();
  if (int code = RunBakeCommand(bake, out, err); code != 0) return code;
  render.output = (folder / "octopus_crawl.png").string();
  if (int code = RunRenderCommand(render, out, err); code != 0) return code;
  bake.clip = render.clip = "";

  // The walk: human.zae on its bone chain (its mesh comes from scripts/setup.sh).
  if (options.samples.empty()) return 0;
  bake.scene = render.scene = walk.string();
  bake.output = (folder / "walk.glb").string();
  if (int code = RunBakeCommand(bake, out, err); code != 0) return code;
  render.output = (folder / "walk.png").string();
  render.size = "400x400";
  render.sheet = 8;  // 1.43 s apart: the steps (one a second) fall at different phases
  render.wires = false;
  return RunRenderCommand(render, out, err);
}

}  // namespace wirerig::cli
