#include "render_command.h"
#include "option_checks.h"
#include "output_checks.h"

#include <cstdio>
#include <ostream>

#include <CLI/CLI.hpp>

#include "wirerig/anim/bake.h"
#include "wirerig/anim/scene.h"
#include "wirerig/io/output_file.h"
#include "wirerig/viewer/headless.h"
#include "wirerig/viewer/image.h"
#include "wirerig/viewer/scene_frame.h"

namespace wirerig::cli {
namespace {

std::string TimeLabel(double t) {
  char label[32];
  std::snprintf(label, sizeof label, "t = %.2f s", t);
  return label;
}

}  // namespace

CLI::App* AddRenderCommand(CLI::App& app, RenderCommandOptions& options) {
  CLI::App* render = app.add_subcommand("render", "Draw a scene at a time to PNG, headless");
  render->add_option("scene", options.scene, "Scene file (JSON)")->required();
  render->add_option("-o,--output", options.output, "PNG file to write")->required();
  render->add_option("-t,--time", options.time, "Time in the clip, s")
      ->check(AtLeast(0))
      ->capture_default_str();
  render->add_option("--size", options.size, "Image (or tile) size, WIDTHxHEIGHT")
      ->check(ImageSize())
      ->capture_default_str();
  render->add_option("--clip", options.clip, "Clip to play (default: the scene's first)");
  render
      ->add_option("--sheet", options.sheet,
                   "Draw a contact sheet of this many times spread over the clip")
      ->check(InRange(1, 64));
  render->add_flag("!--no-wires", options.wires, "Hide the profile and spine wires");
  render
      ->add_option("--color", options.color,
                   "Skin colour: base, moment (bending moment) or strain (axial strain)")
      ->check(CLI::IsMember({"base", "moment", "strain"}))
      ->capture_default_str();
  AddImportLimitOptions(render, options.import_limits);
  return render;
}

int RunRenderCommand(const RenderCommandOptions& options, std::ostream& out, std::ostream& err) {
  auto fail = [&](const std::string& message) {
    err << "wirerig render: " << message << "\n";
    return 1;
  };
  // Where the output goes is checked before any work (PNG only: no other image writer).
  if (Result<bool> writable = CheckOutputFile(options.output, {".png"}); !writable)
    return fail(writable.error());
  if (Result<bool> own = CheckOutputIsNoSceneInput(options.output, options.scene); !own)
    return fail(own.error());
  Size size;
  if (!ParseImageSize(options.size, &size.width, &size.height))
    return fail(std::string("--size: must be ") + kImageSizeRule);
  const int n = options.sheet;
  const int columns = n <= 4 ? n : (n <= 9 ? 3 : 4);
  if (n > 0) {
    const SheetSize sheet = ContactSheetSize(n, size, columns);
    if (sheet.width * sheet.height > kMaxPngPixels) {
      err << "wirerig render: --size " << options.size << " with --sheet " << n
          << ": the sheet would be " << sheet.width << "x" << sheet.height
          << " pixels, more than the " << kMaxPngPixels
          << " a PNG is written with; use a smaller --size or fewer times\n";
      return 2;
    }
  }
  Result<BuiltScene> built = LoadAndBuildScene(options.scene, options.import_limits.Isolation());
  if (!built) return fail(built.error());
  const BuiltScene& scene = built.value();
  const Clip* clip = scene.FindClip(options.clip);
  if (!options.clip.empty() && !clip)
    return fail(options.scene + ": " + scene.MissingClipMessage(options.clip));
  const Clip rest = RestClip(scene.model);  // a scene without clips is drawn at rest
  if (!clip) clip = &rest;
  Result<Playback> made = Playback::Make(scene.model, *clip, scene.description.playback);
  if (!made) return fail(options.scene + ": " + made.error());
  Playback& playback = made.value();

  const SceneColoring coloring = options.color == "moment"   ? SceneColoring::kBendingMoment
                                 : options.color == "strain" ? SceneColoring::kAxialStrain
                                                             : SceneColoring::kBaseColor;
  SceneFrame picture(scene);
  picture.set_coloring(coloring);
  std::vector<Vec3> positions(scene.model.vertices.size()), normals(positions.size());
  RenderOptions render_options;
  render_options.show_wires = options.wires;
  std::vector<PartWarnings> warnings(scene.model.parts.size());
  auto evaluate = [&](double t) -> std::string {
    if (Status s = playback.Evaluate(t, positions, normals, warnings); !s)
      return "t = " + std::to_string(t) + " s: " + ToString(s);
    for (std::size_t p = 0; p < warnings.size(); ++p)
      if (std::string w = DeflectionWarning(scene.model.parts[p], warnings[p], t); !w.empty())
        out << "warning: " << w << "\n";
    picture.Update(playback, positions, normals);
    return {};
  };

  if (options.sheet == 0) {
    if (std::string e = evaluate(options.time); !e.empty()) return fail(options.scene + ": " + e);
    picture.set_caption(scene.description.name + "  " + TimeLabel(options.time));
    const Camera camera = picture.InitialCamera(size);
    Result<std::filesystem::path> written =
        RenderToPng(picture.frame(), camera, size, options.output, render_options);
    if (!written) return fail(written.error());
    out << "written: " << options.output << "\n";
    return 0;
  }
  // Contact sheet: every tile keeps the first tile's camera so motion reads across tiles (moved
  // with the part the camera hint follows, if any).
  std::vector<ContactSheetTile> tiles;
  std::vector<SceneFrame> pictures;
  pictures.reserve(static_cast<std::size_t>(n));
  Camera camera;
  for (int i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.0 : clip->duration * i / (n - 1);
    if (std::string e = evaluate(t); !e.empty()) return fail(options.scene + ": " + e);
    pictures.emplace_back(scene);
    pictures.back().set_coloring(coloring);
    pictures.back().Update(playback, positions, normals);
    if (i == 0) camera = pictures.back().InitialCamera(size);
    Camera tile_camera = camera;  // a followed part: the target moves with it
    tile_camera.target += pictures.back().FollowOffset() - pictures.front().FollowOffset();
    tiles.push_back({pictures.back().frame(), tile_camera, TimeLabel(t)});
  }
  Result<std::filesystem::path> written =
      RenderContactSheet(tiles, size, columns, options.output, render_options);
  if (!written) return fail(written.error());
  out << "written: " << options.output << " (" << n << " times)\n";
  return 0;
}

}  // namespace wirerig::cli
