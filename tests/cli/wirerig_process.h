// Runs the real `wirerig` executable (WIRERIG_BINARY, set by CMake) as a child process, for
// what in-process tests cannot see: exit codes, signals, aborts and hangs.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#ifndef WIRERIG_BINARY
#error "the tests need WIRERIG_BINARY (set by CMake)"
#endif

namespace wirerig::cli::testing {

struct ProcessResult {
  int exit_code = -1;  // when the process exited
  int signal = 0;      // when a signal ended it (SIGABRT: an uncaught exception)
  bool timed_out = false;
  std::string out, err;  // standard output and error
};

class WirerigProcess {
 public:
  // Starts `wirerig args...` with no standard input; its output and errors go to files.
  // `stdout_to`: where standard output goes instead of the captured file (e.g. /dev/full).
  explicit WirerigProcess(const std::vector<std::string>& args, const std::string& stdout_to = {}) {
    const std::string stem =
        (std::filesystem::temp_directory_path() /
         ("wirerig_process_" + std::to_string(::getpid()) + "_" + std::to_string(counter_++)))
            .string();
    out_path_ = stem + ".out";
    err_path_ = stem + ".err";
    pid_ = ::fork();
    if (pid_ == 0) {
      const int null = ::open("/dev/null", O_RDWR);
      const int out = stdout_to.empty()
                          ? ::open(out_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600)
                          : ::open(stdout_to.c_str(), O_WRONLY);
      const int err = ::open(err_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
      ::dup2(null, 0);
      ::dup2(out, 1);
      ::dup2(err, 2);
      std::vector<char*> argv{const_cast<char*>(WIRERIG_BINARY)};
      for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(WIRERIG_BINARY, argv.data());
      ::_exit(127);
    }
  }
  WirerigProcess(const WirerigProcess&) = delete;
  WirerigProcess& operator=(const WirerigProcess&) = delete;
  ~WirerigProcess() {
    if (pid_ > 0 && !reaped_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    ::unlink(out_path_.c_str());
    ::unlink(err_path_.c_str());
  }

  pid_t pid() const { return pid_; }
  void Signal(int sig) const { ::kill(pid_, sig); }

  // Waits up to `timeout`; a process still running then is killed and reported as timed out.
  ProcessResult Wait(std::chrono::milliseconds timeout = std::chrono::seconds(60)) {
    ProcessResult result;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    int status = 0;
    while (::waitpid(pid_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > deadline) {
        result.timed_out = true;
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    reaped_ = true;
    if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
    result.out = Read(out_path_);
    result.err = Read(err_path_);
    return result;
  }

  // Standard output so far.
  std::string ReadOut() const { return Read(out_path_); }

 private:
  static std::string Read(const std::string& path) {
    std::string text;
    if (FILE* f = std::fopen(path.c_str(), "rb")) {
      char buffer[4096];
      std::size_t n;
      while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
      std::fclose(f);
    }
    return text;
  }

  static inline int counter_ = 0;
  pid_t pid_ = -1;
  bool reaped_ = false;
  std::string out_path_, err_path_;
};

// Runs `wirerig args...` to its end (or the timeout).
inline ProcessResult RunWirerig(const std::vector<std::string>& args,
                                std::chrono::milliseconds timeout = std::chrono::seconds(60)) {
  WirerigProcess process(args);
  return process.Wait(timeout);
}

}  // namespace wirerig::cli::testing
