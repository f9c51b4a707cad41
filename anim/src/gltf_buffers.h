// Appending binary data to a tinygltf model: every accessor gets its own buffer view in the
// model's single buffer (buffer 0), 4-byte aligned, so accessors of any component type are
// aligned as glTF requires. Buffer 0's `data` holds the bytes built in memory; morph targets
// reserve views after them (AddReservedView) whose bytes are produced while the file is written.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include <tiny_gltf.h>

namespace wirerig::gltf {

// Float accessor of `values.size() / components` elements; `type` is TINYGLTF_TYPE_SCALAR,
// VEC2, VEC3, VEC4 or MAT4 (components 1, 2, 3, 4, 16). `target` is
// TINYGLTF_TARGET_ARRAY_BUFFER for vertex attributes, 0 for animation and skin data. With
// `min_max`, the per-component min and max of the values are stored (glTF requires them for
// POSITION and animation inputs). Returns the accessor's index.
int AddFloatAccessor(tinygltf::Model& model, std::span<const float> values, int type, int target,
                     bool min_max);

// Triangle indices (#F x 3 flat), as unsigned short when every index fits, else unsigned int.
int AddIndexAccessor(tinygltf::Model& model, std::span<const std::uint32_t> indices,
                     std::uint32_t vertex_count);

// Unsigned VEC4 joint indices (#V x 4 flat), as unsigned byte when joint_count <= 256, else
// unsigned short (joint_count <= 65536).
int AddJointAccessor(tinygltf::Model& model, std::span<const std::uint16_t> joints,
                     std::size_t joint_count);

// What a normalized short stores: value = q / kShortScale (signed), q / kUnsignedShortScale.
inline constexpr double kShortScale = 32767.0;
// A normalized signed byte: value = max(q / kByteScale, -1).
inline constexpr double kByteScale = 127.0;
inline constexpr double kUnsignedShortScale = 65535.0;

// Normalized 16-bit accessor (#values / components elements, components from `type`): signed
// shorts (value = max(q / 32767, -1)) or unsigned (value = q / 65535), as glTF allows for
// rotation keys and WEIGHTS_0 without any extension.
int AddNormalizedShortAccessor(tinygltf::Model& model, std::span<const std::int16_t> values,
                               int type, int target);
int AddNormalizedShortAccessor(tinygltf::Model& model, std::span<const std::uint16_t> values,
                               int type, int target);
// Normalized unsigned bytes (value = q / 255), as glTF allows for WEIGHTS_n and TEXCOORD_n
// without any extension.
inline constexpr double kUnsignedByteScale = 255.0;
int AddNormalizedByteAccessor(tinygltf::Model& model, std::span<const std::uint8_t> values,
                              int type, int target);

// Appends `size` bytes to buffer 0 (created when missing) at a 4-byte aligned offset, as a new
// view with `target` (0: none). Returns the view's index.
int AddBufferView(tinygltf::Model& model, const void* bytes, std::size_t size, int target);

// A view of `bytes` in buffer 0 (an embedded image: no target). Returns the view's index.
int AddBytesView(tinygltf::Model& model, std::span<const unsigned char> bytes);

// KHR_mesh_quantization: attributes and morph targets stored as normalized integers.
inline constexpr const char* kMeshQuantization = "KHR_mesh_quantization";

// Adds `name` to the model's extensionsUsed and extensionsRequired, once.
void RequireExtension(tinygltf::Model& model, const std::string& name);

// Unit vectors (#values / 3 of them) as normalized signed bytes, each padded to 4 bytes (a view
// with byteStride 4, as vertex attributes need): value = max(q / 127, -1). Needs
// KHR_mesh_quantization (required by this call).
int AddNormalizedByteVec3Accessor(tinygltf::Model& model, std::span<const float> values,
                                  int target);

// `size` rounded up to a multiple of 4 (glTF's alignment of views and GLB chunks).
inline std::size_t Padded4(std::size_t size) { return (size + 3) / 4 * 4; }

// `value` for a JSON number: the double nearest the float's shortest decimal, which prints in at
// most 9 significant digits and reads back as the same float (the float itself, as a double,
// prints in up to 17).
double JsonFloat(float value);

// Pads buffer 0's in-memory data (created when missing) to a multiple of 4 bytes and returns
// its size: the offset at which reserved views may start.
std::size_t AlignedBufferEnd(tinygltf::Model& model);

// A view of `size` bytes at byte `offset` of buffer 0 that its in-memory data does not hold
// (streamed when the file is written). `stride` 0: tightly packed.
int AddReservedView(tinygltf::Model& model, std::size_t offset, std::size_t size,
                    std::size_t stride, int target);

// An accessor of `count` elements on `view`, from its byte `byte_offset` (a multiple of the
// component size; several accessors may share a view that is not a vertex attribute's).
int AddAccessor(tinygltf::Model& model, int view, int component_type, int type, std::size_t count,
                bool normalized = false, std::size_t byte_offset = 0);

}  // namespace wirerig::gltf
