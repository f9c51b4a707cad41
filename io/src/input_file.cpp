#include "wirerig/io/input_file.h"
#include "wirerig/io/path_messages.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace wirerig {
namespace {

using detail::PathError;

// What is wrong with a file of this status for a `what` of at most max_bytes, if anything.
std::string Problem(const struct stat& status, std::string_view what, std::uintmax_t max_bytes) {
  if (S_ISDIR(status.st_mode)) return "is a directory, not a " + std::string(what);
  if (!S_ISREG(status.st_mode))
    return "is not a regular file (a FIFO, device or socket), not a " + std::string(what);
  const auto size = static_cast<std::uintmax_t>(status.st_size);
  if (size > max_bytes) {
    return "is " + std::to_string(size) + " bytes, more than the " + std::to_string(max_bytes) +
           " bytes a " + std::string(what) + " may have";
  }
  return {};
}

}  // namespace

Result<std::uintmax_t> CheckInputFile(const std::filesystem::path& path, std::string_view what,
                                      std::uintmax_t max_bytes) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    const int error = errno;
    if (error == ENOENT || error == ENOTDIR) return PathError(path, "no such file");
    return PathError(path, "cannot access (" + std::string(std::strerror(error)) + ")");
  }
  if (std::string problem = Problem(status, what, max_bytes); !problem.empty())
    return PathError(path, problem);
  return static_cast<std::uintmax_t>(status.st_size);
}

Result<std::string> ReadInputFile(const std::filesystem::path& path, std::string_view what,
                                  std::uintmax_t max_bytes) {
  // Checked by path first (its messages), then on the descriptor opened without blocking.
  Result<std::uintmax_t> checked = CheckInputFile(path, what, max_bytes);
  if (!checked) return Error{checked.error()};
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return PathError(path, "cannot open (" + std::string(std::strerror(errno)) + ")");
  struct stat status {};
  std::string problem;
  if (::fstat(fd, &status) != 0) {
    problem = "cannot read its status (" + std::string(std::strerror(errno)) + ")";
  } else {
    problem = Problem(status, what, max_bytes);
  }
  std::string bytes;
  if (problem.empty()) {
    // Read to the end, in case the file grew since fstat; never past max_bytes.
    bytes.resize(static_cast<std::size_t>(status.st_size));
    std::size_t used = 0;
    while (true) {
      if (used == bytes.size()) {
        if (bytes.size() > max_bytes) break;
        bytes.resize(bytes.size() + 65536);
      }
      const ::ssize_t n = ::read(fd, bytes.data() + used, bytes.size() - used);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        problem = "cannot read (" + std::string(std::strerror(errno)) + ")";
        break;
      }
      if (n == 0) break;
      used += static_cast<std::size_t>(n);
    }
    bytes.resize(used);
    if (problem.empty() && used > max_bytes)
      problem = "is more than the " + std::to_string(max_bytes) + " bytes a " + std::string(what) +
                " may have";
  }
  ::close(fd);
  if (!problem.empty()) return PathError(path, problem);
  return bytes;
}

}  // namespace wirerig
