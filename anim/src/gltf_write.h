// Serializing a tinygltf model and writing it atomically: a `.glb` (JSON and BIN chunks), or a
// `.gltf` whose buffer 0 is the external "<stem>.bin" next to it. tinygltf serializes the JSON
// only (images are referenced by their URI, never re-encoded; buffers are left out of its
// serializer, which would copy them). wirerig writes the GLB container itself (glTF 2.0, "GLB
// File Format": 12-byte header, JSON chunk padded with spaces, BIN chunk padded with zeros) or
// the .bin, streaming buffer 0 from where it is: the model's in-memory data, then a tail of
// bytes produced during the write (the morph targets). Every file goes to a temporary file in
// the same folder, renamed over the target once its size (and, for a .glb, its header) is right.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

#include "wirerig/io/result.h"

namespace wirerig::gltf {

// Receives consecutive blocks of a file's bytes; returns false to stop (a write failed).
using ByteSink = std::function<bool(std::span<const unsigned char>)>;

// The part of buffer 0 after the model's in-memory data: `size` bytes that `write` hands to the
// sink in order (returning false when the sink does). The in-memory data's size must be a
// multiple of 4 when there is a tail (AlignedBufferEnd).
struct BufferTail {
  std::size_t size = 0;
  std::function<bool(const ByteSink&)> write;
};

// EXT_meshopt_compression's JSON, which tinygltf's serializer leaves out (it writes no buffer
// view extensions): the fallback buffer 1's length (0: no compression) and each compressed
// view's extension object, as JSON text (gltf_meshopt.h).
struct MeshoptJson {
  std::size_t fallback_bytes = 0;
  std::vector<std::pair<std::size_t, std::string>> views;
};

// Writes `model` (buffer 0 = its in-memory data followed by `tail`) to `out`: binary when
// `binary`, else JSON plus "<stem>.bin" (the .bin first, then the .gltf; if the .gltf cannot be
// written the new .bin is removed). A .glb over 4 GiB is refused (its lengths are 32-bit).
// With `meshopt.fallback_bytes` > 0 the JSON gets the compressed views' extensions and buffer 1,
// the extension's fallback buffer of that length with no data. Returns the files written.
Result<std::vector<std::filesystem::path>> WriteModel(tinygltf::Model model, const BufferTail& tail,
                                                      const std::filesystem::path& out, bool binary,
                                                      const MeshoptJson& meshopt = {});

}  // namespace wirerig::gltf
