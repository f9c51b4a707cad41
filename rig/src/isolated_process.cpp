#include "wirerig/rig/isolated_process.h"
#include "wirerig/io/path_messages.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <new>
#include <string>
#include <string_view>

namespace wirerig {
namespace {

namespace fs = std::filesystem;

// The child's answer: an 8-byte length, then kPayload + the work's bytes or kError + a message.
constexpr char kPayload = 'P';
constexpr char kError = 'E';

using detail::PathError;

std::string Seconds(double seconds) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%g", seconds);
  return buffer;
}

bool WriteAll(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t written = ::write(fd, bytes.data(), bytes.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    bytes.remove_prefix(static_cast<std::size_t>(written));
  }
  return true;
}

// Bytes of address space this process maps now (/proc/self/statm), 0 if unknown.
std::uint64_t AddressSpaceInUse() {
  const int fd = ::open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  char buffer[64] = {};
  const ssize_t got = ::read(fd, buffer, sizeof(buffer) - 1);
  ::close(fd);
  if (got <= 0) return 0;
  std::uint64_t pages = 0;
  for (const char* c = buffer; *c >= '0' && *c <= '9'; ++c) pages = pages * 10 + (*c - '0');
  return pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

// The child: limits itself, runs the work, answers, and ends without returning into the caller.
[[noreturn]] void RunChild(int fd, const fs::path& path, const ImportIsolation& limits,
                           const std::function<Result<std::string>()>& work, pid_t parent) {
  // Dies with the parent; the parent's signal handlers (temp_files.h) are not the child's.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(3);
  ::signal(SIGINT, SIG_DFL);
  ::signal(SIGTERM, SIG_DFL);
  // A crash ends the child by its own signal, which the parent names: the caller's crash
  // handlers (a crash reporter, a sanitizer's, a fuzzer's) belong to the caller, not the child.
  for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) ::signal(sig, SIG_DFL);
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  if (limits.memory_limit_bytes > 0) {
    const std::uint64_t total = AddressSpaceInUse() + limits.memory_limit_bytes;
    const rlimit address_space{static_cast<rlim_t>(total), static_cast<rlim_t>(total)};
    ::setrlimit(RLIMIT_AS, &address_space);
  }
  std::string answer(sizeof(std::uint64_t), '\0');
  try {
    Result<std::string> done = work();
    if (done) {
      answer += kPayload;
      answer += done.value();
    } else {
      answer += kError;
      answer += done.error();
    }
  } catch (const std::bad_alloc&) {
    answer.resize(sizeof(std::uint64_t));
    answer += kError;
    answer += path.string() + ": cannot import: out of memory";
  } catch (const std::exception& e) {
    answer.resize(sizeof(std::uint64_t));
    answer += kError;
    answer += path.string() + ": cannot import: " + e.what();
  }
  const std::uint64_t size = answer.size() - sizeof(std::uint64_t);
  std::memcpy(answer.data(), &size, sizeof(size));
  ::_exit(WriteAll(fd, answer) ? 0 : 4);
}

// Appends what the child writes to `out` until it closes the pipe (true) or `deadline` passes
// (false).
bool ReadUntilClosed(int fd, std::chrono::steady_clock::time_point deadline, std::string& out) {
  char buffer[1 << 16];
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd ready{fd, POLLIN, 0};
    const int n = ::poll(&ready, 1, static_cast<int>(std::min<std::int64_t>(left.count(), 60000)));
    if (n < 0 && errno != EINTR) return true;  // treated as a child that said nothing
    if (n <= 0) continue;
    const ssize_t got = ::read(fd, buffer, sizeof(buffer));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return true;
    out.append(buffer, static_cast<std::size_t>(got));
  }
}

std::string HowItEnded(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = ::strsignal(sig);
    return std::string(name != nullptr ? name : "signal") + ", signal " + std::to_string(sig);
  }
  if (WIFEXITED(status)) return "it exited with status " + std::to_string(WEXITSTATUS(status));
  return "it stopped";
}

}  // namespace

Result<std::string> RunIsolated(const fs::path& path, const ImportIsolation& limits,
                                const std::function<Result<std::string>()>& work) {
  if (!std::isfinite(limits.time_limit_seconds) || !(limits.time_limit_seconds > 0.0)) {
    return PathError(path, "ImportIsolation::time_limit_seconds must be a number > 0 (got " +
                               Seconds(limits.time_limit_seconds) + ")");
  }
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
    return PathError(path, std::string("cannot start the importer process (pipe: ") +
                               std::strerror(errno) + ")");
  }
  const pid_t parent = ::getpid();
  const pid_t child = ::fork();
  if (child < 0) {
    const int error = errno;
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    return PathError(path, std::string("cannot start the importer process (fork: ") +
                               std::strerror(error) + ")");
  }
  if (child == 0) {
    ::close(pipe_fds[0]);
    RunChild(pipe_fds[1], path, limits, work, parent);
  }
  ::close(pipe_fds[1]);

  const auto limit = std::chrono::duration<double>(std::min(limits.time_limit_seconds, 1e7));
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(limit);
  std::string answer;
  const bool finished = ReadUntilClosed(pipe_fds[0], deadline, answer);
  ::close(pipe_fds[0]);
  if (!finished) ::kill(child, SIGKILL);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (!finished) {
    return PathError(path, "the importer timed out on this file (still running after " +
                               Seconds(limits.time_limit_seconds) +
                               " s, ImportIsolation::time_limit_seconds); it was stopped");
  }

  std::uint64_t size = 0;
  if (answer.size() < sizeof(size) + 1 ||
      (std::memcpy(&size, answer.data(), sizeof(size)), size != answer.size() - sizeof(size))) {
    return PathError(path, "the importer crashed on this file (" + HowItEnded(status) +
                               "); the file is corrupted or Assimp cannot read it");
  }
  const std::string_view body = std::string_view(answer).substr(sizeof(size) + 1);
  if (answer[sizeof(size)] == kError) {
    std::string message(body);
    if (message.ends_with("out of memory") && limits.memory_limit_bytes > 0) {
      message += " (limit " + std::to_string(limits.memory_limit_bytes >> 20) +
                 " MiB, ImportIsolation::memory_limit_bytes)";
    }
    return Error{std::move(message)};
  }
  return std::string(body);
}

}  // namespace wirerig
