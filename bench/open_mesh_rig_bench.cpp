// Automatic rigging of an open 100k-triangle mesh, stage by stage (issue target: under 10 s on
// one core, wrap and skeleton included): human.zae (open: its eyes are separate open pieces)
// subdivided once to 115k triangles. Stages: the watertight check and alpha wrap, the curve
// skeleton of the wrap, the parts described from it, the rig built on the mesh (profiles traced
// with the wrap standing in for holes); then the whole automatic path at once.
#include <benchmark/benchmark.h>

#include <string>

#include "wirerig/rig/automatic_description.h"
#include "wirerig/rig/curve_skeleton.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/mesh_subdivision.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/watertight_proxy.h"

#ifndef WIRERIG_ASSET_DIR
#error "the benchmarks need WIRERIG_ASSET_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {

const Mesh& OpenMesh() {
  static const Mesh mesh = [] {
    Result<ImportedMesh> imported =
        ImportMesh(std::string(WIRERIG_ASSET_DIR) + "/assimp/Collada/human.zae");
    if (!imported) return Mesh{};
    return SubdivideMidpoint(imported.value().mesh, 1);
  }();
  return mesh;
}

// The stages' inputs, made once.
struct Stages {
  WatertightProxy wrap;
  CurveSkeleton skeleton;
  RigDescription description;
};
const Stages& Made() {
  static const Stages stages = [] {
    Stages s;
    s.wrap = WrapWatertight(OpenMesh()).value();
    s.skeleton = ExtractCurveSkeleton(s.wrap.mesh).value();
    s.description = DescribeFromCurveSkeleton(s.wrap.mesh, s.skeleton).value();
    return s;
  }();
  return stages;
}

bool Ready(benchmark::State& state) {
  if (OpenMesh().welded_triangles.empty()) {
    state.SkipWithError("human.zae missing (run scripts/setup.sh)");
    return false;
  }
  state.counters["triangles"] = double(OpenMesh().welded_triangles.size());
  return true;
}

void BM_WatertightCheckAndWrap(benchmark::State& state) {
  if (!Ready(state)) return;
  for (auto _ : state) {
    benchmark::DoNotOptimize(WatertightProblem(OpenMesh()));
    benchmark::DoNotOptimize(WrapWatertight(OpenMesh()));
  }
}

void BM_CurveSkeletonOfTheWrap(benchmark::State& state) {
  if (!Ready(state)) return;
  const Mesh& wrap = Made().wrap.mesh;
  state.counters["wrap_triangles"] = double(wrap.welded_triangles.size());
  for (auto _ : state) benchmark::DoNotOptimize(ExtractCurveSkeleton(wrap));
}

void BM_DescribeParts(benchmark::State& state) {
  if (!Ready(state)) return;
  for (auto _ : state)
    benchmark::DoNotOptimize(DescribeFromCurveSkeleton(Made().wrap.mesh, Made().skeleton));
}

void BM_BuildRigOnTheMesh(benchmark::State& state) {
  if (!Ready(state)) return;
  RigBuildOptions options;
  options.wrap = &Made().wrap.mesh;
  options.drop_parts_without_profiles = true;
  for (auto _ : state)
    benchmark::DoNotOptimize(BuildRig(OpenMesh(), Made().description, "human x4", options));
}

void BM_WholeAutomaticRig(benchmark::State& state) {
  if (!Ready(state)) return;
  for (auto _ : state) {
    Result<AutomaticDescription> automatic = DescribeAutomatically(OpenMesh());
    RigBuildOptions options;
    options.wrap = automatic && automatic.value().wrap ? &*automatic.value().wrap : nullptr;
    options.drop_parts_without_profiles = true;
    if (automatic)
      benchmark::DoNotOptimize(
          BuildRig(OpenMesh(), automatic.value().description, "human x4", options));
  }
}

BENCHMARK(BM_WatertightCheckAndWrap)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_CurveSkeletonOfTheWrap)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_DescribeParts)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_BuildRigOnTheMesh)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_WholeAutomaticRig)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
