// Renderer cost per frame, headless (EGL on whatever Mesa driver is present; llvmpipe on a
// machine without a GPU): upload of a deformed 20k-triangle mesh, the shadow and main passes,
// and glFinish, at 1280x720. llvmpipe rasterises on its own threads, so wall time ("Time") is
// the cost a viewer sees; "CPU" counts the calling thread only.
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "wirerig/procedural/shapes.h"
#include "wirerig/viewer/headless.h"

namespace wirerig {
namespace {

struct Scene {
  std::vector<Vec3f> rest, positions, normals;
  std::vector<Triangle> triangles;
  std::vector<Vec3f> spine;
  std::vector<std::vector<Vec3f>> rings;
  std::vector<RenderPolyline> lines;
  RenderMesh mesh;
  RenderFrame frame;
  Camera camera;
};

// A capsule of about 20k triangles with a spine and 16 profile rings.
std::unique_ptr<Scene> MakeScene() {
  auto s = std::make_unique<Scene>();
  const Mesh capsule = MakeCapsule(0.1, 1.0, 96, 96, 6);
  for (const Vec3& p : capsule.positions) s->rest.push_back(p.cast<float>());
  s->triangles = capsule.triangles;
  s->positions = s->rest;
  s->normals.resize(s->rest.size());
  ComputeVertexNormals(s->positions, s->triangles, s->normals);
  for (int i = 0; i <= 64; ++i) s->spine.emplace_back(0.0f, float(i) / 64.0f, 0.0f);
  s->rings.assign(16, {});
  for (int r = 0; r < 16; ++r) {
    for (int k = 0; k < 48; ++k) {
      const float a = 6.2831853f * float(k) / 48.0f;
      s->rings[r].emplace_back(0.105f * std::cos(a), (float(r) + 0.5f) / 16.0f,
                               0.105f * std::sin(a));
    }
  }
  s->lines.resize(17);
  s->lines[0].points = s->spine;
  s->lines[0].kind = WireKind::kSpine;
  for (int r = 0; r < 16; ++r) {
    s->lines[r + 1].points = s->rings[r];
    s->lines[r + 1].closed = true;
  }
  s->mesh.positions = s->positions;
  s->mesh.normals = s->normals;
  s->mesh.triangles = s->triangles;
  s->mesh.cull_back_faces = true;  // closed and outward-oriented
  s->frame.meshes = {&s->mesh, 1};
  s->frame.polylines = s->lines;
  FrameCamera(s->camera, ComputeFrameBounds(s->frame), 1280.0f / 720.0f);
  return s;
}

void BM_RenderFrame(benchmark::State& state) {
  const int samples = static_cast<int>(state.range(0));
  RenderOptions options;
  options.shadows = state.range(1) != 0;
  options.show_wires = state.range(2) != 0;
  options.shadow_map_size = static_cast<int>(state.range(3));
  Result<std::unique_ptr<HeadlessRenderer>> headless = HeadlessRenderer::Create(samples);
  if (!headless) {
    state.SkipWithError(headless.error().c_str());
    return;
  }
  std::unique_ptr<Scene> scene = MakeScene();
  const Size size{1280, 720};
  // Warm-up: llvmpipe compiles shader variants at their first draw.
  headless.value()->RenderAndFinish(scene->frame, scene->camera, size, options);
  int frame = 0;
  for (auto _ : state) {
    // A cheap sway so every frame uploads different positions.
    const float sway = 0.02f * std::sin(0.1f * float(frame++));
    for (std::size_t i = 0; i < scene->rest.size(); ++i) {
      const Vec3f& p = scene->rest[i];
      scene->positions[i] = Vec3f(p.x() + sway * p.y() * p.y(), p.y(), p.z());
    }
    headless.value()->RenderAndFinish(scene->frame, scene->camera, size, options);
  }
  state.counters["triangles"] = double(scene->triangles.size());
  state.counters["fps"] =
      benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.SetLabel(headless.value()->context().gl_renderer());
}
// Args: MSAA samples, shadows, wires, shadow-map texels per side.
BENCHMARK(BM_RenderFrame)
    ->ArgNames({"samples", "shadows", "wires", "shadow_map"})
    ->Args({4, 1, 1, 2048})
    ->Args({1, 1, 1, 2048})
    ->Args({1, 1, 1, 1024})
    ->Args({1, 1, 0, 1024})
    ->Args({1, 0, 0, 1024})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
