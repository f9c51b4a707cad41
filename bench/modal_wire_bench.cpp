// Cost of modal wire dynamics (modal_wire.h) against the static closed form alone (BendingJob)
// at the same samples: 100 cantilever wires (tip force and 3 point loads each, different per
// wire), 32 samples each, displacement and slope (or displacement only). Per wire and frame:
//   static          BendingJob::Run
//   modal           ModalWireStepJob::Run (8 modes, precomputed step table and mode values at
//                   the loads) and ModalWireEvaluateJob::Run (precomputed mode tables)
//   modal_untabled  the same without the tables (modes evaluated at the samples each frame)
//   modal_support   modal plus a support acceleration (an inertial line load)
//   modal_step_only, modal_evaluate_only   the two halves of "modal"
// Report the medians of repetitions and their ratio to "static":
//   wirerig_modal_wire_bench --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <random>
#include <vector>

#include "wirerig/runtime/bending_job.h"
#include "wirerig/runtime/modal_wire.h"

namespace wirerig {
namespace {

constexpr int kWires = 100;
constexpr int kSamples = 32;
constexpr int kLoads = 3;
constexpr int kModes = 8;
constexpr double kDt = 1.0 / 60.0;

struct Wires {
  std::vector<PointLoad> loads;  // kLoads per wire
  std::vector<Vec3> tips;
  std::vector<double> samples;
  std::vector<Vec3> displacement, slope;
  ModalWireModel model;
  std::vector<ModalWireState> states;
  ModalStepTable table;
  std::vector<double> values, slopes;
  std::vector<double> load_modes;  // kLoads x kModes per wire

  Wires()
      : displacement(std::size_t(kWires) * kSamples),
        slope(std::size_t(kWires) * kSamples),
        states(kWires),
        values(std::size_t(kSamples) * kModes),
        slopes(std::size_t(kSamples) * kModes),
        load_modes(std::size_t(kWires) * kLoads * kModes) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> at(0.05, 0.95), force(-5.0, 5.0);
    for (int i = 0; i < kWires * kLoads; ++i)
      loads.push_back({at(rng), Vec3(force(rng), force(rng), force(rng))});
    for (int i = 0; i < kWires; ++i) tips.push_back(Vec3(force(rng), force(rng), 0.0));
    for (int i = 0; i < kSamples; ++i) samples.push_back(i / (kSamples - 1.0));
    // A soft-tissue tentacle segment: L = 0.3 m, EI = 0.5 N m^2, rho A = 1 kg/m, zeta = 0.1.
    if (!BuildModalBasis(BoundaryCondition::kCantileverFree, kModes, &model.basis)) std::abort();
    model.length = 0.3;
    model.bending_stiffness = 0.5;
    model.mass_per_length = 1.0;
    model.damping_ratio = 0.1;
    for (ModalWireState& s : states)
      if (!InitializeModalWireAtRest(model, &s)) std::abort();
    if (!PrecomputeModalStep(model, kDt, &table)) std::abort();
    if (!TabulateModes(model.basis, samples, values, slopes)) std::abort();
    for (int w = 0; w < kWires; ++w) {
      double positions[kLoads];
      for (int j = 0; j < kLoads; ++j) positions[j] = loads[std::size_t(w) * kLoads + j].at;
      if (!TabulateModes(model.basis, positions, LoadModes(w), {})) std::abort();
    }
  }
  std::span<const PointLoad> Loads(int w) const {
    return std::span<const PointLoad>(loads).subspan(std::size_t(w) * kLoads, kLoads);
  }
  std::span<double> LoadModes(int w) {
    return std::span<double>(load_modes).subspan(std::size_t(w) * kLoads * kModes, kLoads * kModes);
  }
  std::span<Vec3> Out(std::vector<Vec3>& v, int w) {
    return std::span<Vec3>(v).subspan(std::size_t(w) * kSamples, kSamples);
  }
};

void Report(benchmark::State& state) {
  // Seconds per wire and frame, printed with an SI prefix (e.g. "450n" = 450 ns).
  state.counters["time/wire"] =
      benchmark::Counter(double(state.iterations()) * kWires,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Static(benchmark::State& state, bool slope) {
  Wires wires;
  BendingJob job;
  job.boundary = BoundaryCondition::kCantileverFree;
  job.length = wires.model.length;
  job.bending_stiffness = wires.model.bending_stiffness;
  job.samples = wires.samples;
  for (auto _ : state) {
    for (int w = 0; w < kWires; ++w) {
      job.point_loads = wires.Loads(w);
      job.tip_force = wires.tips[w];
      job.displacement = wires.Out(wires.displacement, w);
      if (slope) job.slope = wires.Out(wires.slope, w);
      if (!job.Run()) state.SkipWithError("job refused");
    }
    benchmark::DoNotOptimize(wires.displacement.data());
    benchmark::ClobberMemory();
  }
  Report(state);
}
BENCHMARK_CAPTURE(BM_Static, slope, true);
BENCHMARK_CAPTURE(BM_Static, displacement_only, false);

enum Part { kStepAndEvaluate, kStepOnly, kEvaluateOnly };

void BM_Modal(benchmark::State& state, bool tables, bool support, Part part = kStepAndEvaluate,
              bool slope = true) {
  Wires wires;
  ModalWireStepJob step;
  step.model = &wires.model;
  step.dt = kDt;
  step.step_table = tables ? &wires.table : nullptr;
  ModalWireEvaluateJob eval;
  eval.model = &wires.model;
  eval.samples = wires.samples;
  if (tables) {
    eval.mode_values = wires.values;
    if (slope) eval.mode_slopes = wires.slopes;
  }
  for (auto _ : state) {
    for (int w = 0; w < kWires; ++w) {
      ModalWireLoads loads;
      loads.point_loads = wires.Loads(w);
      loads.tip_force = wires.tips[w];
      if (support) loads.support_acceleration = Vec3(0.0, -9.81, 3.0);
      step.loads = loads;
      step.state = &wires.states[w];
      if (tables) step.point_load_modes = wires.LoadModes(w);
      if (part != kEvaluateOnly && !step.Run()) state.SkipWithError("step refused");
      eval.loads = loads;
      eval.state = &wires.states[w];
      eval.displacement = wires.Out(wires.displacement, w);
      if (slope) eval.slope = wires.Out(wires.slope, w);
      if (part != kStepOnly && !eval.Run()) state.SkipWithError("evaluation refused");
    }
    benchmark::DoNotOptimize(wires.displacement.data());
    benchmark::ClobberMemory();
  }
  Report(state);
}
BENCHMARK_CAPTURE(BM_Modal, modal, true, false);
BENCHMARK_CAPTURE(BM_Modal, modal_displacement_only, true, false, kStepAndEvaluate, false);
BENCHMARK_CAPTURE(BM_Modal, modal_untabled, false, false);
BENCHMARK_CAPTURE(BM_Modal, modal_support, true, true);
BENCHMARK_CAPTURE(BM_Modal, modal_step_only, true, false, kStepOnly);
BENCHMARK_CAPTURE(BM_Modal, modal_evaluate_only, true, false, kEvaluateOnly);

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
