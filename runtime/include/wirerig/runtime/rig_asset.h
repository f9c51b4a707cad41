// The built rig as a runtime asset (.wrig): everything the evaluation needs (the RigModel) and
// the source asset's vertex order, in a versioned, endian-defined binary image with a checksum.
// The offline tools write it (`wirerig build`); an engine reads the file's bytes with its own
// file system and parses them here, with no Assimp, CGAL, JSON or glTF code (the runtime does
// no I/O).
//
// Layout (all integers little-endian, reals IEEE-754 binary64 little-endian):
//   bytes 0-3    magic "WRIG"
//   bytes 4-7    u32 format version (kRigAssetVersion)
//   bytes 8-15   u64 payload size in bytes
//   bytes 16-19  u32 CRC-32 (IEEE 802.3, as zlib's crc32) of the payload
//   bytes 20-    the payload: the parts, the vertex attachments, the triangles and the vertex
//                order, each array preceded by its u32 element count (rig_asset.cpp).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "wirerig/runtime/rig_model.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

// 2: JointModel::growth_scale; 3: a vertex's joint influences as a count and those in use;
// 4: a pair binding's beta and gamma in section units (skin_binding.h, SectionUnit);
// 5: JointModel::growth_scales per bend direction.
inline constexpr std::uint32_t kRigAssetVersion = 5;
inline constexpr std::size_t kRigAssetHeaderSize = 20;

struct RigAsset {
  RigModel model;
  // The source asset's vertex order: output vertex i is welded vertex vertex_order[i]
  // (EvaluateRigJob::float_vertex_order). Empty: the welded order.
  std::vector<std::uint32_t> vertex_order;
};

// The asset's bytes. The model should pass ValidateRigModel.
std::vector<std::uint8_t> SerializeRigAsset(const RigAsset& asset);

// Parses and validates bytes made by SerializeRigAsset. Refuses, naming the field: a wrong magic,
// a version this runtime does not read, a size or checksum that does not match, a count larger
// than the bytes left, and any model that fails ValidateRigModel. On failure *out is unchanged.
// Allocates (it is a load, not a frame).
Status ParseRigAsset(std::span<const std::uint8_t> bytes, RigAsset* out);

// Whether a model is safe to evaluate: parents before children, every index in range (parents,
// profiles, wire points, joints, spine samples, triangle corners), at least two spine samples and
// two profiles per part with one frame per sample, finite numbers, valid joints.
Status ValidateRigModel(const RigModel& model);

// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320), as zlib's crc32(0, data, size).
std::uint32_t Crc32(std::span<const std::uint8_t> data);

}  // namespace wirerig
