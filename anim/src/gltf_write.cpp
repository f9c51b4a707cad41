#include "gltf_write.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include <nlohmann/json.hpp>

#include "gltf_buffers.h"
#include "gltf_paths.h"
#include "wirerig/io/atomic_file.h"
#include "wirerig/io/input_file.h"
#include "wirerig/io/json_text.h"
#include "wirerig/io/output_file.h"
#include "wirerig/io/temp_files.h"

namespace wirerig::gltf {
namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kGlbMagic = 0x46546C67u;  // "glTF"
constexpr std::uint32_t kGlbVersion = 2;
constexpr std::uint32_t kJsonChunk = 0x4E4F534Au;  // "JSON"
constexpr std::uint32_t kBinChunk = 0x004E4942u;   // "BIN\0"
constexpr std::size_t kGlbHeader = 12;
constexpr std::size_t kChunkHeader = 8;

// The model's JSON without buffers (buffer 0 is written by the caller), compact.
Result<std::string> SerializeJson(tinygltf::Model& model) {
  model.buffers.clear();
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(nullptr, nullptr);  // keep every image's URI; never re-encode
  std::ostringstream stream;
  if (!writer.WriteGltfSceneToStream(&model, stream, /*prettyPrint=*/false,
                                     /*writeBinary=*/false) ||
      !stream) {
    return Error{"tinygltf could not serialize the model"};
  }
  std::string json = std::move(stream).str();
  while (!json.empty() && (json.back() == '\n' || json.back() == ' ')) json.pop_back();
  if (json.size() < 2 || json.front() != '{' || json.back() != '}') {
    return Error{"tinygltf wrote no JSON object"};
  }
  return json;
}

void PutU32(std::string& bytes, std::uint32_t value) {
  char raw[4];
  std::memcpy(raw, &value, sizeof raw);  // glTF is little-endian, as is every platform
  bytes.append(raw, sizeof raw);         // wirerig builds on
}

std::uint32_t GetU32(const unsigned char* bytes) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes, sizeof value);
  return value;
}

// Writes the bytes `produce` hands to its sink to `path` atomically: a temporary file in the
// same folder, checked (its size is `size`; `check` may look at the open file), then renamed
// over `path`. On failure the target is untouched and no temporary file is left behind.
Result<fs::path> WriteStreamAtomically(
    const fs::path& path, std::uintmax_t size, const std::function<bool(const ByteSink&)>& produce,
    const std::function<std::optional<std::string>(int)>& check = nullptr) {
  if (std::optional<std::string> reason = NotARegularTarget(path))
    return Error{path.string() + ": " + *reason};
  RemoveStaleTemporaryFiles(path);
  const fs::path temp = TemporaryPathFor(path);
  TemporaryFile registered(temp);  // removed if SIGINT or SIGTERM comes before the rename
  const int fd = ::open(temp.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return Error{path.string() + ": cannot write (" + std::strerror(errno) + ")"};
  std::uintmax_t written = 0;
  int write_error = 0;
  const ByteSink sink = [&](std::span<const unsigned char> block) {
    const unsigned char* p = block.data();
    std::size_t left = block.size();
    while (left > 0) {
      const ::ssize_t n = ::write(fd, p, left);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        write_error = n < 0 ? errno : EIO;
        return false;
      }
      p += n;
      left -= static_cast<std::size_t>(n);
      written += static_cast<std::uintmax_t>(n);
    }
    return true;
  };
  std::optional<std::string> problem;
  if (!produce(sink)) {
    problem =
        std::string("write failed (") + std::strerror(write_error != 0 ? write_error : EIO) + ")";
  }
  struct stat status {};
  if (!problem && (written != size || ::fstat(fd, &status) != 0 ||
                   static_cast<std::uintmax_t>(status.st_size) != size)) {
    problem = "written file has the wrong size";
  }
  if (!problem && check) problem = check(fd);
  if (::close(fd) != 0 && !problem) {
    problem = std::string("write failed (") + std::strerror(errno) + ")";
  }
  std::error_code ignored;
  if (problem) {
    fs::remove(temp, ignored);
    return Error{path.string() + ": " + *problem};
  }
  std::error_code error;
  fs::rename(temp, path, error);
  if (error) {
    fs::remove(temp, ignored);
    return Error{path.string() + ": cannot replace (" + error.message() + ")"};
  }
  return path;
}

// The file's first 20 bytes are the GLB header we wrote and its JSON chunk header.
std::optional<std::string> CheckGlbHeader(int fd, std::size_t total, std::size_t json_chunk) {
  std::array<unsigned char, kGlbHeader + kChunkHeader> header{};
  if (::pread(fd, header.data(), header.size(), 0) != static_cast<::ssize_t>(header.size()) ||
      GetU32(&header[0]) != kGlbMagic || GetU32(&header[4]) != kGlbVersion ||
      GetU32(&header[8]) != total || GetU32(&header[12]) != json_chunk ||
      GetU32(&header[16]) != kJsonChunk) {
    return std::string("written file has no valid GLB header");
  }
  return std::nullopt;
}

// Hands buffer 0 (in-memory data, then the tail) to `sink`.
bool WriteBuffer(std::span<const unsigned char> data, const BufferTail& tail,
                 const ByteSink& sink) {
  if (!data.empty() && !sink(data)) return false;
  return tail.size == 0 || tail.write(sink);
}

// Adds EXT_meshopt_compression's view extensions and fallback buffer to `document`, whose
// "buffers" holds buffer 0. Compressed files, whose JSON is a tenth of their bytes, also leave
// out what the spec makes the default: a sampler's LINEAR interpolation.
void AddMeshoptJson(nlohmann::json& document, const MeshoptJson& meshopt) {
  if (meshopt.fallback_bytes == 0) return;
  if (document.contains("animations")) {
    for (nlohmann::json& animation : document["animations"]) {
      if (!animation.contains("samplers")) continue;
      for (nlohmann::json& sampler : animation["samplers"])
        if (sampler.value("interpolation", "") == "LINEAR") sampler.erase("interpolation");
    }
  }
  for (const auto& [view, extension] : meshopt.views) {
    document["bufferViews"][view]["extensions"]["EXT_meshopt_compression"] =
        nlohmann::json::parse(extension);
  }
  document["buffers"].push_back(
      {{"byteLength", meshopt.fallback_bytes},
       {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
}

Result<std::vector<fs::path>> WriteGlb(tinygltf::Model model, const BufferTail& tail,
                                       const fs::path& out, const MeshoptJson& meshopt) {
  std::vector<unsigned char> data;
  if (!model.buffers.empty()) data = std::move(model.buffers[0].data);
  const std::size_t buffer_size = data.size() + tail.size;
  Result<std::string> serialized = SerializeJson(model);
  if (!serialized) return Error{out.string() + ": " + serialized.error()};
  std::string& json = serialized.value();
  if (meshopt.fallback_bytes > 0) {
    nlohmann::json document = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
    if (document.is_discarded()) return Error{out.string() + ": tinygltf wrote invalid JSON"};
    document["buffers"] = nlohmann::json::array({{{"byteLength", buffer_size}}});
    AddMeshoptJson(document, meshopt);
    json = DumpJson(document);
  } else if (buffer_size > 0) {
    json.pop_back();
    json.append(R"(,"buffers":[{"byteLength":)").append(std::to_string(buffer_size)).append("}]}");
  }
  const std::size_t json_chunk = Padded4(json.size());
  const std::size_t bin_chunk = Padded4(buffer_size);
  const std::size_t total =
      kGlbHeader + kChunkHeader + json_chunk + (buffer_size > 0 ? kChunkHeader + bin_chunk : 0);
  if (total > std::numeric_limits<std::uint32_t>::max()) {
    return Error{out.string() + ": " + std::to_string(total) +
                 " bytes is too large for a .glb (4 GiB at most); use .gltf"};
  }
  // Header, JSON chunk and BIN chunk header in one block; then the buffer and its padding.
  std::string head;
  head.reserve(kGlbHeader + 2 * kChunkHeader + json_chunk);
  PutU32(head, kGlbMagic);
  PutU32(head, kGlbVersion);
  PutU32(head, static_cast<std::uint32_t>(total));
  PutU32(head, static_cast<std::uint32_t>(json_chunk));
  PutU32(head, kJsonChunk);
  head.append(json).append(json_chunk - json.size(), ' ');
  if (buffer_size > 0) {
    PutU32(head, static_cast<std::uint32_t>(bin_chunk));
    PutU32(head, kBinChunk);
  }
  const auto produce = [&](const ByteSink& sink) {
    const std::array<unsigned char, 4> zeros{};
    return sink({reinterpret_cast<const unsigned char*>(head.data()), head.size()}) &&
           WriteBuffer(data, tail, sink) && sink({zeros.data(), bin_chunk - buffer_size});
  };
  Result<fs::path> written = WriteStreamAtomically(
      out, total, produce, [&](int fd) { return CheckGlbHeader(fd, total, json_chunk); });
  if (!written) return Error{written.error()};
  return std::vector<fs::path>{out};
}

// The file on disk has exactly `size` bytes.
std::optional<std::string> CheckWritten(const fs::path& path, std::size_t size) {
  std::error_code error;
  const std::uintmax_t on_disk = fs::file_size(path, error);
  if (error || on_disk != size) return path.string() + ": written file has the wrong size";
  return std::nullopt;
}

// Whether `name` is a .bin this writer gives the .gltf of stem `stem`: "<stem>.bin" or
// "<stem>.<n>.bin" (n decimal).
bool IsOwnBinName(std::string_view name, std::string_view stem) {
  constexpr std::string_view kTail = ".bin";
  if (name.size() < stem.size() + kTail.size() || !name.starts_with(stem) || !name.ends_with(kTail))
    return false;
  std::string_view middle = name.substr(stem.size(), name.size() - stem.size() - kTail.size());
  if (middle.empty()) return true;  // "<stem>.bin"
  if (middle.size() < 2 || middle.front() != '.') return false;
  middle.remove_prefix(1);
  return std::all_of(middle.begin(), middle.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// The name of the new .bin: "<stem>.bin", or else "<stem>.<n>.bin" for the first n from 1 with
// no such file: never a file that exists, so the old pair is untouched until the switch.
fs::path FreshBinPath(const fs::path& out) {
  fs::path bin = out;
  bin.replace_extension(".bin");
  std::error_code error;
  for (int n = 1; fs::symlink_status(bin, error).type() != fs::file_type::not_found; ++n) {
    bin = out;
    std::string extension = ".";
    extension.append(std::to_string(n)).append(".bin");
    bin.replace_extension(extension);
  }
  return bin;
}

// The .bin the existing .gltf at `out` refers to, when it is one this writer named (same
// folder, IsOwnBinName): the file to remove once the new .gltf has replaced the old one.
std::optional<fs::path> OwnBinOf(const fs::path& out) {
  Result<std::string> text = ReadInputFile(out, "glTF file");
  if (!text) return std::nullopt;
  const nlohmann::json document =
      nlohmann::json::parse(text.value(), nullptr, /*allow_exceptions=*/false);
  if (!document.is_object()) return std::nullopt;
  const auto buffers = document.find("buffers");
  if (buffers == document.end() || !buffers->is_array() || buffers->empty() ||
      !(*buffers)[0].is_object())
    return std::nullopt;
  const auto uri = (*buffers)[0].find("uri");
  if (uri == (*buffers)[0].end() || !uri->is_string()) return std::nullopt;
  const std::optional<std::string> name = UriToPath(uri->get<std::string>());
  if (!name || name->find('/') != std::string::npos || !IsOwnBinName(*name, out.stem().string()))
    return std::nullopt;
  return out.parent_path() / *name;
}

// The .gltf and its .bin switch together or not at all: the new .bin goes to a name no file
// has (FreshBinPath), the new .gltf referring to it replaces the old one atomically (the
// switch), and only then is the old .bin removed. A failure before the switch removes the new
// .bin and leaves the old pair as it was; a kill before it leaves at most the new .bin (removed
// by the signal cleanup, temp_files.h).
Result<std::vector<fs::path>> WriteGltfAndBin(tinygltf::Model model, const BufferTail& tail,
                                              const fs::path& out, const MeshoptJson& meshopt) {
  const fs::path bin_path = FreshBinPath(out);
  const std::optional<fs::path> old_bin = OwnBinOf(out);
  std::vector<unsigned char> data;
  if (!model.buffers.empty()) data = std::move(model.buffers[0].data);
  const std::size_t buffer_size = data.size() + tail.size;
  Result<std::string> text = SerializeJson(model);
  if (!text) return Error{out.string() + ": " + text.error()};
  nlohmann::json document =
      nlohmann::json::parse(text.value(), nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded()) return Error{out.string() + ": tinygltf wrote invalid JSON"};
  if (buffer_size > 0) {
    document["buffers"] = nlohmann::json::array(
        {{{"byteLength", buffer_size}, {"uri", PathToUri(bin_path.filename())}}});
    AddMeshoptJson(document, meshopt);
  }
  const std::string json = DumpJson(document, 2).append("\n");

  std::vector<fs::path> files;
  // Until the switch the new .bin is removed on SIGINT or SIGTERM like a temporary file.
  TemporaryFile new_bin(buffer_size > 0 ? bin_path : fs::path());
  if (buffer_size > 0) {
    Result<fs::path> written = WriteStreamAtomically(
        bin_path, buffer_size, [&](const ByteSink& sink) { return WriteBuffer(data, tail, sink); });
    if (!written) return Error{written.error()};
    files.push_back(bin_path);
  }
  std::error_code ignored;
  {
    // The switch and keeping the new .bin happen together: a kill between them would leave the
    // new .gltf referring to a .bin the signal cleanup removed.
    const SignalsHeld held;
    if (Result<fs::path> written = WriteFileAtomically(out, json); !written) {
      if (buffer_size > 0) fs::remove(bin_path, ignored);
      return Error{written.error()};
    }
    new_bin.Keep();
  }
  files.push_back(out);
  if (old_bin && *old_bin != bin_path) fs::remove(*old_bin, ignored);
  if (std::optional<std::string> problem = CheckWritten(out, json.size())) return Error{*problem};
  return files;
}

}  // namespace

Result<std::vector<fs::path>> WriteModel(tinygltf::Model model, const BufferTail& tail,
                                         const fs::path& out, bool binary,
                                         const MeshoptJson& meshopt) {
  return binary ? WriteGlb(std::move(model), tail, out, meshopt)
                : WriteGltfAndBin(std::move(model), tail, out, meshopt);
}

}  // namespace wirerig::gltf
