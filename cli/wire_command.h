// `wirerig wire`: solve one wire problem given as JSON (docs/wire-format.md) and print the
// deflected samples as JSON, or as a readable table.
#pragma once

#include <iosfwd>
#include <string>

#include <CLI/App.hpp>

namespace wirerig::cli {

struct WireCommandOptions {
  std::string input;            // a file path, or "-" for standard input
  std::string format = "json";  // "json" or "table"
  std::string output;           // empty: standard output; otherwise written atomically
};

// Registers the subcommand's options on `app`, bound to `options`.
CLI::App* AddWireCommand(CLI::App& app, WireCommandOptions& options);

// Returns the process exit code: 0 on success, 1 when the input is invalid (the message,
// naming the file and field, goes to `err`). Nothing is written to `out` or to the output
// file on failure.
int RunWireCommand(const WireCommandOptions& options, std::istream& in, std::ostream& out,
                   std::ostream& err);

}  // namespace wirerig::cli
