// Bake and export of a 10 s clip at 30 fps (301 keys), morph mode, on the two sample scenes:
// samples/human/human_wave.scene.json (human.zae, 15.6k render vertices) and
// samples/octopus/octopus.scene.json (the procedural octopus, 8.4k). Target: under 1 s each
// (bake + .glb export). Scenes are loaded and built outside the timed loop.
//  * BM_Bake: BakeClip alone.
//  * BM_Export: ExportGltf of a finished bake to a .glb (file written, then removed).
//  * BM_BakeAndExport: both, what `wirerig bake` does after loading; reports the file size.
//  * BM_ExportQuantized: BM_Export with GltfExportOptions::quantize (KHR_mesh_quantization);
//    reports the file size, the quantized position / normal targets and the largest position
//    rounding error (mm).
//  * BM_ExportSkin: ExportGltf in skin mode (the CLI's default: fitted joints, corrective
//    shapes), plain and with EXT_meshopt_compression (*_compressed); reports the file size,
//    joints, correctives and the max error against the bake.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>

#include "wirerig/anim/bake.h"
#include "wirerig/anim/gltf_export.h"
#include "wirerig/anim/scene.h"

#ifndef WIRERIG_SAMPLES_DIR
#error "the benchmarks need WIRERIG_SAMPLES_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {

const BuiltScene& Scene(const std::string& name) {
  static std::map<std::string, BuiltScene> scenes;
  auto it = scenes.find(name);
  if (it != scenes.end()) return it->second;
  const std::string path = std::string(WIRERIG_SAMPLES_DIR) + "/" + name;
  Result<BuiltScene> built = LoadAndBuildScene(path);
  if (!built) {
    std::cerr << built.error() << "\n";
    std::exit(1);
  }
  return scenes.emplace(name, std::move(built).value()).first->second;
}

// `skin`: with the skin weights skin-mode export needs (BakeOptions::skin).
BakedAnimation Bake(const BuiltScene& scene, bool skin = false) {
  BakeOptions options;
  options.skin = skin;
  Result<BakedAnimation> bake =
      BakeClip(scene.mesh, scene.model, scene.clips.front(), scene.description.playback, options);
  if (!bake) {
    std::cerr << bake.error() << "\n";
    std::exit(1);
  }
  return std::move(bake).value();
}

std::filesystem::path Output(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("wirerig_bake_bench_" + std::filesystem::path(name).stem().string() + ".glb");
}

GltfExportReport ExportReport(const BuiltScene& scene, const BakedAnimation& bake,
                              const std::filesystem::path& out, bool quantize,
                              GltfAnimationMode mode = GltfAnimationMode::kMorph,
                              bool compress = false) {
  GltfExportOptions options;
  options.quantize = quantize;
  options.mode = mode;
  options.compress = compress;
  Result<GltfExportReport> report = ExportGltf(scene.mesh, bake, options, out);
  if (!report) {
    std::cerr << report.error() << "\n";
    std::exit(1);
  }
  return std::move(report).value();
}

std::uintmax_t Export(const BuiltScene& scene, const BakedAnimation& bake,
                      const std::filesystem::path& out) {
  return ExportReport(scene, bake, out, false).bytes_written;
}

void SetCounters(benchmark::State& state, const BuiltScene& scene, std::uintmax_t bytes) {
  state.counters["vertices"] = double(scene.mesh.positions.size());
  state.counters["keys"] = double(BakeKeyTimes(scene.clips.front().duration, 30.0).size());
  if (bytes > 0) state.counters["file_MB"] = double(bytes) / 1e6;
}

void BM_Bake(benchmark::State& state, const char* name) {
  const BuiltScene& scene = Scene(name);
  for (auto _ : state) benchmark::DoNotOptimize(Bake(scene));
  SetCounters(state, scene, 0);
}

void BM_Export(benchmark::State& state, const char* name) {
  const BuiltScene& scene = Scene(name);
  const BakedAnimation bake = Bake(scene);
  const auto out = Output(name);
  std::uintmax_t bytes = 0;
  for (auto _ : state) bytes = Export(scene, bake, out);
  std::filesystem::remove(out);
  SetCounters(state, scene, bytes);
}

void BM_ExportQuantized(benchmark::State& state, const char* name) {
  const BuiltScene& scene = Scene(name);
  const BakedAnimation bake = Bake(scene);
  const auto out = Output(name);
  GltfExportReport report;
  for (auto _ : state) report = ExportReport(scene, bake, out, true);
  std::filesystem::remove(out);
  SetCounters(state, scene, report.bytes_written);
  state.counters["q_positions"] = double(report.quantized_position_targets);
  state.counters["q_normals"] = double(report.quantized_normal_targets);
  state.counters["q_error_mm"] = report.quantization_max_error * 1e3;
}

// `compress`: GltfExportOptions::compress (EXT_meshopt_compression).
void BM_ExportSkin(benchmark::State& state, const char* name, bool compress) {
  const BuiltScene& scene = Scene(name);
  const BakedAnimation bake = Bake(scene, /*skin=*/true);
  const auto out = Output(name);
  GltfExportReport report;
  for (auto _ : state)
    report = ExportReport(scene, bake, out, false, GltfAnimationMode::kSkin, compress);
  std::filesystem::remove(out);
  SetCounters(state, scene, report.bytes_written);
  state.counters["joints"] = double(report.joint_count);
  state.counters["correctives"] = double(report.corrective_count);
  state.counters["max_error_mm"] = report.corrected_max_error * 1e3;
}

void BM_BakeAndExport(benchmark::State& state, const char* name) {
  const BuiltScene& scene = Scene(name);
  const auto out = Output(name);
  std::uintmax_t bytes = 0;
  for (auto _ : state) bytes = Export(scene, Bake(scene), out);
  std::filesystem::remove(out);
  SetCounters(state, scene, bytes);
}

constexpr const char* kHuman = "human/human_wave.scene.json";
constexpr const char* kOctopus = "octopus/octopus.scene.json";
constexpr const char* kWalk = "walk/walk.scene.json";

BENCHMARK_CAPTURE(BM_Bake, human, kHuman)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Bake, octopus, kOctopus)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Export, human, kHuman)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Export, octopus, kOctopus)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ExportQuantized, human, kHuman)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ExportQuantized, octopus, kOctopus)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ExportSkin, human, kHuman, false)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ExportSkin, walk, kWalk, false)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ExportSkin, octopus, kOctopus, false)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ExportSkin, human_compressed, kHuman, true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ExportSkin, walk_compressed, kWalk, true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ExportSkin, octopus_compressed, kOctopus, true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_BakeAndExport, human, kHuman)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_BakeAndExport, octopus, kOctopus)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
