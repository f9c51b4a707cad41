// What recorded motion costs an engine (issue 17, "Speed"): a .wclip replayed with the runtime
// alone, SampleClipJob + EvaluateRigJob per frame of 1/60 s, one thread, float engine buffers
// (interleaved positions and normals in the source asset's vertex order), against the same
// clip with its dynamics' record stripped (the wires at their static shapes, the skin's loops
// still):
//   ratio/<scene>   both clips alternately in one loop, each timed on its own (thread CPU time):
//                   counters still_us, moving_us and ratio = moving / still. Alternating frames
//                   see the same machine load, so the ratio is the figure to compare.
// Scenes, sampled at 30 frames per second by SampleClipForRuntime (outside the timed loops):
//   walk      samples/walk/walk.scene.json: the flesh of the trunk, thighs, shins and upper
//             arms (playback.profile_wires: 4 modes on each of their loops)
//   octopus   samples/octopus/octopus.scene.json: 8 modes on each arm (playback.wires) and
//             4 on each loop of the mantle (playback.profile_wires)
//   wirerig_clip_replay_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "bench_setup.h"
#include "wirerig/anim/clip_asset_export.h"
#include "wirerig/anim/scene.h"
#include "wirerig/runtime/clip_asset.h"
#include "wirerig/runtime/rig_evaluation.h"

#ifndef WIRERIG_SAMPLES_DIR
#error "the benchmarks need WIRERIG_SAMPLES_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {

using bench::Check;
using bench::ThreadSeconds;

constexpr double kFrame = 1.0 / 60.0;  // s

void Fail(const Status& s) {
  std::cerr << ToString(s) << "\n";
  std::exit(1);
}

// One clip's player: its buffers and an evaluation job writing float engine buffers.
class Player {
 public:
  Player(const BuiltScene& scene, const SampledClip& clip)
      : clip_(clip),
        buffers_(MakeClipPlaybackBuffers(clip_)),
        workspace_(MakeRigWorkspace(scene.model)),
        buffer_(6 * scene.mesh.weld_map.size()) {
    job_.model = &scene.model;
    job_.workspace = &workspace_;
    job_.preserve_volume = scene.description.playback.preserve_volume;
    job_.float_positions = buffer_;
    job_.float_position_stride = 6;
    job_.float_normals = std::span<float>(buffer_).subspan(3);
    job_.float_normal_stride = 6;
    job_.float_vertex_order = scene.mesh.weld_map;
  }

  void Frame() {
    const double t = double(frame_++) * kFrame;
    if (Status s = SampleClipJob{&clip_, t, &buffers_}.Run(); !s) Fail(s);
    job_.poses = buffers_.poses;
    job_.profile_loads = buffers_.used_profile_loads();
    if (Status s = job_.Run(); !s) Fail(s);
    if (t > clip_.duration) frame_ = 0;
  }
  const std::vector<float>& buffer() const { return buffer_; }

 private:
  SampledClip clip_;
  ClipPlaybackBuffers buffers_;
  RigWorkspace workspace_;
  std::vector<float> buffer_;
  EvaluateRigJob job_;
  std::size_t frame_ = 0;
};

void BM_Ratio(benchmark::State& state, const char* file) {
  const BuiltScene scene =
      Check(LoadAndBuildScene(std::string(WIRERIG_SAMPLES_DIR) + "/" + file), file);
  const SampledClip moving = Check(
      SampleClipForRuntime(scene.model, scene.clips.front(), scene.description.playback, 30.0),
      "clip");
  SampledClip still = moving;
  still.wires.clear(), still.wire_motion.clear();
  still.profile_wires.clear(), still.profile_wire_motion.clear();
  Player with(scene, moving), without(scene, still);
  double still_seconds = 0.0, moving_seconds = 0.0;
  bool moving_first = false;
  for (auto _ : state) {
    for (int half = 0; half < 2; ++half) {
      const bool is_moving = (half == 0) == moving_first;
      Player& player = is_moving ? with : without;
      const double start = ThreadSeconds();
      player.Frame();
      benchmark::DoNotOptimize(player.buffer().data());
      benchmark::ClobberMemory();
      (is_moving ? moving_seconds : still_seconds) += ThreadSeconds() - start;
    }
    moving_first = !moving_first;
  }
  const double n = double(state.iterations());
  state.counters["still_us"] = 1e6 * still_seconds / n;
  state.counters["moving_us"] = 1e6 * moving_seconds / n;
  state.counters["ratio"] = still_seconds > 0.0 ? moving_seconds / still_seconds : 0.0;
  state.counters["wires"] = double(moving.wires.size());
  state.counters["loops"] = double(moving.profile_wires.size());
}

BENCHMARK_CAPTURE(BM_Ratio, walk, "walk/walk.scene.json")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Ratio, octopus, "octopus/octopus.scene.json")->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
