// Loading wire problems: a stream that cannot be read (an ifstream on a directory, whose
// libstdc++ buffer throws) and paths that are not regular files come back as errors naming the
// source, never as exceptions.
#include "wirerig/wire_problem/wire_problem.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "wirerig/io/input_file.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

fs::path ScratchDir() {
  const fs::path dir = fs::path(::testing::TempDir()) / "wirerig_wire_problem_test";
  fs::create_directories(dir);
  return dir;
}

TEST(LoadWireProblem, AStreamOnADirectoryIsAnError) {
  std::ifstream in(ScratchDir(), std::ios::binary);  // opens on Linux; reading throws
  Result<WireProblem> problem(Error{""});
  ASSERT_NO_THROW(problem = LoadWireProblem(in, "dir.json"));
  ASSERT_FALSE(problem.ok());
  EXPECT_EQ(problem.error().rfind("dir.json: cannot read", 0), 0u) << problem.error();
}

TEST(LoadWireProblem, ADirectoryPathIsNamed) {
  const Result<WireProblem> problem = LoadWireProblem(ScratchDir());
  ASSERT_FALSE(problem.ok());
  EXPECT_EQ(problem.error(), ScratchDir().string() + ": is a directory, not a wire problem (JSON)");
}

TEST(LoadWireProblem, AFifoIsRefusedWithoutBlocking) {
  const fs::path path = ScratchDir() / "pipe.json";
  fs::remove(path);
  ASSERT_EQ(mkfifo(path.c_str(), 0600), 0);
  const Result<WireProblem> problem = LoadWireProblem(path);
  fs::remove(path);
  ASSERT_FALSE(problem.ok());
  EXPECT_NE(problem.error().find("pipe.json: is not a regular file"), std::string::npos)
      << problem.error();
}

TEST(LoadWireProblem, AnEndlessStreamIsCutAtTheLimit) {
  // A stream longer than kMaxJsonFileBytes is refused (not parsed, not read to its end).
  std::istringstream in(std::string(kMaxJsonFileBytes + 10, ' '));
  const Result<WireProblem> problem = LoadWireProblem(in, "<stdin>");
  ASSERT_FALSE(problem.ok());
  EXPECT_NE(problem.error().find("<stdin>: more than the"), std::string::npos) << problem.error();
}

TEST(LoadWireProblem, AGoodFileLoads) {
  const fs::path path = ScratchDir() / "good.json";
  std::ofstream(path) << R"({"length": 1, "material": {"E": 1e9, "nu": 0.3},
    "section": {"A": 1e-4, "I": 1e-8}, "samples": 3, "bending": {"bc": "clamped"}})";
  const Result<WireProblem> problem = LoadWireProblem(path);
  ASSERT_TRUE(problem.ok()) << problem.error();
  EXPECT_EQ(problem.value().samples, 3);
}

nlohmann::json Cantilever(int samples) {
  nlohmann::json d = nlohmann::json::parse(R"({"length": 1, "material": {"E": 1e9, "nu": 0.3},
    "section": {"A": 1e-4, "I": 1e-8}, "bending": {"bc": "cantilever_free"}})");
  d["samples"] = samples;
  return d;
}

TEST(WireWork, EstimateCountsSamplesTimesLoadsOrTerms) {
  nlohmann::json d = Cantilever(1001);
  d["bending"]["point_loads"] = nlohmann::json::array();
  for (int i = 0; i < 4; ++i)
    d["bending"]["point_loads"].push_back({{"at", 0.2 * i}, {"force", {0, 1, 0}}});
  d["axial"] = {{"point_loads", {{{"at", 1.0}, {"force", 1.0}}}}};
  WireProblem p = ParseWireProblem(d).value();
  EXPECT_EQ(EstimateWireOperations(p), 1001.0 * 5 + 1001.0 * 2);
  p.bending->mode = BendingMode::kSeries;
  p.bending->series_terms = 50;
  // A series term costs 5 per point load for the coefficients (measured, docs/wire-format.md).
  EXPECT_EQ(EstimateWireOperations(p), 1001.0 * 50 + 5.0 * 50 * 4 + 1001.0 * 2);
}

// Valid inputs that ran for minutes are refused with their estimate.
TEST(WireWork, SeriesSamplesTimesTermsOverTheLimitIsRefused) {
  nlohmann::json d = Cantilever(1000000);
  d["bending"]["mode"] = "series";
  d["bending"]["terms"] = 100000;
  const Result<WireProblem> p = ParseWireProblem(d);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().rfind("/: too much work (1000000 samples x 100000 series terms, 0 bending "
                            "loads): about 1e+11 operations, more than the 2e+09 allowed",
                            0),
            0u)
      << p.error();
  d["bending"]["terms"] = 2000;  // 2e9 + 0: at the limit
  EXPECT_TRUE(ParseWireProblem(d).ok());
}

TEST(WireWork, ExactSamplesTimesPointLoadsOverTheLimitIsRefused) {
  nlohmann::json d = Cantilever(1000000);
  nlohmann::json loads = nlohmann::json::array();
  for (int i = 0; i < 100000; ++i) loads.push_back({{"at", i / 100000.0}, {"force", {0, 1, 0}}});
  d["bending"]["point_loads"] = loads;
  const Result<WireProblem> p = ParseWireProblem(d);
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.error().find("1000000 samples, 100000 bending loads): about 1e+11 operations"),
            std::string::npos)
      << p.error();
  // SolveWireProblem refuses a problem built in code alike, before any work.
  WireProblem built = ParseWireProblem(Cantilever(1000000)).value();
  built.bending->point_loads.assign(100000, PointLoad{0.5, Vec3(0, 1, 0)});
  const Result<WireSolution> solved = SolveWireProblem(built);
  ASSERT_FALSE(solved.ok());
  EXPECT_EQ(solved.error().rfind("/: too much work", 0), 0u) << solved.error();
}

// "linear_line_loads": read, solved (a cantilever under a load rising from 0 at the clamp to w
// at the tip deflects 11 w L^4 / 120 EI there, the textbook value), counted as loads in the
// work estimate, and refused by field.
TEST(WireProblem, LinearLineLoadsAreReadSolvedAndNamedInErrors) {
  nlohmann::json d = Cantilever(3);
  d["bending"]["linear_line_loads"] = nlohmann::json::parse(
      R"([{"from": 0, "to": 1, "start_force_per_length": [0, 0, 0],
           "end_force_per_length": [0, -5, 0]}])");
  const Result<WireProblem> problem = ParseWireProblem(d);
  ASSERT_TRUE(problem.ok()) << problem.error();
  ASSERT_EQ(problem.value().bending->linear_line_loads.size(), 1u);
  const Result<WireSolution> solution = SolveWireProblem(problem.value());
  ASSERT_TRUE(solution.ok()) << solution.error();
  const double ei = 1e9 * 1e-8;  // E I, N m^2
  const double expected = 11.0 * -5.0 / (120.0 * ei);
  EXPECT_NEAR(solution.value().bending.back().y(), expected, 1e-14);
  // 3 samples x (1 + 7): a linear line load costs 7 point loads per sample.
  EXPECT_DOUBLE_EQ(EstimateWireOperations(problem.value()), 3.0 * (1.0 + 7.0));

  nlohmann::json reversed = d;
  reversed["bending"]["linear_line_loads"][0]["from"] = 0.8;
  reversed["bending"]["linear_line_loads"][0]["to"] = 0.3;
  const Result<WireSolution> refused = SolveWireProblem(ParseWireProblem(reversed).value());
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error(), "/bending/linear_line_loads/0/to: must be greater than from");
  nlohmann::json missing = d;
  missing["bending"]["linear_line_loads"][0].erase("end_force_per_length");
  const Result<WireProblem> incomplete = ParseWireProblem(missing);
  ASSERT_FALSE(incomplete.ok());
  EXPECT_NE(incomplete.error().find("/bending/linear_line_loads/0/end_force_per_length"),
            std::string::npos)
      << incomplete.error();
  nlohmann::json unknown = d;
  unknown["bending"]["linear_line_loads"][0]["force_per_length"] = {0, 1, 0};
  EXPECT_FALSE(ParseWireProblem(unknown).ok());
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
