#include "gltf_write.h"

#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <system_error>

#include <nlohmann/json.hpp>

#include "gltf_paths.h"
#include "wirerig/rig/atomic_file.h"

namespace wirerig::gltf {
namespace {

namespace fs = std::filesystem;

Result<std::string> Serialize(const tinygltf::Model& model, bool binary) {
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(nullptr, nullptr);  // keep every image's URI; never re-encode
  std::ostringstream stream;
  if (!writer.WriteGltfSceneToStream(&model, stream, /*prettyPrint=*/!binary, binary) || !stream) {
    return Error{"tinygltf could not serialize the model"};
  }
  return stream.str();
}

std::uint32_t ReadU32(const std::string& bytes, std::size_t offset) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;  // glTF is little-endian, as is every platform wirerig builds on
}

// A .glb: header "glTF", version 2, total length, then a JSON chunk and a BIN chunk of the buffer.
std::optional<std::string> CheckGlb(const std::string& bytes, std::size_t buffer_size) {
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0 || ReadU32(bytes, 4) != 2 ||
      ReadU32(bytes, 8) != bytes.size()) {
    return "tinygltf wrote no valid GLB header";
  }
  const std::size_t bin = 20 + std::size_t{ReadU32(bytes, 12)};
  if (buffer_size > 0 && (bin + 8 > bytes.size() || ReadU32(bytes, bin) < buffer_size ||
                          ReadU32(bytes, bin + 4) != 0x004E4942u)) {
    return "tinygltf wrote no BIN chunk holding the buffer";
  }
  return std::nullopt;
}

// The file on disk has exactly `size` bytes.
std::optional<std::string> CheckWritten(const fs::path& path, std::size_t size) {
  std::error_code error;
  const std::uintmax_t on_disk = fs::file_size(path, error);
  if (error || on_disk != size) return path.string() + ": written file has the wrong size";
  return std::nullopt;
}

Result<std::vector<fs::path>> WriteGlb(const tinygltf::Model& model, const fs::path& out) {
  Result<std::string> bytes = Serialize(model, true);
  if (!bytes) return Error{out.string() + ": " + bytes.error()};
  const std::size_t buffer_size = model.buffers.empty() ? 0 : model.buffers[0].data.size();
  if (auto problem = CheckGlb(bytes.value(), buffer_size))
    return Error{out.string() + ": " + *problem};
  if (Result<fs::path> written = WriteFileAtomically(out, bytes.value()); !written) {
    return Error{written.error()};
  }
  if (auto problem = CheckWritten(out, bytes.value().size())) {
    std::error_code ignored;
    fs::remove(out, ignored);
    return Error{*problem};
  }
  return std::vector<fs::path>{out};
}

Result<std::vector<fs::path>> WriteGltfAndBin(tinygltf::Model model, const fs::path& out) {
  fs::path bin_path = out;
  bin_path.replace_extension(".bin");
  std::string bin;
  if (!model.buffers.empty()) {
    bin.assign(model.buffers[0].data.begin(), model.buffers[0].data.end());
    model.buffers[0].data.clear();  // serialized below as a URI, not embedded
  }
  Result<std::string> text = Serialize(model, false);
  if (!text) return Error{out.string() + ": " + text.error()};
  nlohmann::json document =
      nlohmann::json::parse(text.value(), nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded()) return Error{out.string() + ": tinygltf wrote invalid JSON"};
  if (!bin.empty()) {
    document["buffers"] = nlohmann::json::array(
        {{{"byteLength", bin.size()}, {"uri", PathToUri(bin_path.filename())}}});
  }
  const std::string json = document.dump(2).append("\n");

  std::vector<fs::path> files;
  if (!bin.empty()) {
    if (Result<fs::path> written = WriteFileAtomically(bin_path, bin); !written) {
      return Error{written.error()};
    }
    files.push_back(bin_path);
  }
  std::optional<std::string> problem;
  if (Result<fs::path> written = WriteFileAtomically(out, json); !written) {
    problem = written.error();
  } else {
    files.push_back(out);
  }
  for (const fs::path& file : files) {
    if (problem) break;
    problem = CheckWritten(file, file == out ? json.size() : bin.size());
  }
  if (problem) {
    std::error_code ignored;
    for (const fs::path& file : files) fs::remove(file, ignored);
    return Error{*problem};
  }
  return files;
}

}  // namespace

Result<std::vector<fs::path>> WriteModel(const tinygltf::Model& model, const fs::path& out,
                                         bool binary) {
  return binary ? WriteGlb(model, out) : WriteGltfAndBin(model, out);
}

}  // namespace wirerig::gltf
