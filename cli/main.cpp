// wirerig: the command-line tool. Each subcommand lives in its own *_command.{h,cpp}.
// One exit-code policy for every command (printed by --help): 0 success, 1 bad input or
// failure, 2 usage error (CLI11's own parse error codes, 100 and up, are mapped to 2).
#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bake_command.h"
#include "build_command.h"
#include "rig_command.h"
#ifdef WIRERIG_HAS_VIEWER
#include "demo_command.h"
#include "render_command.h"
#include "samples_command.h"
#include "view_command.h"
#endif
#include "wire_command.h"
#include "wirerig/io/name_hint.h"

int main(int argc, char** argv) {
  CLI::App app{"wirerig: character rigging and animation with physically based wire deformations"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "wirerig " WIRERIG_VERSION);
  app.footer(
      "Exit codes (every command): 0 success; 1 bad input or failure (the message names the "
      "file and field); 2 usage error (unknown or missing subcommand, option or value).");

  wirerig::cli::WireCommandOptions wire_options;
  CLI::App* wire = wirerig::cli::AddWireCommand(app, wire_options);

  wirerig::cli::RigCommandOptions rig_options;
  CLI::App* rig = wirerig::cli::AddRigCommand(app, rig_options);

  wirerig::cli::BakeCommandOptions bake_options;
  CLI::App* bake = wirerig::cli::AddBakeCommand(app, bake_options);

  wirerig::cli::BuildCommandOptions build_options;
  CLI::App* build = wirerig::cli::AddBuildCommand(app, build_options);

#ifdef WIRERIG_HAS_VIEWER
  wirerig::cli::RenderCommandOptions render_options;
  CLI::App* render = wirerig::cli::AddRenderCommand(app, render_options);
  wirerig::cli::DemoCommandOptions demo_options;
  CLI::App* demo = wirerig::cli::AddDemoCommand(app, demo_options);
  wirerig::cli::SamplesCommandOptions samples_options;
  CLI::App* samples = wirerig::cli::AddSamplesCommand(app, samples_options);
  CLI::App* gallery = wirerig::cli::AddGalleryCommand(app, samples_options);
  wirerig::cli::ViewCommandOptions view_options;
  CLI::App* view = wirerig::cli::AddViewCommand(app, view_options);
#endif

  // An unknown command is named, with the nearest known one (CLI11 says only that a
  // subcommand is required).
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> names;
    for (const CLI::App* command : app.get_subcommands({})) names.push_back(command->get_name());
    if (std::find(names.begin(), names.end(), argv[1]) == names.end()) {
      std::cerr << "wirerig: unknown command \"" << argv[1] << "\""
                << wirerig::NameHint(argv[1], names, "commands")
                << "\nRun with --help for more information.\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end the parse with code 0; every other parse error is a usage error.
    return app.exit(e) == 0 ? 0 : 2;
  }
  auto run = [&]() -> int {
    if (wire->parsed())
      return wirerig::cli::RunWireCommand(wire_options, std::cin, std::cout, std::cerr);
    if (rig->parsed()) return wirerig::cli::RunRigCommand(rig_options, std::cout, std::cerr);
    if (build->parsed()) return wirerig::cli::RunBuildCommand(build_options, std::cout, std::cerr);
    if (bake->parsed()) {
      bake_options.progress = isatty(STDERR_FILENO) != 0;
      return wirerig::cli::RunBakeCommand(bake_options, std::cout, std::cerr);
    }
#ifdef WIRERIG_HAS_VIEWER
    if (render->parsed())
      return wirerig::cli::RunRenderCommand(render_options, std::cout, std::cerr);
    if (demo->parsed()) {
      demo_options.progress = isatty(STDERR_FILENO) != 0;
      return wirerig::cli::RunDemoCommand(demo_options, std::cout, std::cerr);
    }
    if (samples->parsed())
      return wirerig::cli::RunSamplesCommand(samples_options, std::cout, std::cerr);
    if (gallery->parsed())
      return wirerig::cli::RunGalleryCommand(samples_options, std::cout, std::cerr);
    if (view->parsed()) return wirerig::cli::RunViewCommand(view_options);
#endif
    return 1;
  };
  // The last line of defence: a command that runs out of memory (whatever its size checks
  // missed) says so and exits 1 instead of aborting; outputs are written to a temporary and
  // renamed, so nothing half-written is left.
  try {
    const int code = run();
    // Output that could not be written (a full disk, a closed pipe) is a failure, not success.
    std::cout.flush();
    if (!std::cout) {
      std::cerr << "wirerig: cannot write standard output\n";
      return 1;
    }
    return code;
  } catch (const std::bad_alloc&) {
    std::cerr << "wirerig: out of memory (the input asks for more than this machine has)\n";
    return 1;
  }
}
