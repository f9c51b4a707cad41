// EXT_meshopt_compression (GltfExportOptions::compress): every buffer view of the finished model
// is encoded with meshoptimizer's codecs (triangle indices with the index codec, everything else
// with the vertex codec) into buffer 0, while the views point into a fallback buffer 1 that holds
// no data, as the extension asks. Float data that tolerates rounding (UVs, corrective deltas,
// translation keys, float rest positions) is first rounded the way the EXPONENTIAL filter stores it
// (RoundLikeExpFilter), before anything is fitted to or measured on it, so every error the export
// reports is the decoded file's; the filter then stores it with no further loss. Rotation keys
// (normalized shorts) are rounded likewise for the QUATERNION filter (RoundLikeQuatFilter), rest
// normals (normalized bytes) for the OCTAHEDRAL filter (RoundLikeOctFilter). Rest positions are
// normalized shorts (QuantizePositions), stored by the codec with no filter, except beside
// residual targets (float, EXPONENTIAL).
#pragma once

#include <cstddef>
#include <span>

#include <tiny_gltf.h>
#include <Eigen/Geometry>

#include "gltf_morph.h"
#include "gltf_write.h"

namespace wirerig::gltf {

// Mantissa bits the EXPONENTIAL filter keeps (a vector's components share the exponent of its
// largest): relative precision 2^(1 - bits) of that component.
inline constexpr int kPositionBits = 16;  // float rest positions (beside residual targets)
inline constexpr int kUvBits = 12;        // within 2.5e-4 of the texture (gltfpack's default)
inline constexpr int kDeltaBits = 10;     // a 2 cm corrective delta: within 2e-5 m
// Translation keys: each joint's bits chosen so that its keys are stored within
// kTranslationPrecision (ExpFilterBits), at most kTranslationBits (the filter's maximum).
inline constexpr double kTranslationPrecision = 4e-5;  // m
inline constexpr int kTranslationBits = 24;
// Bits of the OCTAHEDRAL filter for the rest normals, stored as normalized signed bytes: within
// about a degree (lighting only; no error the export reports depends on them).
inline constexpr int kOctahedralBits = 8;
// Bits per component the QUATERNION filter keeps (the largest component is rebuilt from the
// other three, each within 2^-(bits-1) / sqrt(2)): 16, about the precision of the normalized
// shorts an uncompressed file stores.
inline constexpr int kRotationBits = 16;

// Rounds `values` (vectors of `components` floats, 1 to 4) to what the EXPONENTIAL filter with
// `bits` mantissa bits stores and a reader decodes (meshoptimizer's own encoder and decoder),
// repeated until the filter gives the values back unchanged.
void RoundLikeExpFilter(std::span<float> values, std::size_t components, int bits);

// The fewest mantissa bits (1 to `most`) with which the EXPONENTIAL filter stores vectors
// whose largest component magnitude is at most `largest` within `precision` (both m).
int ExpFilterBits(double largest, double precision, int most);

// The unit quaternion `q` (x, y, z, w) as the QUATERNION filter with `bits` per component stores
// it and a reader decodes it (normalized signed shorts, meshoptimizer's own encoder and
// decoder; the sign may flip, the rotation does not).
Eigen::Quaternionf RoundLikeQuatFilter(const Eigen::Quaternionf& q, int bits);

// Unit vectors (x, y, z, #values / 3 of them) rounded to what the OCTAHEDRAL filter with
// `bits` stores in normalized signed bytes and a reader decodes (meshoptimizer's own encoder
// and decoder), repeated until the filter gives them back unchanged.
void RoundLikeOctFilter(std::span<float> values, int bits);

// Compresses every view of `model`, whose buffer 0 is its in-memory data followed by `tail`'s
// bytes, into a new buffer 0; views keep their byte ranges in the fallback buffer 1 and carry
// the extension (mode, count, byteStride, and the EXPONENTIAL filter where the data is rounded
// for it). Views no accessor reads (embedded images) are copied into buffer 0 as they are.
// Adds EXT_meshopt_compression to extensionsUsed and extensionsRequired. Returns what the writer
// adds to the JSON: the fallback buffer's byte length (the uncompressed size) and the views'
// extension objects.
MeshoptJson CompressBuffers(tinygltf::Model& model, const StreamedTargets& tail);

}  // namespace wirerig::gltf
