// Serializing a tinygltf model and writing it atomically: a `.glb` (JSON and BIN chunks), or a
// `.gltf` whose buffer 0 is the external "<stem>.bin" next to it. tinygltf serializes into
// memory (images are referenced by their URI, never re-encoded); wirerig writes the files with
// WriteFileAtomically and checks the bytes on disk.
#pragma once

#include <filesystem>
#include <vector>

#include <tiny_gltf.h>

#include "wirerig/rig/result.h"

namespace wirerig::gltf {

// Writes `model` (its buffer 0 holds all binary data) to `out`: binary when `binary`, else JSON
// plus "<stem>.bin" (the .bin first, then the .gltf; if the .gltf cannot be written the new
// .bin is removed). Returns the files written.
Result<std::vector<std::filesystem::path>> WriteModel(const tinygltf::Model& model,
                                                      const std::filesystem::path& out,
                                                      bool binary);

}  // namespace wirerig::gltf
