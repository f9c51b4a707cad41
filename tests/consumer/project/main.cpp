// A downstream program built against the installed wirerig package: solves a simply
// supported wire with a centre load and checks F L^3 / (48 EI), and samples a keyed track.
#include <cmath>
#include <cstdio>

#include <wirerig/anim/track.h>
#include <wirerig/runtime/bending_job.h>
#include <wirerig/wire_problem/wire_problem.h>
#include <nlohmann/json.hpp>

int main() {
  const wirerig::PointLoad load{0.5, wirerig::Vec3(0.0, -10.0, 0.0)};
  const double v = 0.5;
  wirerig::Vec3 x;
  wirerig::BendingJob job;
  job.length = 2.0;
  job.bending_stiffness = 20.0;
  job.point_loads = {&load, 1};
  job.samples = {&v, 1};
  job.displacement = {&x, 1};
  if (!job.Run()) return 1;
  const double expected = -10.0 * 8.0 / (48.0 * 20.0);
  std::printf("centre deflection %.9f m, expected %.9f m\n", x.y(), expected);
  const auto problem = wirerig::ParseWireProblem(nlohmann::json::parse(
      R"({"length": 1, "material": "steel", "section": {"A": 1e-4, "I": 1e-8},
          "axial": {"point_loads": [{"at": 1, "force": 1}]}})"));
  if (!problem) return 3;
  // wirerig::anim: a keyed track, halfway between two linear keys.
  wirerig::RawScalarTrack raw;
  raw.keys = {{0.0, 1.0, wirerig::Interpolation::kLinear},
              {2.0, 3.0, wirerig::Interpolation::kLinear}};
  const auto track = wirerig::BuildTrack(raw);
  if (!track || std::abs(track.value().Sample(1.0) - 2.0) > 1e-15) return 4;
  return std::abs(x.y() - expected) < 1e-12 ? 0 : 2;
}
