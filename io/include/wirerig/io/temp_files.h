// Temporary files that never outlive their process: a file registered here is removed if the
// process is killed by SIGHUP, SIGINT, SIGTERM, SIGQUIT, SIGPIPE, SIGALRM, SIGUSR1, SIGUSR2,
// SIGXFSZ or SIGXCPU (an async-signal-safe handler unlinks every registered path, then
// re-raises the signal with its default action), and a temporary file left by a process that
// died otherwise (SIGKILL, a crash) is removed by the next write beside it.
// Temporary files are named "<target>.tmp<pid>" (TemporaryPathFor).
#pragma once

#include <filesystem>

namespace wirerig {

// "<target>.tmp<pid of this process>".
std::filesystem::path TemporaryPathFor(const std::filesystem::path& target);

// Removes "<target>.tmp<pid>" files beside `target` whose process is no longer alive (kill(pid,
// 0) fails with ESRCH); another live process's temporary file, and this process's, are kept.
void RemoveStaleTemporaryFiles(const std::filesystem::path& target);

// Registers `path` (if not empty) for removal on those signals until destruction or Keep().
// The handlers are installed on first use, for signals whose action is still the default (an
// application's own handler or an ignored signal is left alone). At most 32 files are
// registered at a time; beyond that a file is simply not covered.
class TemporaryFile {
 public:
  explicit TemporaryFile(const std::filesystem::path& path);
  ~TemporaryFile();
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  // The file stays (it was renamed into place, or removed by the caller): no longer covered.
  void Keep();

 private:
  int slot_ = -1;
};

// Holds those signals (blocked, not lost) for its lifetime, so that steps which must not
// be split by a kill (renaming a file into place and no longer covering it) happen together;
// a signal that came meanwhile is delivered at destruction.
class SignalsHeld {
 public:
  SignalsHeld();
  ~SignalsHeld();
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

 private:
  unsigned long long saved_[16];  // the previous signal mask (a sigset_t)
};

}  // namespace wirerig
