// The paper's Table 2 analogue: deform 100, 1,000 and 10,000 profile wires (clamped, 3 point
// loads, 64 samples each) in exact and series (N = 20) modes, one thread. Reports samples per
// second ("samples/s") and time per wire ("time/wire"). Target: >= 1.5e8 samples/s, exact mode
// (docs/benchmarks.md).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "wirerig/runtime/bending_job.h"

namespace wirerig {
namespace {

constexpr int kSamplesPerWire = 64;
constexpr int kLoadsPerWire = 3;

struct ProfileWires {
  std::vector<PointLoad> loads;  // kLoadsPerWire per wire
  std::vector<double> samples;   // shared by every wire
  std::vector<Vec3> displacement;

  explicit ProfileWires(int count) : displacement(std::size_t(count) * kSamplesPerWire) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> at(0.05, 0.95), force(-5.0, 5.0);
    for (int i = 0; i < count * kLoadsPerWire; ++i)
      loads.push_back({at(rng), Vec3(force(rng), force(rng), force(rng))});
    for (int i = 0; i < kSamplesPerWire; ++i) samples.push_back(i / (kSamplesPerWire - 1.0));
  }
};

void BM_ProfileWires(benchmark::State& state, BendingMode mode) {
  const int count = static_cast<int>(state.range(0));
  ProfileWires wires(count);
  BendingJob job;
  job.boundary = BoundaryCondition::kClamped;
  job.mode = mode;
  job.series_terms = 20;
  job.length = 0.3;
  job.bending_stiffness = 0.5;
  job.samples = wires.samples;
  for (auto _ : state) {
    for (int w = 0; w < count; ++w) {
      job.point_loads =
          std::span<const PointLoad>(wires.loads).subspan(w * kLoadsPerWire, kLoadsPerWire);
      job.displacement = std::span<Vec3>(wires.displacement)
                             .subspan(std::size_t(w) * kSamplesPerWire, kSamplesPerWire);
      if (!job.Run()) state.SkipWithError("job refused");
    }
    benchmark::DoNotOptimize(wires.displacement.data());
    benchmark::ClobberMemory();
  }
  const double samples = double(state.iterations()) * count * kSamplesPerWire;
  state.counters["samples/s"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
  // Seconds per wire, printed with an SI prefix (e.g. "450n" = 450 ns).
  state.counters["time/wire"] =
      benchmark::Counter(double(state.iterations()) * count,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

BENCHMARK_CAPTURE(BM_ProfileWires, exact, BendingMode::kExact)->Arg(100)->Arg(1000)->Arg(10000);
BENCHMARK_CAPTURE(BM_ProfileWires, series20, BendingMode::kSeries)->Arg(100)->Arg(1000)->Arg(10000);

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
