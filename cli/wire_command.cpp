#include "wire_command.h"

#include <filesystem>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "wire_table.h"
#include "wirerig/io/atomic_file.h"
#include "wirerig/io/output_file.h"
#include "wirerig/wire_problem/wire_problem.h"

namespace wirerig::cli {

namespace fs = std::filesystem;

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
  // Where the output goes is checked before any work (any extension: JSON or a table).
  if (!options.output.empty()) {
    if (Result<bool> writable = CheckOutputFile(options.output, {}); !writable) {
      err << "wirerig wire: " << writable.error() << "\n";
      return 1;
    }
    if (options.input != "-") {
      if (Result<bool> own = CheckNotAnInput(options.output, options.input, "the wire problem");
          !own) {
        err << "wirerig wire: " << own.error() << "\n";
        return 1;
      }
    }
  }
  const bool from_stdin = options.input == "-";
  const std::string source = from_stdin ? "<stdin>" : options.input;
  // A file is checked before it is opened (a directory or FIFO is refused, never read).
  const Result<WireProblem> problem =
      from_stdin ? LoadWireProblem(in, source) : LoadWireProblem(fs::path(options.input));
  if (!problem) {
    err << "wirerig wire: " << problem.error() << "\n";
    return 1;
  }
  const Result<WireSolution> solution = SolveWireProblem(problem.value());
  if (!solution) {
    err << "wirerig wire: " << source << ": " << solution.error() << "\n";
    return 1;
  }
  for (const std::string& warning : WireSolutionWarnings(problem.value(), solution.value()))
    err << "wirerig wire: warning: " << source << ": " << warning << "\n";
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
