#include "wirerig/io/atomic_file.h"

#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <memory>
#include <system_error>

#include "wirerig/io/output_file.h"
#include "wirerig/io/temp_files.h"

namespace wirerig {
namespace {

namespace fs = std::filesystem;

// `bytes` in the temporary file beside `file.path` (registered in *registered), or an error
// naming the target; on failure no temporary file is left.
Result<fs::path> WriteTemporary(const FileToWrite& file,
                                std::vector<std::unique_ptr<TemporaryFile>>* registered) {
  const fs::path& path = file.path;
  if (std::optional<std::string> reason = NotARegularTarget(path))
    return Error{path.string() + ": " + *reason};
  RemoveStaleTemporaryFiles(path);
  const fs::path temp = TemporaryPathFor(path);
  // Removed if SIGINT or SIGTERM comes before the rename.
  registered->push_back(std::make_unique<TemporaryFile>(temp));
  std::ofstream out(temp, std::ios::binary | std::ios::trunc);
  if (!out) return Error{path.string() + ": cannot write (" + std::strerror(errno) + ")"};
  out.write(file.bytes.data(), static_cast<std::streamsize>(file.bytes.size()));
  out.flush();
  if (!out) {
    const int cause = errno;  // the failed write(2)'s: a full disk, a file-size limit
    out.close();
    std::error_code ignored;
    fs::remove(temp, ignored);
    return Error{path.string() + ": write failed (" +
                 (cause != 0 ? std::strerror(cause) : "unknown cause") + ")"};
  }
  return temp;
}

}  // namespace

Result<std::vector<fs::path>> WriteFilesAtomically(std::span<const FileToWrite> files) {
  std::vector<std::unique_ptr<TemporaryFile>> registered;
  std::vector<fs::path> temporaries;
  auto remove_temporaries = [&] {
    std::error_code ignored;
    for (const fs::path& temp : temporaries) fs::remove(temp, ignored);
  };
  for (const FileToWrite& file : files) {
    Result<fs::path> temp = WriteTemporary(file, &registered);
    if (!temp) {
      remove_temporaries();
      if (files.size() == 1) return Error{temp.error()};
      return Error{temp.error() + "; none of the " + std::to_string(files.size()) +
                   " files was replaced"};
    }
    temporaries.push_back(std::move(temp.value()));
  }
  std::vector<fs::path> written;
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code error;
    fs::rename(temporaries[i], files[i].path, error);
    if (error) {
      std::error_code ignored;
      for (std::size_t j = i; j < files.size(); ++j) fs::remove(temporaries[j], ignored);
      std::string message = files[i].path.string() + ": cannot replace (" + error.message() + ")";
      if (!written.empty()) {
        message += "; already replaced:";
        for (const fs::path& done : written) message.append(" ").append(done.string());
      }
      return Error{message};
    }
    written.push_back(files[i].path);
  }
  return written;
}

Result<fs::path> WriteFileAtomically(const fs::path& path, std::string_view bytes) {
  const FileToWrite file{path, bytes};
  Result<std::vector<fs::path>> written = WriteFilesAtomically({&file, 1});
  if (!written) return Error{written.error()};
  return path;
}

}  // namespace wirerig
