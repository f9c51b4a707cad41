// Loading the human's built rig asset (.wrig): parsing and validating its bytes (what an engine
// pays at load; target under 5 ms), the evaluation plan made once per rig, and a further
// thread's context from that plan.
//   build/bench/wirerig_rig_asset_bench --benchmark_repetitions=9
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>

#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_description.h"
#include "wirerig/rig/rig_model_builder.h"
#include "wirerig/runtime/rig_asset.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace {
using namespace wirerig;

template <class T>
T Check(Result<T> result, const char* what) {
  if (!result) {
    std::fprintf(stderr, "%s: %s\n", what, result.error().c_str());
    std::exit(1);
  }
  return std::move(result).value();
}

const std::vector<std::uint8_t>& HumanBytes() {
  static const std::vector<std::uint8_t> bytes = [] {
    const RigDescription description =
        Check(LoadRigDescription(std::string(WIRERIG_SAMPLES_DIR) + "/rigs/human.description.json"),
              "human.description.json");
    const Mesh mesh =
        Check(ImportMesh(description.mesh.string(), description.import), "human.zae").mesh;
    const Rig rig = Check(BuildRig(mesh, description, "human.zae"), "rig").rig;
    RigAsset asset;
    asset.model = Check(BuildRigModel(mesh, rig), "model").model;
    asset.vertex_order = mesh.weld_map;
    return SerializeRigAsset(asset);
  }();
  return bytes;
}

void BM_ParseHumanRigAsset(benchmark::State& state) {
  const std::vector<std::uint8_t>& bytes = HumanBytes();
  for (auto _ : state) {
    RigAsset asset;
    if (!ParseRigAsset(bytes, &asset)) state.SkipWithError("parse failed");
    benchmark::DoNotOptimize(asset.model.vertices.data());
  }
  state.counters["bytes"] = double(bytes.size());
  state.SetBytesProcessed(std::int64_t(state.iterations()) * std::int64_t(bytes.size()));
}
BENCHMARK(BM_ParseHumanRigAsset)->Unit(benchmark::kMillisecond);

void BM_Crc32HumanRigAsset(benchmark::State& state) {
  const std::vector<std::uint8_t>& bytes = HumanBytes();
  for (auto _ : state) benchmark::DoNotOptimize(Crc32(bytes));
  state.SetBytesProcessed(std::int64_t(state.iterations()) * std::int64_t(bytes.size()));
}
BENCHMARK(BM_Crc32HumanRigAsset)->Unit(benchmark::kMillisecond);

// The evaluation plan, made once per rig at load (shared by every thread's context).
void BM_MakeHumanPlan(benchmark::State& state) {
  RigAsset asset;
  if (!ParseRigAsset(HumanBytes(), &asset)) state.SkipWithError("parse failed");
  for (auto _ : state) benchmark::DoNotOptimize(MakeRigEvaluationPlan(asset.model).get());
}
BENCHMARK(BM_MakeHumanPlan)->Unit(benchmark::kMillisecond);

// A further thread's context from the shared plan: per-frame buffers only.
void BM_MakeHumanContext(benchmark::State& state) {
  RigAsset asset;
  if (!ParseRigAsset(HumanBytes(), &asset)) state.SkipWithError("parse failed");
  const auto plan = MakeRigEvaluationPlan(asset.model);
  for (auto _ : state) {
    RigWorkspace workspace = MakeRigWorkspace(asset.model, plan);
    benchmark::DoNotOptimize(workspace.spine_points.data());
  }
}
BENCHMARK(BM_MakeHumanContext)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
