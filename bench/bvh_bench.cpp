// TriangleBvh on procedural tori of 10k, 100k and 1M triangles, one thread: build time
// (target: under 50 ms for 100k triangles), ray casting throughput from random points inside
// the tube in random directions ("rays/s"; every ray hits), and closest-point queries from
// random points within twice the tube radius of the core circle ("queries/s"; points near the
// core are nearly equidistant from a whole ring of triangles, the hard case for branch and
// bound).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/triangle_bvh.h"

namespace wirerig {
namespace {

constexpr double kMajor = 1.0, kMinor = 0.35;
constexpr int kQueries = 1 << 14;

// A torus of exactly 2 * rings * tube = `triangles` triangles for 10k (100 x 50),
// 100k (250 x 200) and 1M (1000 x 500); about that many otherwise.
Mesh TorusOf(std::int64_t triangles) {
  const int tube = triangles == 10'000    ? 50
                   : triangles == 100'000 ? 200
                   : triangles == 1'000'000
                       ? 500
                       : static_cast<int>(std::lround(std::sqrt(double(triangles) / 4.0)));
  return MakeTorus(kMajor, kMinor, static_cast<int>(triangles / (2 * tube)), tube);
}

// Random points within `max_offset` of the core circle (inside the tube when < kMinor).
std::vector<Vec3> PointsAroundCore(int count, double max_offset, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi), unit(0.0, 1.0);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    const double phi = angle(rng), theta = angle(rng), s = max_offset * std::sqrt(unit(rng));
    const double rho = kMajor + s * std::cos(theta);
    points.emplace_back(rho * std::cos(phi), s * std::sin(theta), rho * std::sin(phi));
  }
  return points;
}

std::vector<Vec3> RandomDirections(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<Vec3> directions;
  while (static_cast<int>(directions.size()) < count) {
    const Vec3 d(normal(rng), normal(rng), normal(rng));
    if (d.norm() > 1e-3) directions.push_back(d.normalized());
  }
  return directions;
}

void BM_Build(benchmark::State& state) {
  const Mesh torus = TorusOf(state.range(0));
  for (auto _ : state) {
    TriangleBvh bvh = TriangleBvh::Build(torus.welded_positions, torus.welded_triangles);
    benchmark::DoNotOptimize(bvh);
  }
  state.counters["triangles"] = double(torus.welded_triangles.size());
  state.counters["tris/s"] =
      benchmark::Counter(double(state.iterations()) * double(torus.welded_triangles.size()),
                         benchmark::Counter::kIsRate);
}

void BM_Raycast(benchmark::State& state) {
  const Mesh torus = TorusOf(state.range(0));
  const TriangleBvh bvh = TriangleBvh::Build(torus.welded_positions, torus.welded_triangles);
  const std::vector<Vec3> origins = PointsAroundCore(kQueries, 0.9 * kMinor, 1);
  const std::vector<Vec3> directions = RandomDirections(kQueries, 2);
  std::size_t misses = 0;
  for (auto _ : state) {
    double sum = 0.0;
    for (int i = 0; i < kQueries; ++i) {
      const auto hit =
          bvh.Raycast(origins[i], directions[i], 0.0, std::numeric_limits<double>::max());
      if (hit) {
        sum += hit->t;
      } else {
        ++misses;
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  if (misses > 0) state.SkipWithError("a ray from inside the torus missed");
  state.counters["rays/s"] =
      benchmark::Counter(double(state.iterations()) * kQueries, benchmark::Counter::kIsRate);
}

void BM_Closest(benchmark::State& state) {
  const Mesh torus = TorusOf(state.range(0));
  const TriangleBvh bvh = TriangleBvh::Build(torus.welded_positions, torus.welded_triangles);
  const std::vector<Vec3> points = PointsAroundCore(kQueries, 2.0 * kMinor, 3);
  for (auto _ : state) {
    double sum = 0.0;
    for (const Vec3& p : points) sum += bvh.Closest(p)->distance;
    benchmark::DoNotOptimize(sum);
  }
  state.counters["queries/s"] =
      benchmark::Counter(double(state.iterations()) * kQueries, benchmark::Counter::kIsRate);
}

BENCHMARK(BM_Build)->Arg(10'000)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Raycast)->Arg(10'000)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Closest)->Arg(10'000)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace wirerig

BENCHMARK_MAIN();
