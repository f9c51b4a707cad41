#include "bake_command.h"
#include "option_checks.h"
#include "output_checks.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <ostream>

#include <CLI/CLI.hpp>

#include "wirerig/anim/bake.h"
#include "wirerig/anim/gltf_export.h"
#include "wirerig/anim/scene.h"
#include "wirerig/io/output_file.h"

namespace wirerig::cli {
namespace {

// "[#########.......] 123/301 keys" redrawn in place.
void DrawProgress(std::ostream& err, std::size_t done, std::size_t total) {
  constexpr int kWidth = 32;
  const int filled = total == 0 ? kWidth : static_cast<int>(kWidth * done / total);
  err << "\r  baking [" << std::string(static_cast<std::size_t>(filled), '#')
      << std::string(static_cast<std::size_t>(kWidth - filled), '.') << "] " << done << "/" << total
      << " keys" << (done == total ? "\n" : "") << std::flush;
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

CLI::App* AddBakeCommand(CLI::App& app, BakeCommandOptions& options) {
  CLI::App* bake = app.add_subcommand("bake", "Bake a scene's clip and export animated glTF 2.0");
  bake->add_option("scene", options.scene, "Scene file (JSON)")->required();
  bake->add_option("-o,--output", options.output, "Output file: .glb, or .gltf (+ .bin)")
      ->required();
  bake->add_option(
          "--mode", options.mode,
          "skin: the rig's joints plus a few per deformable part, fitted to the bake, "
          "and corrective shapes (small; the default); morph: a morph target per key (exact, "
          "large, for offline tools)")
      ->check(CLI::IsMember({"skin", "morph"}))
      ->capture_default_str();
  bake->add_option("--fps", options.fps, "Keys per second")
      ->check(InRange(1, 1000))
      ->capture_default_str();
  bake->add_option("--clip", options.clip, "Clip to bake (default: the scene's first clip)");
  bake->add_flag("--residual", options.residual,
                 "skin mode: add residual morph targets so the export matches the bake exactly");
  bake->add_flag("--quantize", options.quantize,
                 "Smaller file, KHR_mesh_quantization: morph mode: deltas as shorts; skin mode: "
                 "corrective shapes as bytes, rest mesh as shorts and bytes, weights as bytes");
  bake->add_option("--max-joints", options.max_joints, "skin mode: joints per skin at most")
      ->check(InRange(1, 65535))
      ->capture_default_str();
  bake->add_option("--joints-per-part", options.joints_per_part,
                   "skin mode: joints of a deformable part at most (0: one per spine sample)")
      ->check(InRange(0, 65535))
      ->capture_default_str();
  bake->add_option("--max-correctives", options.max_correctives,
                   "skin mode: corrective shapes at most (0: none)")
      ->check(InRange(0, 256))
      ->capture_default_str();
  bake->add_option("--corrective-error", options.corrective_error,
                   "skin mode: correctives are added until the error is below this, m")
      ->check(Above(0))
      ->capture_default_str();
  bake->add_flag("--compress", options.compress,
                 "skin mode: EXT_meshopt_compression (smaller; needs a reader with a meshopt "
                 "decoder: three.js, Babylon.js; not Assimp 5.2 or Blender 3.4)");
  bake->add_flag("--keep-vertex-order", options.keep_vertex_order,
                 "with --compress: store the vertices in the mesh's order (by default, in the "
                 "order the codec stores in fewer bytes)");
  bake->add_option("--max-texture-size", options.max_texture_size,
                   "Embedded textures larger than this many pixels on their longer side are "
                   "downscaled to it and re-encoded (PNG, or JPEG at quality 90; 0: unchanged)")
      ->check(InRange(0, 65536))
      ->capture_default_str();
  bake->add_flag("--jpeg-textures", options.jpeg_textures,
                 "Embedded PNG textures stored as JPEG (quality 90) when that is smaller (the "
                 "materials are opaque: their alpha is not used)");
  bake->add_option("--influences", options.influences,
                   "skin mode: joints per vertex, 4 or 8 (8 adds JOINTS_1/WEIGHTS_1, which "
                   "three.js does not read)")
      ->check(CLI::IsMember({4, 8}))
      ->capture_default_str();
  bake->add_flag("--no-flesh-joints", options.no_flesh_joints,
                 "skin mode: no joints for jiggling skin (by default, joints left in the "
                 "--max-joints budget go where the bones miss the bake by more than "
                 "--corrective-error)");
  bake->add_option("--key-tolerance", options.key_tolerance,
                   "skin mode: a joint key is left out when interpolating its neighbours moves "
                   "the joint's vertices by at most this, m (0: every key)")
      ->check(InRange(0.0, 1.0))
      ->capture_default_str();
  // Options that do not apply to the chosen mode are refused, not ignored.
  bake->callback([bake, &options] {
    if (options.keep_vertex_order && !options.compress) {
      throw CLI::ValidationError("--keep-vertex-order",
                                 "applies to --compress only (other files keep the order)");
    }
    if (options.mode == "morph") {
      for (const char* name : {"--residual", "--max-joints", "--joints-per-part",
                               "--max-correctives", "--corrective-error", "--key-tolerance",
                               "--compress", "--influences", "--no-flesh-joints"}) {
        if (bake->count(name) > 0) throw CLI::ValidationError(name, "applies to --mode skin only");
      }
    } else if (options.residual &&
               (bake->count("--max-correctives") > 0 || bake->count("--corrective-error") > 0)) {
      throw CLI::ValidationError("--residual",
                                 "carries a target per key: it replaces the corrective shapes");
    } else if (options.quantize && !options.residual && options.max_correctives == 0) {
      throw CLI::ValidationError("--quantize",
                                 "quantizes morph targets: this skin has none (no --residual, "
                                 "--max-correctives 0)");
    }
  });
  AddImportLimitOptions(bake, options.import_limits);
  return bake;
}

int RunBakeCommand(const BakeCommandOptions& options, std::ostream& out, std::ostream& err) {
  auto fail = [&](const std::string& message) {
    if (options.progress) err << "\n";
    err << "wirerig bake: " << message << "\n";
    return 1;
  };
  // Where the output goes is checked before any work.
  if (Result<bool> writable = CheckOutputFile(options.output, {".glb", ".gltf"}); !writable)
    return fail(writable.error());
  if (Result<bool> own = CheckOutputIsNoSceneInput(options.output, options.scene); !own)
    return fail(own.error());
  const auto start = std::chrono::steady_clock::now();
  Result<BuiltScene> built = LoadAndBuildScene(options.scene, options.import_limits.Isolation());
  if (!built) return fail(built.error());
  const BuiltScene& scene = built.value();
  const Clip* clip = scene.FindClip(options.clip);
  if (!clip) {
    return fail(options.scene + ": " + scene.MissingClipMessage(options.clip));
  }
  out << "scene: " << options.scene << ": " << scene.mesh.positions.size() << " vertices, "
      << scene.mesh.triangles.size() << " triangles, " << scene.model.parts.size()
      << " parts; clip \"" << clip->name << "\", " << clip->duration << " s at " << options.fps
      << " fps\n";

  GltfExportOptions export_options;
  export_options.mode =
      options.mode == "skin" ? GltfAnimationMode::kSkin : GltfAnimationMode::kMorph;
  export_options.residual_morph_targets = options.residual;
  export_options.quantize = options.quantize;
  export_options.max_joints = options.max_joints;
  export_options.max_joints_per_part = options.joints_per_part;
  export_options.max_correctives = options.max_correctives;
  export_options.corrective_error = options.corrective_error;
  export_options.key_tolerance = options.key_tolerance;
  export_options.compress = options.compress;
  export_options.keep_vertex_order = options.keep_vertex_order;
  export_options.max_texture_size = options.max_texture_size;
  export_options.jpeg_textures = options.jpeg_textures;
  export_options.influences = options.influences;
  export_options.flesh_joints = !options.no_flesh_joints;
  export_options.node_name = scene.description.name;
  // An export too large to write is refused with its numbers before anything is baked.
  {
    std::size_t joints = 0;
    for (const PartModel& part : scene.model.parts) joints += part.spine_points.size();
    const double keys = BakeKeyCount(clip->duration, options.fps);
    const double bytes =
        EstimateGltfBytes(scene.mesh.positions.size(), joints, keys, true, export_options);
    if (bytes > kMaxGltfBytes) {
      const bool morph = export_options.mode == GltfAnimationMode::kMorph || options.residual;
      char numbers[160];
      std::snprintf(numbers, sizeof numbers,
                    "%s keys (%g s at %g fps) x %zu vertices: ", KeyCountText(keys).c_str(),
                    clip->duration, options.fps, scene.mesh.positions.size());
      return fail(options.output + ": " + numbers + GltfTooLargeMessage(bytes) +
                  "; bake fewer keys (--fps, a shorter clip)" +
                  (morph ? ", or --mode skin without --residual" : ""));
    }
  }

  BakeOptions bake_options;
  bake_options.fps = options.fps;
  bake_options.skin = options.mode == "skin";
  if (options.progress)
    bake_options.progress = [&](std::size_t done, std::size_t total) {
      DrawProgress(err, done, total);
    };
  const auto bake_start = std::chrono::steady_clock::now();
  Result<BakedAnimation> bake =
      BakeClip(scene.mesh, scene.model, *clip, scene.description.playback, bake_options);
  if (!bake) return fail(options.scene + ": clip \"" + clip->name + "\": " + bake.error());
  const double bake_seconds = Seconds(bake_start);

  if (!scene.description.mesh.file.empty()) {
    const std::filesystem::path mesh_file =
        scene.description.mesh.file.is_absolute()
            ? scene.description.mesh.file
            : scene.description.folder / scene.description.mesh.file;
    export_options.texture_dir = mesh_file.parent_path();
  }
  const auto export_start = std::chrono::steady_clock::now();
  Result<GltfExportReport> exported =
      ExportGltf(scene.mesh, bake.value(), export_options, options.output);
  if (!exported) return fail(exported.error());  // it names the file
  const GltfExportReport& report = exported.value();
  char line[256];
  std::snprintf(line, sizeof line,
                "baked %zu keys in %.3f s, exported %s (%.2f MB) in %.3f s; total %.3f s\n",
                report.key_count, bake_seconds, options.output.c_str(),
                static_cast<double>(report.bytes_written) / 1e6, Seconds(export_start),
                Seconds(start));
  out << line;
  if (export_options.mode == GltfAnimationMode::kSkin) {
    std::snprintf(line, sizeof line,
                  "skin: %zu joint%s (%zu keys stored), error against the bake max %.3g m (%.3g "
                  "of the diagonal), RMS %.3g m\n",
                  report.joint_count, report.joint_count == 1 ? "" : "s", report.joint_keys,
                  report.skin_max_error, report.skin_max_error_relative, report.skin_rms_error);
    out << line;
    if (options.residual) {
      std::snprintf(line, sizeof line, "residual targets: %zu, error max %.3g m",
                    report.morph_target_count, report.residual_max_error);
      out << line;
      if (report.quantized_position_targets > 0) {
        // The shorts round each delta: the file's error is within their bound.
        std::snprintf(line, sizeof line,
                      " as floats; %zu of them stored as shorts, within %.2g m of the bake",
                      report.quantized_position_targets,
                      report.residual_max_error + report.quantization_max_error);
        out << line;
      }
      out << "\n";
    } else if (options.max_correctives > 0) {
      std::snprintf(line, sizeof line,
                    "correctives: %zu shape%s, error against the bake max %.3g m, RMS %.3g m\n",
                    report.corrective_count, report.corrective_count == 1 ? "" : "s",
                    report.corrected_max_error, report.corrected_rms_error);
      out << line;
    }
  }
  for (const std::string& warning : bake.value().warnings) out << "warning: " << warning << "\n";
  for (const std::string& warning : report.warnings) out << "warning: " << warning << "\n";
  return 0;
}

}  // namespace wirerig::cli
