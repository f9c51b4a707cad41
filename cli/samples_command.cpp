#include "samples_command.h"

#include <filesystem>
#include <ostream>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bake_command.h"
#include "render_command.h"
#include "wirerig/io/atomic_file.h"
#include "wirerig/io/input_file.h"
#include "wirerig/io/json_fields.h"
#include "wirerig/io/json_text.h"
#include "wirerig/io/output_file.h"

#ifndef WIRERIG_SAMPLES_DIR
#define WIRERIG_SAMPLES_DIR "samples"
#endif

namespace wirerig::cli {
namespace {

namespace fs = std::filesystem;

std::string SamplesDir(const SamplesCommandOptions& options) {
  return options.dir.empty() ? std::string(WIRERIG_SAMPLES_DIR) : options.dir;
}

}  // namespace

Result<std::vector<CatalogEntry>> LoadCatalog(const std::string& path) {
  Result<std::string> text = ReadInputFile(path, "sample catalog (JSON)");
  if (!text) return Error{text.error()};
  Result<nlohmann::json> parsed = ParseJsonText(text.value(), path);
  if (!parsed) return Error{parsed.error()};
  const nlohmann::json& document = parsed.value();
  std::vector<CatalogEntry> entries;
  try {
    const nlohmann::json& array = RequireArray(document, "");
    for (std::size_t i = 0; i < ArraySize(array); ++i) {
      const JsonObject o(ArrayElement(array, i), "/" + std::to_string(i));
      o.RejectUnknownKeys({"name", "title", "figure", "scene", "clip", "picture", "summary", "time",
                           "sheet", "skin"});
      CatalogEntry e;
      e.name = o.String("name");
      e.title = o.String("title");
      e.figure = o.Has("figure") ? o.String("figure") : "";
      if (o.Has("scene") == o.Has("picture"))
        throw FieldError(o.path(), "needs exactly one of \"scene\" and \"picture\"");
      e.scene = o.Has("scene") ? o.String("scene") : "";
      e.clip = o.Has("clip") ? o.String("clip") : "";
      e.picture = o.Has("picture") ? o.String("picture") : "";
      e.summary = o.String("summary");
      e.time = o.Number("time", -1.0);
      e.sheet = o.Integer("sheet", 4);
      if (e.sheet < 1 || e.sheet > 16) throw FieldError(o.PathOf("sheet"), "must be in [1, 16]");
      e.skin = o.Bool("skin", e.skin);
      entries.push_back(std::move(e));
    }
  } catch (const FieldError& e) {
    return Error{path + ": " + e.what()};
  }
  return entries;
}

CLI::App* AddSamplesCommand(CLI::App& app, SamplesCommandOptions& options) {
  CLI::App* samples = app.add_subcommand("samples", "List the samples (the paper's examples)");
  samples->add_option("--dir", options.dir, "Samples folder (holding catalog.json)");
  return samples;
}

CLI::App* AddGalleryCommand(CLI::App& app, SamplesCommandOptions& options) {
  CLI::App* gallery = app.add_subcommand(
      "gallery", "Draw every sample's picture and write the gallery page, headless");
  gallery->add_option("--dir", options.dir, "Samples folder (holding catalog.json)");
  gallery->add_option("--page", options.page, "Gallery page to write (Markdown)");
  gallery->add_flag("--glb", options.glb, "Also bake every sample to <name>.glb in its folder");
  return gallery;
}

int RunSamplesCommand(const SamplesCommandOptions& options, std::ostream& out, std::ostream& err) {
  const std::string dir = SamplesDir(options);
  Result<std::vector<CatalogEntry>> catalog = LoadCatalog(dir + "/catalog.json");
  if (!catalog) {
    err << "wirerig samples: " << catalog.error() << "\n";
    return 1;
  }
  for (const CatalogEntry& e : catalog.value()) {
    out << e.name << std::string(e.name.size() < 14 ? 14 - e.name.size() : 1, ' ') << e.title;
    if (!e.figure.empty()) out << " (" << e.figure << ")";
    out << "\n"
        << std::string(14, ' ') << e.summary << "\n"
        << std::string(14, ' ')
        << (fs::path(dir) / (e.scene.empty() ? e.picture : e.scene)).string() << "\n";
  }
  return 0;
}

int RunGalleryCommand(const SamplesCommandOptions& options, std::ostream& out, std::ostream& err) {
  const fs::path dir = SamplesDir(options);
  const fs::path page =
      options.page.empty() ? dir.parent_path() / "docs" / "gallery.md" : fs::path(options.page);
  // Where the page goes is checked before any picture is drawn.
  if (Result<bool> writable = CheckOutputFile(page, {".md"}); !writable) {
    err << "wirerig gallery: " << writable.error() << "\n";
    return 1;
  }
  Result<std::vector<CatalogEntry>> catalog = LoadCatalog((dir / "catalog.json").string());
  if (!catalog) {
    err << "wirerig gallery: " << catalog.error() << "\n";
    return 1;
  }
  std::ostringstream md;
  md << "# Gallery\n\n"
     << "Every sample of [`samples/catalog.json`](../samples/catalog.json), drawn by the headless\n"
     << "renderer (EGL on Mesa, no GPU). Regenerate with `build/cli/wirerig gallery`.\n"
     << "Profile wires are blue, spine wires pink, load arrows red.\n";
  for (const CatalogEntry& e : catalog.value()) {
    if (e.scene.empty()) {  // a picture made by the sample's own program
      md << "\n## " << e.title << (e.figure.empty() ? "" : " (" + e.figure + ")") << "\n\n"
         << e.summary << "\n\n![" << e.name << "]("
         << fs::relative(dir / e.picture, page.parent_path()).generic_string() << ")\n";
      continue;
    }
    const fs::path scene = dir / e.scene;
    const fs::path picture = scene.parent_path() / (e.name + ".png");
    RenderCommandOptions render;
    render.scene = scene.string();
    render.output = picture.string();
    render.clip = e.clip;
    if (e.time >= 0.0) {
      render.time = e.time;
      render.size = "960x640";
    } else {
      render.sheet = e.sheet;
      render.size = "480x360";
    }
    if (int code = RunRenderCommand(render, out, err); code != 0) {
      err << "wirerig gallery: " << e.name << ": the picture failed\n";
      return code;
    }
    const fs::path skin_picture = scene.parent_path() / (e.name + "_skin.png");
    if (e.skin) {
      render.output = skin_picture.string();
      render.wires = false;
      if (int code = RunRenderCommand(render, out, err); code != 0) {
        err << "wirerig gallery: " << e.name << ": the picture without wires failed\n";
        return code;
      }
    }
    if (options.glb) {
      BakeCommandOptions bake;
      bake.scene = scene.string();
      bake.output = (scene.parent_path() / (e.name + ".glb")).string();
      if (int code = RunBakeCommand(bake, out, err); code != 0) {
        err << "wirerig gallery: " << e.name << ": the bake failed\n";
        return code;
      }
    }
    const fs::path relative = fs::relative(picture, page.parent_path());
    md << "\n## " << e.title;
    if (!e.figure.empty()) md << " (" << e.figure << ")";
    md << "\n\n"
       << e.summary << " Scene: [`" << e.scene << "`]("
       << fs::relative(scene, page.parent_path()).generic_string() << ").\n\n![" << e.name << "]("
       << relative.generic_string() << ")\n";
    if (e.skin)
      md << "\nWithout the wires:\n\n![" << e.name << " skin]("
         << fs::relative(skin_picture, page.parent_path()).generic_string() << ")\n";
  }
  if (Result<fs::path> written = WriteFileAtomically(page, md.str()); !written) {
    err << "wirerig gallery: " << written.error() << "\n";
    return 1;
  }
  out << "written: " << page.string() << "\n";
  return 0;
}

}  // namespace wirerig::cli
