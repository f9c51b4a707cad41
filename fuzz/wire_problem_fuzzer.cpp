// libFuzzer target: wire problems (`wirerig wire`, docs/wire-format.md) through the stream
// loader; problems small enough to solve quickly are solved, warned about and written back.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzz_support.h"
#include "wirerig/wire_problem/wire_problem.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  const wirerig::Result<wirerig::WireProblem> problem = wirerig::LoadWireProblem(in, "fuzz.json");
  if (!problem) {
    FUZZ_CHECK(problem.error().rfind("fuzz.json: ", 0) == 0,
               "error does not name the source: " + problem.error());
    return 0;
  }
  // Solving is bounded at kMaxOperations (seconds); the fuzzer solves the small ones only.
  if (wirerig::EstimateWireOperations(problem.value()) > 2e5) return 0;
  const wirerig::Result<wirerig::WireSolution> solution =
      wirerig::SolveWireProblem(problem.value());
  if (!solution) return 0;
  const wirerig::WireSolution& s = solution.value();
  FUZZ_CHECK(s.v.size() == static_cast<std::size_t>(problem.value().samples),
             "one solution sample per requested sample");
  (void)wirerig::WireSolutionWarnings(problem.value(), s);
  (void)wirerig::WireSolutionToJson(s).dump();
  return 0;
}
