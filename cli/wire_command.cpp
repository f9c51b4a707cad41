#include "wire_command.h"

#include <fstream>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "wire_table.h"
#include "wirerig/rig/atomic_file.h"
#include "wirerig/rig/wire_problem.h"

namespace wirerig::cli {

CLI::App* AddWireCommand(CLI::App& app, WireCommandOptions& options) {
  CLI::App* wire =
      app.add_subcommand("wire", "Solve one wire problem (JSON) and print its deflected samples");
  wire->add_option("input", options.input, "Wire problem file (JSON), or - for standard input")
      ->required();
  wire->add_option("--format", options.format, "Output format")
      ->check(CLI::IsMember({"json", "table"}))
      ->capture_default_str();
  wire->add_option("-o,--output", options.output, "Write here instead of standard output");
  return wire;
}

int RunWireCommand(const WireCommandOptions& options, std::istream& in, std::ostream& out,
                   std::ostream& err) {
  const bool from_stdin = options.input == "-";
  std::ifstream file;
  if (!from_stdin) {
    file.open(options.input, std::ios::binary);
    if (!file) {
      err << "wirerig wire: " << options.input << ": cannot open file\n";
      return 1;
    }
  }
  const std::string source = from_stdin ? "<stdin>" : options.input;
  const Result<WireProblem> problem = LoadWireProblem(from_stdin ? in : file, source);
  if (!problem) {
    err << "wirerig wire: " << problem.error() << "\n";
    return 1;
  }
  const Result<WireSolution> solution = SolveWireProblem(problem.value());
  if (!solution) {
    err << "wirerig wire: " << source << ": " << solution.error() << "\n";
    return 1;
  }
  std::ostringstream text;
  if (options.format == "table")
    PrintWireTable(text, problem.value(), solution.value());
  else
    text << WireSolutionToJson(solution.value()).dump() << "\n";

  if (options.output.empty()) {
    out << text.str();
    return 0;
  }
  const auto written = WriteFileAtomically(options.output, text.str());
  if (!written) {
    err << "wirerig wire: " << written.error() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace wirerig::cli
