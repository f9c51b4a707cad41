// The chest sample's speed claim (issue 7, paper Fig. 3; PHYSICS.md section 5, "Timing"):
// a clamped-plate finite-difference solve (assembly + sparse LDLT, n = 48 and 96 intervals per
// side) against one evaluation of the 5 interior closed-form wires of the 7-wire model at the
// plate's n + 1 nodes each, with xi precomputed. The wire benchmark reports "plate/wires": the
// median of 3 plate solves (timed before the loop) over its own time per iteration, both
// wall-clock.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "plate_reference.h"
#include "wire_patch.h"

namespace wirerig::chest {
namespace {

constexpr int kWires = 7;

PlateProblem UnitSquare(int n) {
  PlateProblem problem;
  problem.intervals = n;
  return problem;
}

void BM_PlateSolve(benchmark::State& state) {
  const PlateProblem problem = UnitSquare(static_cast<int>(state.range(0)));
  PlateSolution plate;
  for (auto _ : state) {
    if (Status s = SolveClampedPlate(problem, &plate); !s) state.SkipWithError("plate solve");
    benchmark::DoNotOptimize(plate.deflection.data());
  }
  state.counters["unknowns"] = double((problem.intervals - 1) * (problem.intervals - 1));
}
BENCHMARK(BM_PlateSolve)->Arg(48)->Arg(96)->Unit(benchmark::kMillisecond);

void BM_WireEvaluation(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  PlateSolution plate;
  std::vector<double> solve_seconds;
  for (int r = 0; r < 3; ++r) {
    const auto start = std::chrono::steady_clock::now();
    if (Status s = SolveClampedPlate(UnitSquare(n), &plate); !s) {
      state.SkipWithError("plate solve");
      return;
    }
    solve_seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(solve_seconds.begin(), solve_seconds.end());
  WirePatch patch;
  if (Status s = FitWirePatch(plate, kWires, XiFit::kPerWire, &patch); !s) {
    state.SkipWithError("fit");
    return;
  }
  const std::size_t count = static_cast<std::size_t>(n + 1);
  std::vector<double> samples(count);
  for (std::size_t k = 0; k < count; ++k) samples[k] = double(k) / n;
  std::vector<Vec3> scratch(count);
  std::vector<double> deflection(kWires * count);
  WirePatchJob job;
  job.patch = &patch;
  job.samples = samples;
  job.scratch = scratch;
  job.deflection = deflection;
  const auto loop_start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    if (Status s = job.Run(); !s) state.SkipWithError("wires");
    benchmark::DoNotOptimize(deflection.data());
    benchmark::ClobberMemory();
  }
  const double wire_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count() /
      double(std::max<benchmark::IterationCount>(state.iterations(), 1));
  // Both wall-clock: the median plate solve over the wire evaluation's time per iteration.
  if (wire_seconds > 0.0) state.counters["plate/wires"] = solve_seconds[1] / wire_seconds;
  state.counters["samples"] = double(5 * count);
}
BENCHMARK(BM_WireEvaluation)->Arg(48)->Arg(96)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace wirerig::chest

BENCHMARK_MAIN();
