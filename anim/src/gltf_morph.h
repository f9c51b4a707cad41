// Morph targets, one per key, and the `weights` animation that shows target k at key k.
//
// The targets are most of an animated file (#K x #V x 24 bytes as float), so they are never
// built in memory as a whole: their deltas come from a DeltaSource, key by key, once to find
// every accessor's min/max (and whether a key can be quantized) while the model is built, and
// once more while the file is written, straight into the output in blocks of a few megabytes
// (StreamedTargets). Their buffer views come after buffer 0's in-memory data. Both passes use
// up to two threads; the bytes do not depend on the thread count.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace wirerig::gltf {

// Fills the deltas of target `key` against the base: `positions` and `normals`, #V x 3 each
// (`normals` is empty when the targets have none). Called from several threads at once for
// different keys; must give the same values every time.
using DeltaSource =
    std::function<void(std::size_t key, std::span<float> positions, std::span<float> normals)>;

struct MorphTargetSet {
  std::size_t key_count = 0;         // targets (one per key in morph mode)
  std::string name_prefix = "key_";  // target k is named name_prefix + k
  std::size_t vertex_count = 0;
  bool normals = false;
  // Every POSITION delta is a multiple of 1 / 127 in [-1, 1] (the caller rounded them: corrective
  // shapes scaled into their weights): stored as normalized signed bytes, 4 per vertex
  // (KHR_mesh_quantization), exactly.
  bool byte_positions = false;
  DeltaSource deltas;
};

// KHR_mesh_quantization for morph targets. A key's POSITION deltas are stored as normalized
// signed shorts (value = round(d * 32767) / 32767, padded to an 8-byte stride as vertex
// attributes must be 4-byte aligned) when every component lies in [-1, 1] m and the rounding
// bound sqrt(3) / 2 / 32767 m = 2.6e-5 m per vertex is at most `max_position_error`; its NORMAL
// deltas likewise when every component lies in [-1, 1] (rounding at most 1.5e-5 per component).
// Otherwise that key's accessor stays float.
struct MorphQuantization {
  bool enabled = false;
  double max_position_error = 0.0;  // m
};

// The targets' bytes, produced key by key while the file is written.
class StreamedTargets {
 public:
  using Sink = std::function<bool(std::span<const unsigned char>)>;

  StreamedTargets() = default;
  StreamedTargets(MorphTargetSet set, std::vector<bool> quantized_positions,
                  std::vector<bool> quantized_normals);

  std::size_t Size() const { return size_; }
  // Produces every target's bytes in buffer order, in blocks of whole keys (up to ~4 MB),
  // handing each block to `sink`; stops and returns false as soon as `sink` does.
  bool Write(const Sink& sink) const;

  // Bytes of one key's position (or normal) block.
  std::size_t PositionBytes(std::size_t key) const;
  std::size_t NormalBytes(std::size_t key) const;
  // Shorts, or bytes (MorphTargetSet::byte_positions).
  bool PositionsQuantized(std::size_t key) const {
    return set_.byte_positions || quantized_positions_[key];
  }
  bool PositionsInBytes() const { return set_.byte_positions; }
  bool NormalsQuantized(std::size_t key) const { return set_.normals && quantized_normals_[key]; }

 private:
  // The bytes of keys [first, last) into `out` (held as floats: every part is 4-byte sized).
  void EncodeKeys(std::size_t first, std::size_t last, std::vector<float>& scratch,
                  std::vector<float>& out) const;

  MorphTargetSet set_;
  std::vector<bool> quantized_positions_;
  std::vector<bool> quantized_normals_;
  std::size_t size_ = 0;
};

struct MorphTargetsAdded {
  StreamedTargets stream;
  std::size_t quantized_position_targets = 0;  // as shorts or bytes
  std::size_t quantized_normal_targets = 0;
  double quantization_max_error = 0.0;  // m: bound of the position rounding, when quantized
};

// Adds `set.key_count` morph targets to every primitive of mesh `mesh_index`, all primitives
// sharing the same accessors (POSITION with min/max as glTF requires; NORMAL when the set has
// normals), with views after buffer 0's in-memory data: nothing may be appended to buffer 0
// afterwards. Sets the mesh's default weights (all 0) and its extras.targetNames (name_prefix + k);
// adds KHR_mesh_quantization to extensionsUsed and extensionsRequired when a key is quantized.
MorphTargetsAdded AddMorphTargets(tinygltf::Model& model, int mesh_index, MorphTargetSet set,
                                  const MorphQuantization& quantization);

// Adds to `animation` a LINEAR sampler on `time_accessor` (#K key times) and a channel animating
// the `weights` of `node`: at key k weight k is 1 and the others 0, so between keys k and k + 1
// the mesh blends linearly from target k to target k + 1.
void AddKeyWeightsChannel(tinygltf::Model& model, tinygltf::Animation& animation, int node,
                          int time_accessor, std::size_t key_count);

// The same with any weights: #K x #targets values, key-major.
void AddWeightsChannel(tinygltf::Model& model, tinygltf::Animation& animation, int node,
                       int time_accessor, const std::vector<float>& weights);

}  // namespace wirerig::gltf
