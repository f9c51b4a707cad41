// `--import-seconds S` and `--import-memory MIB`: the limits of the child process in which every
// command imports outside files through Assimp (ImportIsolation, rig/isolated_process.h).
#pragma once

#include <cstdint>

#include <CLI/CLI.hpp>

#include "wirerig/rig/mesh_import.h"

namespace wirerig::cli {

struct ImportLimitOptions {
  double seconds = ImportIsolation{}.time_limit_seconds;                  // wall clock, > 0
  std::uint64_t memory_mib = ImportIsolation{}.memory_limit_bytes >> 20;  // 0: no limit

  ImportIsolation Isolation() const;
};

// Adds both options to `command`, bound to `limits`.
void AddImportLimitOptions(CLI::App* command, ImportLimitOptions& limits);

}  // namespace wirerig::cli
