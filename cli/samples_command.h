// `wirerig samples [--dir DIR]`: lists the samples of the catalog (DIR/catalog.json).
// `wirerig gallery [--dir DIR] [--page FILE]`: draws every sample's picture headless into its
// folder (DIR/<name>/<name>.png) and writes the gallery page (default docs/gallery.md).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include <CLI/App.hpp>

#include "wirerig/io/result.h"

namespace wirerig::cli {

struct CatalogEntry {
  std::string name;  // folder and picture name
  std::string title;
  std::string figure;   // the paper's figure, e.g. "Fig. 6"
  std::string scene;    // relative to the samples folder; or empty and:
  std::string picture;  // a picture the sample's own program draws (relative to the folder)
  std::string summary;  // one line
  double time = -1.0;   // picture: a single time (s), or -1 for a contact sheet
  int sheet = 4;        // picture: tiles of the contact sheet
  std::string clip;     // the scene's clip to draw; empty: its first
  bool skin = false;    // also a picture without the wire overlay (<name>_skin.png)
};

// Errors name the file and the JSON pointer.
Result<std::vector<CatalogEntry>> LoadCatalog(const std::string& path);

struct SamplesCommandOptions {
  std::string dir;   // default: the source tree's samples/ folder
  std::string page;  // gallery page; default: <dir>/../docs/gallery.md
  bool glb = false;  // gallery: also bake every scene sample to <dir>/<name>/<name>.glb
};

CLI::App* AddSamplesCommand(CLI::App& app, SamplesCommandOptions& options);
CLI::App* AddGalleryCommand(CLI::App& app, SamplesCommandOptions& options);

int RunSamplesCommand(const SamplesCommandOptions& options, std::ostream& out, std::ostream& err);
int RunGalleryCommand(const SamplesCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace wirerig::cli
