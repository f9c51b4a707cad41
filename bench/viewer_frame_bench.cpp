// The viewer's CPU time per frame on human.zae (issue 6 target: under 4 ms): what `wirerig view`
// does every frame for samples/human/human_wave.scene.json, split in its parts.
//  * BM_FrameEvaluation: Playback::Evaluate (clip sampling, the closed forms of every wire, the
//    skin's positions and normals) plus SceneFrame::Update (the float buffers the renderer
//    reads), at a time that moves every frame.
//  * BM_FrameEvaluationAndUpload: the same plus Renderer::Render headless (buffer uploads and
//    draw calls; 1× AA, 1024 shadow map, 960x540) and glFinish. "CPU" is the calling thread
//    only: evaluation plus upload plus issuing the draws; rasterisation runs on llvmpipe's
//    own threads (no GPU here) and shows in the wall time ("Time"). Counters give the issue's
//    measure, evaluation plus upload per frame (the renderer times its uploads: mesh buffers,
//    wire ribbons and arrows built on the CPU).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>

#include "wirerig/anim/scene.h"
#include "wirerig/viewer/headless.h"
#include "wirerig/viewer/scene_frame.h"

#ifndef WIRERIG_SAMPLES_DIR
#error "the benchmarks need WIRERIG_SAMPLES_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {

struct Viewer {
  BuiltScene scene;
  std::unique_ptr<Playback> playback;
  std::unique_ptr<SceneFrame> picture;
  std::vector<Vec3> positions, normals;
  double t = 0.0;

  void Step() {
    t += 1.0 / 60.0;
    if (!playback->Evaluate(t, positions, normals).ok()) std::abort();
    picture->Update(*playback, positions, normals);
  }
};

Viewer& Human() {
  static Viewer* viewer = [] {
    auto* v = new Viewer;
    const std::string path = std::string(WIRERIG_SAMPLES_DIR) + "/human/human_wave.scene.json";
    Result<BuiltScene> built = LoadAndBuildScene(path);
    if (!built) {
      std::cerr << built.error() << "\n";
      std::exit(1);
    }
    v->scene = std::move(built).value();
    v->playback = std::make_unique<Playback>(
        Playback::Make(v->scene.model, v->scene.clips.front(), v->scene.description.playback)
            .value());
    v->picture = std::make_unique<SceneFrame>(v->scene);
    v->positions.resize(v->scene.model.vertices.size());
    v->normals.resize(v->positions.size());
    return v;
  }();
  return *viewer;
}

void BM_FrameEvaluation(benchmark::State& state) {
  Viewer& viewer = Human();
  for (auto _ : state) viewer.Step();
  state.counters["vertices"] = double(viewer.positions.size());
}
BENCHMARK(BM_FrameEvaluation)->Unit(benchmark::kMillisecond);

void BM_FrameEvaluationAndUpload(benchmark::State& state) {
  Viewer& viewer = Human();
  Result<std::unique_ptr<HeadlessRenderer>> renderer = HeadlessRenderer::Create(1);
  if (!renderer) {
    state.SkipWithError(renderer.error().c_str());
    return;
  }
  const Size size{960, 540};
  const Camera camera = viewer.picture->InitialCamera(size);
  RenderOptions options;
  options.shadow_map_size = 1024;
  double upload_ms = 0.0, evaluation_ms = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    viewer.Step();
    evaluation_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    renderer.value()->RenderAndFinish(viewer.picture->frame(), camera, size, options);
    upload_ms += renderer.value()->renderer().stats().upload_ms;
  }
  // The measure: evaluation plus upload, per frame (ms, wall time of the calling thread).
  const double frames = double(state.iterations());
  state.counters["evaluation_ms"] = evaluation_ms / frames;
  state.counters["upload_ms"] = upload_ms / frames;
  state.counters["evaluation_plus_upload_ms"] = (evaluation_ms + upload_ms) / frames;
}
BENCHMARK(BM_FrameEvaluationAndUpload)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
