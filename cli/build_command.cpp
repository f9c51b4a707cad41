#include "build_command.h"
#include "option_checks.h"
#include "output_checks.h"

#include <cctype>
#include <map>
#include <ostream>

#include <CLI/CLI.hpp>

#include "wirerig/anim/clip_asset_export.h"
#include "wirerig/anim/scene.h"
#include "wirerig/io/atomic_file.h"
#include "wirerig/io/output_file.h"
#include "wirerig/runtime/rig_asset.h"

namespace wirerig::cli {

CLI::App* AddBuildCommand(CLI::App& app, BuildCommandOptions& options) {
  CLI::App* build =
      app.add_subcommand("build", "Build a scene's rig into a runtime asset (.wrig) for engines");
  build->add_option("scene", options.scene, "Scene file (JSON)")->required();
  build->add_option("-o,--output", options.output, "Output file (.wrig)")->required();
  build->add_flag("--clips", options.clips,
                  "Also write each clip, sampled for the runtime, as OUT.<clip>.wclip");
  build->add_option("--fps", options.fps, "Frames per second of the sampled clips")
      ->check(InRange(1, 1000))
      ->capture_default_str();
  // Options that do not apply are refused, not ignored.
  build->callback([build, &options] {
    if (build->count("--fps") > 0 && !options.clips)
      throw CLI::ValidationError("--fps", "samples the clips: applies with --clips only");
  });
  AddImportLimitOptions(build, options.import_limits);
  return build;
}

int RunBuildCommand(const BuildCommandOptions& options, std::ostream& out, std::ostream& err) {
  auto fail = [&](const std::string& message) {
    err << "wirerig build: " << message << "\n";
    return 1;
  };
  if (Result<bool> writable = CheckOutputFile(options.output, {".wrig"}); !writable)
    return fail(writable.error());
  if (Result<bool> own = CheckOutputIsNoSceneInput(options.output, options.scene); !own)
    return fail(own.error());
  Result<BuiltScene> built = LoadAndBuildScene(options.scene, options.import_limits.Isolation());
  if (!built) return fail(built.error());
  // The clips first, while the scene is whole; nothing is written until everything is made and
  // every clip's file is known to be writable and its own.
  std::vector<std::pair<std::filesystem::path, std::vector<std::uint8_t>>> clip_files;
  std::map<std::filesystem::path, std::string> clip_of_file;
  if (options.clips) {
    const std::filesystem::path output(options.output);
    for (const Clip& clip : built.value().clips) {
      std::vector<std::string> warnings;
      Result<SampledClip> sampled = SampleClipForRuntime(
          built.value().model, clip, built.value().description.playback, options.fps, &warnings);
      if (!sampled) return fail(options.scene + ": " + sampled.error());
      for (const std::string& warning : warnings) out << "warning: " << warning << "\n";
      std::filesystem::path path = output;
      std::string name = clip.name;  // as a file name: letters, digits, '-' and '_' kept
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
      path.replace_filename(output.stem().string() + "." + name + ".wclip");
      if (const auto [it, added] = clip_of_file.emplace(path, clip.name); !added)
        return fail(options.scene + ": clips \"" + it->second + "\" and \"" + clip.name +
                    "\" would both be written to " + path.string() +
                    " (a clip's file name keeps letters, digits, '-' and '_'): rename one; "
                    "nothing written");
      if (Result<bool> writable = CheckOutputFile(path, {".wclip"}); !writable)
        return fail(writable.error() + " (clip \"" + clip.name + "\"); nothing written");
      if (Result<bool> own =
              CheckOutputIsNoSceneInput(path, options.scene, built.value().description);
          !own)
        return fail(own.error() + " (clip \"" + clip.name + "\"); nothing written");
      out << "clip \"" << clip.name << "\": " << sampled.value().frame_count() << " frames at "
          << options.fps << " fps";
      if (!sampled.value().wires.empty())
        out << ", " << sampled.value().wires.size() << " wires with inertia";
      out << "\n";
      clip_files.emplace_back(path, SerializeClipAsset(sampled.value()));
    }
  }
  RigAsset asset;
  asset.model = std::move(built.value().model);
  asset.vertex_order = std::move(built.value().mesh.weld_map);
  if (Status valid = ValidateRigModel(asset.model); !valid)
    return fail(options.scene + ": the built rig is not valid: " + ToString(valid));
  const std::vector<std::uint8_t> bytes = SerializeRigAsset(asset);
  // All or nothing: the rig and its clips are written together, or none replaces an old file.
  auto view = [](const std::vector<std::uint8_t>& data) {
    return std::string_view(reinterpret_cast<const char*>(data.data()), data.size());
  };
  std::vector<FileToWrite> files = {{options.output, view(bytes)}};
  for (const auto& [path, clip_bytes] : clip_files) files.push_back({path, view(clip_bytes)});
  const auto written = WriteFilesAtomically(files);
  if (!written) return fail(written.error());
  out << "rig asset: " << asset.model.parts.size() << " parts, " << asset.model.vertices.size()
      << " welded vertices (" << asset.vertex_order.size() << " in the source order), "
      << asset.model.triangles.size() << " triangles, " << bytes.size() << " bytes\n"
      << "written: " << options.output << "\n";
  for (const auto& [path, clip_bytes] : clip_files)
    out << "written: " << path.string() << " (" << clip_bytes.size() << " bytes)\n";
  return 0;
}

}  // namespace wirerig::cli
