#include "wirerig/io/atomic_file.h"

#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "wirerig/io/output_file.h"
#include "wirerig/io/temp_files.h"

namespace wirerig {

Result<std::filesystem::path> WriteFileAtomically(const std::filesystem::path& path,
                                                  std::string_view bytes) {
  namespace fs = std::filesystem;
  if (std::optional<std::string> reason = NotARegularTarget(path))
    return Error{path.string() + ": " + *reason};
  RemoveStaleTemporaryFiles(path);
  const fs::path temp = TemporaryPathFor(path);
  TemporaryFile registered(temp);  // removed if SIGINT or SIGTERM comes before the rename
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) return Error{path.string() + ": cannot write (" + std::strerror(errno) + ")"};
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) {
      const int cause = errno;  // the failed write(2)'s: a full disk, a file-size limit
      std::error_code ignored;
      fs::remove(temp, ignored);
      return Error{path.string() + ": write failed (" +
                   (cause != 0 ? std::strerror(cause) : "unknown cause") + ")"};
    }
  }
  std::error_code error;
  fs::rename(temp, path, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    return Error{path.string() + ": cannot replace (" + error.message() + ")"};
  }
  return path;
}

}  // namespace wirerig
