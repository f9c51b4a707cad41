// The paper's Table 1 analogue: generate 103 profile curves with 20, 50 and 100 points each
// on cow.off (parts from its curve skeleton, profiles shared out by central-curve length), and
// the same on a 100k-triangle mesh (a procedural capsule). BVHs are built beforehand; their
// build time is reported apart, by bvh_bench. Targets: under 1 ms for 103 x 100 on cow.off.
// BM_*Batch: every part's profiles in one batch call, on 1 or 2 threads (wall time).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/curve_skeleton.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/part_assignment.h"
#include "wirerig/rig/profile_curves.h"
#include "wirerig/rig/triangle_bvh.h"
#include "wirerig/runtime/parallel.h"

#ifndef WIRERIG_ASSET_DIR
#error "the benchmarks need WIRERIG_ASSET_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {

constexpr int kProfiles = 103;

// Everything profile generation needs, prepared once.
struct Scene {
  Mesh mesh;
  TriangleBvh mesh_bvh;
  std::vector<TriangleBvh> part_bvhs;
  std::vector<Curve> curves;
  std::vector<int> counts;  // profiles per part, summing to kProfiles
  PartAssignment assignment;
};

double PolylineLength(const std::vector<Vec3>& points) {
  double length = 0.0;
  for (std::size_t k = 1; k < points.size(); ++k) length += (points[k] - points[k - 1]).norm();
  return length;
}

void Prepare(Scene& scene, const RigDescription& description) {
  scene.mesh_bvh = TriangleBvh::Build(scene.mesh.welded_positions, scene.mesh.welded_triangles);
  const std::vector<bool> passive(scene.mesh.welded_triangles.size(), false);
  scene.assignment = AssignParts(scene.mesh, description, scene.mesh_bvh, passive).value();
  double total = 0.0;
  for (const PartDescription& part : description.parts) total += PolylineLength(part.central_curve);
  int assigned = 0;
  for (std::size_t i = 0; i < description.parts.size(); ++i) {
    const PartDescription& part = description.parts[i];
    Curve curve;
    Curve::Build(
        part.central_curve, false,
        part.central_curve.size() >= 3 ? CurveInterpolation::kCubic : CurveInterpolation::kLinear,
        &curve);
    scene.curves.push_back(curve);
    const int count =
        i + 1 == description.parts.size()
            ? kProfiles - assigned
            : std::max(2, int(std::lround(kProfiles * PolylineLength(part.central_curve) / total)));
    scene.counts.push_back(count);
    assigned += count;
  }
  for (std::size_t i = 0; i < description.parts.size(); ++i)
    scene.part_bvhs.push_back(TriangleBvh::Build(scene.mesh.welded_positions,
                                                 scene.mesh.welded_triangles,
                                                 scene.assignment.part_triangles[i]));
}

const Scene& Cow() {
  static const Scene scene = [] {
    Scene s;
    s.mesh = ImportMesh(std::string(WIRERIG_ASSET_DIR) + "/cow.off").value().mesh;
    const CurveSkeleton skeleton = ExtractCurveSkeleton(s.mesh).value();
    Prepare(s, DescribeFromCurveSkeleton(s.mesh, skeleton).value());
    return s;
  }();
  return scene;
}

const Scene& Capsule100k() {
  static const Scene scene = [] {
    Scene s;
    s.mesh = MakeCapsule(0.1, 1.0, 256, 180, 8);  // ~100k triangles
    RigDescription description;
    description.parts.push_back(
        {"body", {Vec3(0, 0, 0), Vec3(0, 1, 0)}, kProfiles, 20, "", {}, {}});
    Prepare(s, description);
    return s;
  }();
  return scene;
}

// Generates all 103 profiles. `full`: the pipeline's defaults (2 re-centring passes, other-part
// and orientation diagnostics); otherwise the paper's operation alone (one ray per point).
void Run(benchmark::State& state, const Scene& scene, bool full) {
  const int points = int(state.range(0));
  std::size_t rays = 0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < scene.curves.size(); ++i) {
      ProfileRequest request;
      request.central_curve = &scene.curves[i];
      request.profile_count = scene.counts[i];
      request.points_per_profile = points;
      request.part_bvh = &scene.part_bvhs[i];
      if (full) {
        request.mesh_bvh = &scene.mesh_bvh;
        request.triangle_part = scene.assignment.triangle_part;
        request.part = int(i);
        request.positions = scene.mesh.welded_positions;
        request.triangles = scene.mesh.welded_triangles;
      } else {
        request.recentre_passes = 0;
      }
      const ProfileSet set = GenerateProfiles(request);
      rays += set.diagnostics.rays;
      benchmark::DoNotOptimize(set.profiles.data());
    }
  }
  state.counters["triangles"] = double(scene.mesh.welded_triangles.size());
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}

// One pool per thread count, made once per process (its threads are running and warm when a
// repetition starts, as in an engine that keeps its pool).
const ThreadPool& Pool(std::size_t threads) {
  static std::vector<std::unique_ptr<ThreadPool>> pools(8);
  std::unique_ptr<ThreadPool>& pool = pools.at(threads);
  if (!pool) pool = std::make_unique<ThreadPool>(threads);
  return *pool;
}

// All parts at once through the batch GenerateProfiles, on state.range(1) threads (a ThreadPool
// made beforehand; 1: no pool). Wall time is the figure when threaded.
void RunBatch(benchmark::State& state, const Scene& scene, bool full) {
  const int points = int(state.range(0));
  const auto threads = static_cast<std::size_t>(state.range(1));
  const ThreadPool* pool = threads > 1 ? &Pool(threads) : nullptr;
  std::vector<ProfileRequest> requests(scene.curves.size());
  for (std::size_t i = 0; i < scene.curves.size(); ++i) {
    ProfileRequest& request = requests[i];
    request.central_curve = &scene.curves[i];
    request.profile_count = scene.counts[i];
    request.points_per_profile = points;
    request.part_bvh = &scene.part_bvhs[i];
    if (full) {
      request.mesh_bvh = &scene.mesh_bvh;
      request.triangle_part = scene.assignment.triangle_part;
      request.part = int(i);
      request.positions = scene.mesh.welded_positions;
      request.triangles = scene.mesh.welded_triangles;
    } else {
      request.recentre_passes = 0;
    }
  }
  std::size_t rays = 0;
  for (auto _ : state) {
    const std::vector<ProfileSet> sets = GenerateProfiles(requests, pool);
    for (const ProfileSet& set : sets) rays += set.diagnostics.rays;
    benchmark::DoNotOptimize(sets.data());
  }
  state.counters["triangles"] = double(scene.mesh.welded_triangles.size());
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}

void BM_CowProfiles(benchmark::State& state) { Run(state, Cow(), false); }
void BM_CowProfilesBatch(benchmark::State& state) { RunBatch(state, Cow(), false); }
void BM_CowProfilesFullPipelineBatch(benchmark::State& state) { RunBatch(state, Cow(), true); }
void BM_CowProfilesFullPipeline(benchmark::State& state) { Run(state, Cow(), true); }
void BM_Capsule100kProfiles(benchmark::State& state) { Run(state, Capsule100k(), false); }
void BM_Capsule100kProfilesFullPipeline(benchmark::State& state) {
  Run(state, Capsule100k(), true);
}

BENCHMARK(BM_CowProfiles)->Arg(20)->Arg(50)->Arg(100)->Unit(benchmark::kMicrosecond);
// The fastest repetition too: on a loaded machine the minimum is the figure closest to an idle
// one (run with many repetitions).
double Minimum(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

BENCHMARK(BM_CowProfilesBatch)
    ->ArgsProduct({{100}, {1, 2}})
    ->UseRealTime()
    ->ComputeStatistics("min", Minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CowProfilesFullPipelineBatch)
    ->ArgsProduct({{100}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CowProfilesFullPipeline)->Arg(20)->Arg(50)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Capsule100kProfiles)->Arg(20)->Arg(50)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Capsule100kProfilesFullPipeline)
    ->Arg(20)
    ->Arg(50)
    ->Arg(100)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
