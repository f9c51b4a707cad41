#include "wirerig/io/output_file.h"
#include "wirerig/io/path_messages.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

namespace wirerig {
namespace {

namespace fs = std::filesystem;

using detail::Lowercase;
using detail::PathError;

}  // namespace

std::optional<std::string> NotARegularTarget(const fs::path& path) {
  std::error_code error;
  const fs::file_status status = fs::symlink_status(path, error);
  if (error || !fs::exists(status) || fs::is_regular_file(status)) return std::nullopt;
  if (fs::is_symlink(status))
    return "is a symbolic link: give the file it points to (writing would replace the link)";
  if (fs::is_directory(status)) return "is a directory, not a file to write";
  return "is not a regular file (a device, FIFO or socket): writing would replace it";
}

Result<bool> CheckNotAnInput(const fs::path& output, const fs::path& input, std::string_view what) {
  std::error_code error;
  if (input.empty() || !fs::equivalent(output, input, error) || error) return true;
  std::string problem = "is ";
  problem.append(what).append(" (").append(input.string());
  problem.append("), which this command reads; write elsewhere");
  return PathError(output, problem);
}

Result<bool> CheckOutputFile(const fs::path& path,
                             std::initializer_list<std::string_view> extensions) {
  if (path.empty()) return Error{"the output path is empty"};
  if (extensions.size() > 0) {
    const std::string extension = Lowercase(path.extension().string());
    bool known = false;
    std::string listed;
    for (const std::string_view allowed : extensions) {
      known = known || extension == allowed;
      if (!listed.empty()) listed += " or ";
      listed += allowed;
    }
    if (!known) {
      return PathError(path, "the output must be a " + listed + " file" +
                                 (extension.empty() ? std::string(" (it has no extension)")
                                                    : " (not " + extension + ")"));
    }
  }
  std::error_code error;
  if (fs::is_directory(path, error)) return PathError(path, "is a directory, not a file to write");
  if (std::optional<std::string> reason = NotARegularTarget(path)) return PathError(path, *reason);
  // Writing goes through "<name>.tmp<pid>" beside the target: that name must fit as well.
  constexpr std::size_t kLongestName = 255 - 12;
  if (const std::size_t length = path.filename().string().size(); length > kLongestName) {
    return PathError(path, "the file name is too long (" + std::to_string(length) +
                               " bytes; at most " + std::to_string(kLongestName) + ")");
  }
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::exists(folder, error)) {
    // Name the nearest missing folder, once.
    fs::path missing = folder;
    while (missing.has_parent_path() && missing.parent_path() != missing &&
           !fs::exists(missing.parent_path(), error)) {
      missing = missing.parent_path();
    }
    return PathError(path, "the folder " + missing.string() + " does not exist");
  }
  if (!fs::is_directory(folder, error)) {
    return PathError(path, folder.string() + " is not a folder");
  }
  if (::faccessat(AT_FDCWD, folder.c_str(), W_OK | X_OK, AT_EACCESS) != 0) {
    return PathError(path, "the folder " + folder.string() + " is not writable");
  }
  // Permission bits do not tell everything (root in /sys, a read-only mount): an empty probe
  // file is made and removed.
  const fs::path probe = folder / (".wirerig-probe-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0 && errno != EEXIST) {
    return PathError(
        path, "the folder " + folder.string() + " is not writable (" + std::strerror(errno) + ")");
  }
  if (fd >= 0) {
    ::close(fd);
    ::unlink(probe.c_str());
  }
  return true;
}

}  // namespace wirerig
