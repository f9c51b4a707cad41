#include "gltf_morph.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "gltf_buffers.h"

namespace wirerig::gltf {
namespace {

constexpr std::size_t kFloatStride = 3 * sizeof(float);         // 12 bytes
constexpr std::size_t kShortStride = 4 * sizeof(std::int16_t);  // 8: 4-byte aligned
constexpr std::size_t kByteStride = 4;                          // 3 bytes padded to 4
constexpr std::size_t kBlockBytes = std::size_t{4} << 20;       // write blocks, ~4 MB

// Threads for `jobs` independent jobs: up to 2 (the machines wirerig runs on share few cores).
std::size_t ThreadCount(std::size_t jobs) {
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  return std::max<std::size_t>(1, std::min({cores, std::size_t{2}, jobs}));
}

// Normalized signed short of a value in [-1, 1] (to nearest, halves away from zero; exact in
// double: a float times 32767 needs 39 bits). glTF decodes it as max(q / 32767, -1).
std::int16_t ToShort(float value) {
  const double scaled = static_cast<double>(value) * kShortScale;
  return static_cast<std::int16_t>(scaled + (scaled >= 0.0 ? 0.5 : -0.5));
}

// Normalized signed byte of a multiple of 1/127 in [-1, 1] (MorphTargetSet::byte_positions).
std::int8_t ToByte(float value) {
  return static_cast<std::int8_t>(std::lround(static_cast<double>(value) * kByteScale));
}

// Largest rounding of a vertex whose three components are rounded to shorts (half a step each).
const double kShortRounding = std::sqrt(3.0) * 0.5 / kShortScale;

// One key's deltas, measured: per-component range of the positions, largest normal component.
struct KeyStats {
  std::array<float, 3> low{};
  std::array<float, 3> high{};
  float normal_magnitude = 0.0f;  // max |component|
};

KeyStats MeasureKey(std::span<const float> positions, std::span<const float> normals) {
  // Four vertices (12 values) per step in separate lanes, so that the loop vectorizes.
  constexpr std::size_t kLanes = 12;
  std::array<float, kLanes> low;
  std::array<float, kLanes> high;
  low.fill(std::numeric_limits<float>::max());
  high.fill(std::numeric_limits<float>::lowest());
  const std::size_t whole = positions.size() / kLanes * kLanes;
  for (std::size_t i = 0; i < whole; i += kLanes) {
    for (std::size_t j = 0; j < kLanes; ++j) {
      low[j] = std::min(low[j], positions[i + j]);
      high[j] = std::max(high[j], positions[i + j]);
    }
  }
  for (std::size_t i = whole; i < positions.size(); ++i) {
    low[i - whole] = std::min(low[i - whole], positions[i]);
    high[i - whole] = std::max(high[i - whole], positions[i]);
  }
  KeyStats stats;
  stats.low.fill(std::numeric_limits<float>::max());
  stats.high.fill(std::numeric_limits<float>::lowest());
  for (std::size_t j = 0; j < kLanes; ++j) {
    stats.low[j % 3] = std::min(stats.low[j % 3], low[j]);
    stats.high[j % 3] = std::max(stats.high[j % 3], high[j]);
  }
  float magnitude = 0.0f;
  for (float n : normals) magnitude = std::max(magnitude, std::abs(n));
  stats.normal_magnitude = magnitude;
  return stats;
}

bool FitsShorts(const KeyStats& stats) {
  for (std::size_t c = 0; c < 3; ++c) {
    if (stats.low[c] < -1.0f || stats.high[c] > 1.0f) return false;
  }
  return true;
}

// Runs job(thread, first, last) over [0, count) split into one contiguous range per thread.
template <typename Job>
void ParallelRanges(std::size_t count, std::size_t threads, const Job& job) {
  if (threads <= 1) {
    job(std::size_t{0}, std::size_t{0}, count);
    return;
  }
  std::vector<std::thread> workers;
  const std::size_t per_thread = (count + threads - 1) / threads;
  for (std::size_t t = 1; t < threads; ++t) {
    const std::size_t first = std::min(count, t * per_thread);
    const std::size_t last = std::min(count, first + per_thread);
    workers.emplace_back([&job, t, first, last] { job(t, first, last); });
  }
  job(std::size_t{0}, std::size_t{0}, std::min(count, per_thread));
  for (std::thread& worker : workers) worker.join();
}

std::span<const unsigned char> AsBytes(const std::vector<float>& block) {
  return {reinterpret_cast<const unsigned char*>(block.data()), block.size() * sizeof(float)};
}

}  // namespace

StreamedTargets::StreamedTargets(MorphTargetSet set, std::vector<bool> quantized_positions,
                                 std::vector<bool> quantized_normals)
    : set_(std::move(set)),
      quantized_positions_(std::move(quantized_positions)),
      quantized_normals_(std::move(quantized_normals)) {
  for (std::size_t k = 0; k < set_.key_count; ++k) size_ += PositionBytes(k) + NormalBytes(k);
}

std::size_t StreamedTargets::PositionBytes(std::size_t key) const {
  if (set_.byte_positions) return set_.vertex_count * kByteStride;
  return set_.vertex_count * (quantized_positions_[key] ? kShortStride : kFloatStride);
}

std::size_t StreamedTargets::NormalBytes(std::size_t key) const {
  if (!set_.normals) return 0;
  return set_.vertex_count * (quantized_normals_[key] ? kShortStride : kFloatStride);
}

void StreamedTargets::EncodeKeys(std::size_t first, std::size_t last, std::vector<float>& scratch,
                                 std::vector<float>& out) const {
  std::size_t bytes = 0;
  for (std::size_t k = first; k < last; ++k) bytes += PositionBytes(k) + NormalBytes(k);
  out.resize(bytes / sizeof(float));  // every block is a multiple of 4 bytes
  const std::size_t values = set_.vertex_count * 3;
  scratch.resize(2 * values);
  // Float deltas go straight to their place in `out`; quantized ones through `scratch`.
  // Quantized: all values to shorts in one flat (vectorizable) loop, then spread to 4 per vertex.
  std::vector<std::int16_t> flat(values);
  std::vector<std::int16_t> padded(set_.vertex_count * 4, 0);
  const auto pack = [&](std::span<const float> from, float* to) {
    for (std::size_t i = 0; i < values; ++i) flat[i] = ToShort(from[i]);
    for (std::size_t v = 0; v < set_.vertex_count; ++v) {
      for (std::size_t c = 0; c < 3; ++c) padded[v * 4 + c] = flat[v * 3 + c];
    }
    std::memcpy(to, padded.data(), padded.size() * sizeof(std::int16_t));
  };
  std::vector<std::int8_t> bytes_out(set_.byte_positions ? set_.vertex_count * 4 : 0, 0);
  const auto pack_bytes = [&](std::span<const float> from, float* to) {
    for (std::size_t v = 0; v < set_.vertex_count; ++v) {
      for (std::size_t c = 0; c < 3; ++c) bytes_out[v * 4 + c] = ToByte(from[v * 3 + c]);
    }
    std::memcpy(to, bytes_out.data(), bytes_out.size());
  };
  float* cursor = out.data();
  for (std::size_t k = first; k < last; ++k) {
    float* normals_at = cursor + PositionBytes(k) / sizeof(float);
    const std::span<float> positions(PositionsQuantized(k) ? scratch.data() : cursor, values);
    std::span<float> normals;
    if (set_.normals) {
      normals =
          std::span<float>(NormalsQuantized(k) ? scratch.data() + values : normals_at, values);
    }
    set_.deltas(k, positions, normals);
    if (PositionsInBytes()) {
      pack_bytes(positions, cursor);
    } else if (PositionsQuantized(k)) {
      pack(positions, cursor);
    }
    if (NormalsQuantized(k)) pack(normals, normals_at);
    cursor = normals_at + NormalBytes(k) / sizeof(float);
  }
}

bool StreamedTargets::Write(const Sink& sink) const {
  // Blocks of whole keys, in order.
  std::vector<std::pair<std::size_t, std::size_t>> blocks;
  const std::size_t key_bytes = std::max<std::size_t>(1, 2 * set_.vertex_count * kFloatStride);
  const std::size_t keys_per_block = std::max<std::size_t>(1, kBlockBytes / key_bytes);
  for (std::size_t k = 0; k < set_.key_count; k += keys_per_block) {
    blocks.emplace_back(k, std::min(set_.key_count, k + keys_per_block));
  }
  if (ThreadCount(blocks.size()) <= 1) {
    std::vector<float> scratch;
    std::vector<float> block;
    for (const auto& [first, last] : blocks) {
      EncodeKeys(first, last, scratch, block);
      if (!sink(AsBytes(block))) return false;
    }
    return true;
  }
  // Two slots: a producer thread encodes block b into slot b % 2 while this thread hands the
  // previous block to the sink.
  std::array<std::vector<float>, 2> slots;
  std::array<std::size_t, 2> filled{};  // block index + 1 held by each slot, 0 when free
  bool stop = false;
  std::mutex mutex;
  std::condition_variable changed;
  std::thread producer([&] {
    std::vector<float> scratch;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const std::size_t slot = b % 2;
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return stop || filled[slot] == 0; });
        if (stop) return;
      }
      EncodeKeys(blocks[b].first, blocks[b].second, scratch, slots[slot]);
      {
        std::lock_guard lock(mutex);
        filled[slot] = b + 1;
      }
      changed.notify_all();
    }
  });
  bool ok = true;
  for (std::size_t b = 0; b < blocks.size() && ok; ++b) {
    const std::size_t slot = b % 2;
    {
      std::unique_lock lock(mutex);
      changed.wait(lock, [&] { return filled[slot] == b + 1; });
    }
    ok = sink(AsBytes(slots[slot]));
    {
      std::lock_guard lock(mutex);
      filled[slot] = 0;
      stop = !ok;
    }
    changed.notify_all();
  }
  producer.join();
  return ok;
}

MorphTargetsAdded AddMorphTargets(tinygltf::Model& model, int mesh_index, MorphTargetSet set,
                                  const MorphQuantization& quantization) {
  const std::size_t keys = set.key_count;
  const std::size_t values = set.vertex_count * 3;

  // Pass 1: measure every key (ranges per thread; the results are per key).
  std::vector<KeyStats> stats(keys);
  const std::size_t threads = ThreadCount(keys);
  ParallelRanges(keys, threads, [&](std::size_t, std::size_t first, std::size_t last) {
    std::vector<float> positions(values);
    std::vector<float> normals(set.normals ? values : 0);
    for (std::size_t k = first; k < last; ++k) {
      set.deltas(k, positions, normals);
      stats[k] = MeasureKey(positions, normals);
    }
  });

  MorphTargetsAdded added;
  std::vector<bool> quantized_positions(keys, false);
  std::vector<bool> quantized_normals(keys, false);
  if (set.byte_positions) {
    added.quantized_position_targets = keys;
  }
  for (std::size_t k = 0; k < keys; ++k) {
    if (!quantization.enabled) break;
    quantized_positions[k] = !set.byte_positions && set.vertex_count > 0 && FitsShorts(stats[k]) &&
                             kShortRounding <= quantization.max_position_error;
    quantized_normals[k] = set.normals && stats[k].normal_magnitude <= 1.0f;
    if (quantized_positions[k]) {
      ++added.quantized_position_targets;
      added.quantization_max_error = kShortRounding;
    }
    if (quantized_normals[k]) ++added.quantized_normal_targets;
  }
  if (added.quantized_position_targets + added.quantized_normal_targets > 0) {
    RequireExtension(model, kMeshQuantization);
  }

  // Views and accessors, key after key (POSITION then NORMAL), after the in-memory data.
  const int target = TINYGLTF_TARGET_ARRAY_BUFFER;
  const std::size_t vertices = set.vertex_count;
  const bool normals = set.normals;
  const bool in_bytes = set.byte_positions;
  added.stream =
      StreamedTargets(std::move(set), std::move(quantized_positions), std::move(quantized_normals));
  const StreamedTargets& stream = added.stream;
  std::size_t offset = AlignedBufferEnd(model);
  std::vector<std::map<std::string, int>> targets(keys);
  std::vector<tinygltf::Value> names;
  const auto add = [&](std::size_t bytes, bool quantized, bool in_bytes_here) {
    const int view = AddReservedView(
        model, offset, bytes, in_bytes_here ? kByteStride : (quantized ? kShortStride : 0), target);
    offset += bytes;
    const int type = in_bytes_here ? TINYGLTF_COMPONENT_TYPE_BYTE
                     : quantized   ? TINYGLTF_COMPONENT_TYPE_SHORT
                                   : TINYGLTF_COMPONENT_TYPE_FLOAT;
    return AddAccessor(model, view, type, TINYGLTF_TYPE_VEC3, vertices, quantized);
  };
  // min/max in the stored values (bytes, shorts or floats), as glTF asks.
  const auto stored = [&](float value, bool quantized) {
    if (in_bytes) return static_cast<double>(ToByte(value));
    return quantized ? static_cast<double>(ToShort(value)) : static_cast<double>(value);
  };
  for (std::size_t k = 0; k < keys; ++k) {
    const bool quantized = stream.PositionsQuantized(k);
    const int position = add(stream.PositionBytes(k), quantized, in_bytes);
    tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(position)];
    for (std::size_t c = 0; c < 3; ++c) {
      accessor.minValues.push_back(stored(stats[k].low[c], quantized));
      accessor.maxValues.push_back(stored(stats[k].high[c], quantized));
    }
    targets[k]["POSITION"] = position;
    if (normals) {
      targets[k]["NORMAL"] = add(stream.NormalBytes(k), stream.NormalsQuantized(k), false);
    }
    names.emplace_back(set.name_prefix + std::to_string(k));
  }

  tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(mesh_index)];
  for (tinygltf::Primitive& primitive : mesh.primitives) primitive.targets = targets;
  mesh.weights.assign(keys, 0.0);
  tinygltf::Value::Object extras;
  extras["targetNames"] = tinygltf::Value(std::move(names));
  mesh.extras = tinygltf::Value(std::move(extras));
  return added;
}

void AddKeyWeightsChannel(tinygltf::Model& model, tinygltf::Animation& animation, int node,
                          int time_accessor, std::size_t key_count) {
  std::vector<float> weights(key_count * key_count, 0.0f);
  for (std::size_t k = 0; k < key_count; ++k) weights[k * key_count + k] = 1.0f;
  AddWeightsChannel(model, animation, node, time_accessor, weights);
}

void AddWeightsChannel(tinygltf::Model& model, tinygltf::Animation& animation, int node,
                       int time_accessor, const std::vector<float>& weights) {
  tinygltf::AnimationSampler sampler;
  sampler.input = time_accessor;
  sampler.output = AddFloatAccessor(model, weights, TINYGLTF_TYPE_SCALAR, 0, false);
  sampler.interpolation = "LINEAR";
  animation.samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
  channel.target_node = node;
  channel.target_path = "weights";
  animation.channels.push_back(channel);
}

}  // namespace wirerig::gltf
