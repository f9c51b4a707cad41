// `wirerig wire`, run in-process: results against textbook values, and one test per kind of
// malformed input, each expecting an error that names the file and the JSON field.
#include "wire_command.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

namespace wirerig::cli {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

struct CommandRun {
  int exit_code;
  std::string out, err;
};

CommandRun RunOnText(const std::string& json_text, const std::string& format = "json") {
  WireCommandOptions options;
  options.input = "-";
  options.format = format;
  std::istringstream in(json_text);
  std::ostringstream out, err;
  const int code = RunWireCommand(options, in, out, err);
  return {code, out.str(), err.str()};
}

// A valid clamped problem: E I = 2e9 * 1e-8 = 20 N m^2, L = 2 m.
nlohmann::json ValidProblem() {
  return nlohmann::json::parse(R"({
    "length": 2.0,
    "material": {"E": 2.0e9, "nu": 0.3},
    "section": {"A": 1e-4, "I": 1e-8},
    "samples": 101,
    "bending": {"bc": "clamped", "point_loads": [{"at": 0.5, "force": [0, -10, 0]}]},
    "axial": {"fixed_at": 0.0, "point_loads": [{"at": 1.0, "force": 10.0}]}
  })");
}

TEST(WireCommand, SolvesAndPrintsSamplesAsJson) {
  const CommandRun run = RunOnText(ValidProblem().dump());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(run.err.empty());
  const nlohmann::json out = nlohmann::json::parse(run.out);
  ASSERT_EQ(out["v"].size(), 101u);
  ASSERT_EQ(out["bending"].size(), 101u);
  ASSERT_EQ(out["axial"].size(), 101u);
  EXPECT_DOUBLE_EQ(out["v"][50].get<double>(), 0.5);
  // Clamped centre load: F L^3 / (192 EI); axial tip load: F L / EA.
  EXPECT_NEAR(out["bending"][50][1].get<double>(), -10.0 * 8.0 / (192.0 * 20.0), 1e-12);
  EXPECT_NEAR(out["axial"][100].get<double>(), 10.0 * 2.0 / (2.0e9 * 1e-4), 1e-18);
}

TEST(WireCommand, StripSectionUsesThePlateModulus) {
  nlohmann::json problem = ValidProblem();
  problem["section"] = {{"strip", {{"b", 0.05}, {"h", 0.002}}}};
  const CommandRun run = RunOnText(problem.dump());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const double ei = 2.0e9 / (1.0 - 0.09) * 0.05 * 8e-9 / 12.0;
  const nlohmann::json out = nlohmann::json::parse(run.out);
  EXPECT_NEAR(out["bending"][50][1].get<double>(), -10.0 * 8.0 / (192.0 * ei), 1e-12);
}

// A 1e12 N load on a soft wire gave 3e24 m with no warning: solved, printed, and warned about.
TEST(WireCommand, ADeflectionLongerThanTheWireIsWarnedAbout) {
  nlohmann::json problem = ValidProblem();
  problem["material"] = {{"E", 1e5}, {"nu", 0.45}};
  problem["bending"]["point_loads"][0]["force"] = {0, -1e12, 0};
  problem.erase("axial");
  const CommandRun run = RunOnText(problem.dump());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Clamped, centre load: F L^3 / 192 EI = 1e12 * 8 / (192 * 1e-3) = 4.17e13 m at v = 0.5.
  EXPECT_NE(run.err.find("wirerig wire: warning: <stdin>: bending displacement 4.17e+13 m at v = "
                         "0.5 exceeds the wire's length 2 m: linear beam theory no longer holds"),
            std::string::npos)
      << run.err;
  // The textbook problem warns about nothing.
  EXPECT_TRUE(RunOnText(ValidProblem().dump()).err.empty());
}

// Valid but huge problems ran for minutes; they are refused with the estimate, exit 1.
TEST(WireCommand, TooMuchWorkIsRefusedWithTheEstimate) {
  nlohmann::json problem = ValidProblem();
  problem["samples"] = 1000000;
  problem["bending"]["mode"] = "series";
  problem["bending"]["terms"] = 100000;
  const CommandRun run = RunOnText(problem.dump());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("<stdin>: /: too much work (1000000 samples x 100000 series terms"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("more than the 2e+09 allowed"), std::string::npos) << run.err;
  // Linear line loads cost more than point loads: 9,900 of them over 100,000 series terms (2
  // samples) were estimated at 2e9 and ran for 102 s.
  problem = ValidProblem();
  problem["samples"] = 2;
  problem["bending"] = {{"bc", "simply_supported"}, {"mode", "series"}, {"terms", 100000}};
  for (int i = 0; i < 9900; ++i) {
    problem["bending"]["linear_line_loads"].push_back({{"from", 0.1},
                                                       {"to", 0.9},
                                                       {"start_force_per_length", {0, -1, 0}},
                                                       {"end_force_per_length", {0, -2, 0}}});
  }
  const CommandRun linear = RunOnText(problem.dump());
  EXPECT_EQ(linear.exit_code, 1);
  EXPECT_NE(linear.err.find("9900 bending loads"), std::string::npos) << linear.err;
  EXPECT_NE(linear.err.find("about 1.98e+10 operations"), std::string::npos) << linear.err;
}

TEST(WireCommand, SeriesModeAndMaterialPresets) {
  nlohmann::json problem = ValidProblem();
  problem["material"] = "steel";
  problem["bending"]["mode"] = "series";
  problem["bending"]["terms"] = 400;
  const CommandRun run = RunOnText(problem.dump());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const double expected = -10.0 * 8.0 / (192.0 * 200e9 * 1e-8);
  EXPECT_NEAR(nlohmann::json::parse(run.out)["bending"][50][1].get<double>(), expected,
              1e-6 * std::abs(expected));
}

TEST(WireCommand, TableFormatIsReadable) {
  const CommandRun run = RunOnText(ValidProblem().dump(), "table");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("EI = 20 N m^2"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("clamped, exact solution"), std::string::npos);
  EXPECT_NE(run.out.find("X_y [mm]"), std::string::npos);
}

// Each malformed input: exit 1, nothing on stdout, and the expected "<field>: <reason>".
void ExpectError(const nlohmann::json& problem, const std::string& expected) {
  const CommandRun run = RunOnText(problem.dump());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_TRUE(run.out.empty());
  EXPECT_NE(run.err.find("<stdin>: " + expected), std::string::npos) << run.err;
}

TEST(WireCommandErrors, NotJson) {
  const CommandRun run = RunOnText("{\"length\": 2.0,");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("<stdin>: not valid JSON"), std::string::npos) << run.err;
}

TEST(WireCommandErrors, MissingOrMistypedFields) {
  nlohmann::json p = ValidProblem();
  p.erase("length");
  ExpectError(p, "/length: is required");
  p = ValidProblem();
  p["length"] = "two";
  ExpectError(p, "/length: must be a number");
  p = ValidProblem();
  p["bending"]["point_loads"][0]["force"] = {0, -10};
  ExpectError(p, "/bending/point_loads/0/force: must be an array of 3 numbers");
  p = ValidProblem();
  p["bending"]["pointloads"] = nlohmann::json::array();
  ExpectError(p, "/bending/pointloads: unknown field");
  p = ValidProblem();
  p.erase("bending");
  p.erase("axial");
  ExpectError(p, "/: needs \"bending\", \"axial\" or both");
}

TEST(WireCommandErrors, InvalidMaterialAndSection) {
  nlohmann::json p = ValidProblem();
  p["material"]["E"] = -1.0;
  ExpectError(p, "/material/E: must be positive and finite");
  p = ValidProblem();
  p["material"]["nu"] = 0.5;
  ExpectError(p, "/material/nu: must lie in (-1, 0.5)");
  p = ValidProblem();
  p["material"] = "cheese";
  ExpectError(p,
              "/material: unknown material preset 'cheese' (presets: rubber, soft_tissue, skin, "
              "cartilage, wood, aluminium, steel)");
  p["material"] = "steal";  // a misspelling gets the nearest preset
  ExpectError(p, "/material: unknown material preset 'steal'; did you mean \"steel\"?");
  p = ValidProblem();
  p["section"] = {{"A", 0.0}, {"I", 1e-8}};
  ExpectError(p, "/section/A: must be positive and finite");
  p = ValidProblem();
  p["section"] = {{"tube", {{"r", 0.01}, {"h", 0.05}}}};
  ExpectError(p, "/section/tube/h: must not exceed twice the mean radius r");
  p = ValidProblem();
  p["section"]["strip"] = {{"b", 0.1}, {"h", 0.01}};
  ExpectError(p, "/section: needs exactly one of");
}

TEST(WireCommandErrors, InvalidLoadsAndSamples) {
  nlohmann::json p = ValidProblem();
  p["bending"]["point_loads"][0]["at"] = 1.5;
  ExpectError(p, "/bending/point_loads/0/at: must lie in [0, 1]");
  p = ValidProblem();
  p["bending"]["line_loads"] = {{{"from", 0.6}, {"to", 0.2}, {"force_per_length", {0, 1, 0}}}};
  ExpectError(p, "/bending/line_loads/0/to: must be greater than from");
  p = ValidProblem();
  p["bending"]["tip_force"] = {0, -1, 0};
  ExpectError(p, "/bending/tip_force: applies to cantilevers only");
  p = ValidProblem();
  p["bending"]["bc"] = "pinned";
  ExpectError(p, "/bending/bc: unknown boundary condition 'pinned'");
  p = ValidProblem();
  p["bending"]["mode"] = "series";
  p["bending"]["terms"] = 0;
  ExpectError(p, "/bending/terms: must lie in [1, 100000]");
  p = ValidProblem();
  p["axial"]["fixed_at"] = -0.5;
  ExpectError(p, "/axial/fixed_at: must lie in [0, 1]");
  p = ValidProblem();
  p["samples"] = 1;
  ExpectError(p, "/samples: must lie in [2, 1000000]");
  p = ValidProblem();
  p["samples"] = 5000000000LL;
  ExpectError(p, "/samples: is out of range (an integer within [-2147483648, 2147483647])");
  // 2^64 - 1 (unsigned: must not wrap to -1), 2^64 and 1e300 (floating point in JSON, yet
  // integers): out of range; 2.5: not an integer.
  for (const nlohmann::json& huge :
       {nlohmann::json(18446744073709551615ULL), nlohmann::json::parse("18446744073709551616"),
        nlohmann::json(1e300)}) {
    p = ValidProblem();
    p["samples"] = huge;
    ExpectError(p, "/samples: is out of range (an integer within [-2147483648, 2147483647])");
  }
  p = ValidProblem();
  p["samples"] = 2.5;
  ExpectError(p, "/samples: must be an integer");
  p = ValidProblem();
  p["bending"]["point_loads"][0]["force"] = {0, -1e200, 0};
  p["material"]["E"] = 1.0;
  ExpectError(p, "/bending: too large for the stiffness");
}

TEST(WireCommandErrors, MissingFileIsNamed) {
  WireCommandOptions options;
  options.input = "/nonexistent/wire.json";
  std::istringstream in;
  std::ostringstream out, err;
  EXPECT_EQ(RunWireCommand(options, in, out, err), 1);
  EXPECT_NE(err.str().find("/nonexistent/wire.json: no such file"), std::string::npos);
}

TEST(WireCommandFiles, ErrorsNameTheFileAndLeaveNoOutput) {
  const fs::path dir = fs::temp_directory_path() / "wirerig_cli_test";
  fs::create_directories(dir);
  const fs::path input = dir / "bad.json", output = dir / "out.json";
  fs::remove(output);
  nlohmann::json p = ValidProblem();
  p["length"] = -2.0;
  std::ofstream(input) << p.dump();
  WireCommandOptions options{input.string(), "json", output.string()};
  std::istringstream in;
  std::ostringstream out, err;
  EXPECT_EQ(RunWireCommand(options, in, out, err), 1);
  EXPECT_NE(err.str().find(input.string() + ": /length: must be positive"), std::string::npos)
      << err.str();
  EXPECT_FALSE(fs::exists(output));
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos);
}

// An output in a missing folder was found only after the problem was read and solved: it is
// refused first, the folder named once, the input not read.
TEST(WireCommandFiles, AnUnwritableOutputIsRefusedBeforeTheInputIsRead) {
  WireCommandOptions options{"-", "json", "/nonexistent/deeper/out.json"};
  std::istringstream in(ValidProblem().dump());
  std::ostringstream out, err;
  EXPECT_EQ(RunWireCommand(options, in, out, err), 1);
  EXPECT_EQ(err.str(),
            "wirerig wire: /nonexistent/deeper/out.json: the folder /nonexistent does not exist\n");
  EXPECT_EQ(in.tellg(), 0);  // nothing read, nothing solved
  EXPECT_TRUE(out.str().empty());
}

TEST(WireCommandFiles, WritesTheOutputFile) {
  const fs::path dir = fs::temp_directory_path() / "wirerig_cli_test";
  fs::create_directories(dir);
  const fs::path output = dir / "worked.json";
  WireCommandOptions options{
      std::string(WIRERIG_SAMPLES_DIR) + "/worked_wire/steel_cantilever.json", "json",
      output.string()};
  std::istringstream in;
  std::ostringstream out, err;
  ASSERT_EQ(RunWireCommand(options, in, out, err), 0) << err.str();
  EXPECT_TRUE(out.str().empty());
  std::ifstream written(output);
  const nlohmann::json result = nlohmann::json::parse(written);
  EXPECT_EQ(result["v"].size(), 11u);
  EXPECT_EQ(result["bending"].size(), 11u);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::cli
