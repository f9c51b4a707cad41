// Shared by the libFuzzer targets (docs/fuzzing.md): a per-process scratch folder for loaders
// that read a path, and FUZZ_CHECK for the properties each target asserts beyond "no crash".
#pragma once

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

// A property that must hold for every input: a failure is a finding, reported as a crash.
#define FUZZ_CHECK(condition, detail)                                                    \
  do {                                                                                   \
    if (!(condition)) {                                                                  \
      std::fprintf(stderr, "FUZZ_CHECK failed at %s:%d: %s\n  %s\n", __FILE__, __LINE__, \
                   #condition, std::string(detail).c_str());                             \
      std::abort();                                                                      \
    }                                                                                    \
  } while (false)

namespace wirerig::fuzz {

// "wirerig-fuzz-<pid>" under /dev/shm (memory, when there) or the temporary folder: one per
// fuzzer process, so parallel fuzzers (-jobs) never share an input file. A crash ends a fuzzer
// without cleanup, so each new process first removes the folders of processes that are gone.
inline const std::filesystem::path& ScratchFolder() {
  static const std::filesystem::path folder = [] {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::path base = "/dev/shm";
    if (!fs::is_directory(base, ec) || ::access(base.c_str(), W_OK) != 0)
      base = fs::temp_directory_path(ec);
    for (const fs::directory_entry& entry : fs::directory_iterator(base, ec)) {
      const std::string name = entry.path().filename().string();
      if (!name.starts_with("wirerig-fuzz-")) continue;
      const long pid = std::strtol(name.c_str() + 13, nullptr, 10);
      if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
        fs::remove_all(entry.path(), ec);
    }
    fs::path own = base / ("wirerig-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(own, ec);
    std::atexit([] {
      std::error_code ignored;
      fs::remove_all(ScratchFolder(), ignored);
    });
    return own;
  }();
  return folder;
}

// Writes the input to ScratchFolder()/name (replacing it) and returns that path.
inline std::filesystem::path WriteInput(const std::uint8_t* data, std::size_t size,
                                        std::string_view name) {
  const std::filesystem::path path = ScratchFolder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  FUZZ_CHECK(out.good(), "cannot write the fuzz input to " + path.string());
  return path;
}

// Errors of loaders that read a path start with that path (README: errors name the file).
inline void CheckNamesFile(const std::string& error, const std::filesystem::path& path) {
  FUZZ_CHECK(error.rfind(path.string() + ": ", 0) == 0, "error does not name the file: " + error);
}

}  // namespace wirerig::fuzz
