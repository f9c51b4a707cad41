#include "import_limits.h"

#include "option_checks.h"

namespace wirerig::cli {

ImportIsolation ImportLimitOptions::Isolation() const {
  ImportIsolation isolation;
  isolation.time_limit_seconds = seconds;
  isolation.memory_limit_bytes = memory_mib << 20;
  return isolation;
}

void AddImportLimitOptions(CLI::App* command, ImportLimitOptions& limits) {
  command
      ->add_option("--import-seconds", limits.seconds,
                   "Time an import of a mesh or motion file may take before it is stopped (s)")
      ->check(InRange(1e-3, 1e6))
      ->capture_default_str();
  command
      ->add_option("--import-memory", limits.memory_mib,
                   "Memory an import may add, MiB (0: no limit); it runs in a child process")
      ->check(InRange(0.0, 1e6))
      ->capture_default_str();
}

}  // namespace wirerig::cli
