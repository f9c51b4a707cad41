#include "gltf_meshopt.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "gltf_buffers.h"

namespace wirerig::gltf {
namespace {

constexpr const char* kExtension = "EXT_meshopt_compression";

// A filter a view's role allows, with its bits.
enum class Filter { kNone, kExponential, kQuaternion, kOctahedral };
struct FilterUse {
  Filter filter = Filter::kNone;
  int bits = 0;
};

// How a view is read: its first accessor's element size, and the filter its role allows.
struct ViewUse {
  std::size_t element = 0;  // bytes per element
  FilterUse filter;
};

// Whether a view of elements of `element` bytes read by `accessor` has the layout `filter` takes:
// floats packed tightly (EXPONENTIAL), normalized shorts x 4 (QUATERNION), normalized bytes
// padded to 4 (OCTAHEDRAL).
bool FilterFits(Filter filter, const tinygltf::Accessor& accessor, std::size_t element,
                bool strided) {
  switch (filter) {
    case Filter::kExponential:
      return accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && !strided;
    case Filter::kQuaternion:
      return accessor.componentType == TINYGLTF_COMPONENT_TYPE_SHORT && accessor.normalized &&
             element == 8;
    case Filter::kOctahedral:
      return accessor.componentType == TINYGLTF_COMPONENT_TYPE_BYTE && accessor.normalized &&
             element == 4;
    case Filter::kNone:
      break;
  }
  return false;
}

std::map<int, ViewUse> ViewUses(const tinygltf::Model& model) {
  std::map<int, FilterUse> wanted;  // by accessor: the filter its role allows
  for (const tinygltf::Mesh& mesh : model.meshes) {
    for (const tinygltf::Primitive& primitive : mesh.primitives) {
      for (const auto& [name, accessor] : primitive.attributes) {
        if (name == "POSITION") wanted[accessor] = {Filter::kExponential, kPositionBits};
        if (name == "NORMAL") wanted[accessor] = {Filter::kOctahedral, kOctahedralBits};
        if (name == "TEXCOORD_0") wanted[accessor] = {Filter::kExponential, kUvBits};
      }
      for (const auto& target : primitive.targets) {
        const auto position = target.find("POSITION");
        if (position != target.end()) wanted[position->second] = {Filter::kExponential, kDeltaBits};
      }
    }
  }
  for (const tinygltf::Animation& animation : model.animations) {
    for (const tinygltf::AnimationChannel& channel : animation.channels) {
      const int output = animation.samplers[static_cast<std::size_t>(channel.sampler)].output;
      if (channel.target_path == "translation")
        wanted[output] = {Filter::kExponential, kTranslationBits};
      if (channel.target_path == "rotation") wanted[output] = {Filter::kQuaternion, kRotationBits};
    }
  }
  std::map<int, ViewUse> uses;
  for (std::size_t a = 0; a < model.accessors.size(); ++a) {
    const tinygltf::Accessor& accessor = model.accessors[a];
    if (accessor.bufferView < 0 || uses.count(accessor.bufferView) > 0) continue;
    const tinygltf::BufferView& view =
        model.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
    ViewUse use;
    use.element =
        view.byteStride != 0
            ? view.byteStride
            : static_cast<std::size_t>(
                  tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type)) *
                  tinygltf::GetComponentSizeInBytes(
                      static_cast<std::uint32_t>(accessor.componentType)));
    const auto role = wanted.find(static_cast<int>(a));
    if (role != wanted.end() &&
        FilterFits(role->second.filter, accessor, use.element, view.byteStride != 0))
      use.filter = role->second;
    uses[accessor.bufferView] = use;
  }
  return uses;
}

// A normalized integer's value (signed: at least -1).
template <class T>
float Normalized(T q, double scale) {
  return std::max(static_cast<float>(q) / static_cast<float>(scale), -1.0f);
}

// The normalized integers of type T in `raw`, as floats.
template <class T>
std::vector<float> NormalizedValues(std::span<const unsigned char> raw, double scale) {
  std::vector<T> integers(raw.size() / sizeof(T));
  std::memcpy(integers.data(), raw.data(), integers.size() * sizeof(T));
  std::vector<float> values(integers.size());
  for (std::size_t i = 0; i < integers.size(); ++i) values[i] = Normalized(integers[i], scale);
  return values;
}

// meshoptimizer's filter decoder `decode` on `count` elements of `stride` bytes at `data`, run on
// a copy padded to a whole number of its 4-wide SIMD groups with copies of the first element:
// it pads a partial group with zeros itself, and a zero octahedral element divides by zero
// (harmless, but a trap where floating-point exceptions are enabled).
void DecodeFilter(void (*decode)(void*, std::size_t, std::size_t), unsigned char* data,
                  std::size_t count, std::size_t stride) {
  if (count == 0) return;
  const std::size_t padded = (count + 3) / 4 * 4;
  std::vector<unsigned char> copy(padded * stride);
  std::memcpy(copy.data(), data, count * stride);
  for (std::size_t i = count; i < padded; ++i) std::memcpy(copy.data() + i * stride, data, stride);
  decode(copy.data(), padded, stride);
  std::memcpy(data, copy.data(), count * stride);
}

// The view's elements encoded by its filter, when decoding them gives `raw` back bit for bit
// (the data was rounded for it); else empty.
std::vector<unsigned char> Filtered(std::span<const unsigned char> raw, const ViewUse& use) {
  const std::size_t count = raw.size() / use.element;
  std::vector<unsigned char> encoded(raw.size());
  std::vector<unsigned char> decoded;
  const int bits = use.filter.bits;
  if (use.filter.filter == Filter::kExponential) {
    std::vector<float> values(raw.size() / sizeof(float));
    std::memcpy(values.data(), raw.data(), raw.size());
    meshopt_encodeFilterExp(encoded.data(), count, use.element, bits, values.data());
    decoded = encoded;
    DecodeFilter(meshopt_decodeFilterExp, decoded.data(), count, use.element);
  } else if (use.filter.filter == Filter::kQuaternion) {
    const std::vector<float> values = NormalizedValues<std::int16_t>(raw, kShortScale);
    meshopt_encodeFilterQuat(encoded.data(), count, use.element, bits, values.data());
    decoded = encoded;
    DecodeFilter(meshopt_decodeFilterQuat, decoded.data(), count, use.element);
  } else if (use.filter.filter == Filter::kOctahedral) {
    const std::vector<float> values = NormalizedValues<std::int8_t>(raw, kByteScale);
    meshopt_encodeFilterOct(encoded.data(), count, use.element, bits, values.data());
    decoded = encoded;
    DecodeFilter(meshopt_decodeFilterOct, decoded.data(), count, use.element);
  } else {
    return {};
  }
  if (std::memcmp(decoded.data(), raw.data(), raw.size()) != 0) return {};
  return encoded;
}

const char* FilterName(Filter filter) {
  switch (filter) {
    case Filter::kExponential:
      return "EXPONENTIAL";
    case Filter::kQuaternion:
      return "QUATERNION";
    case Filter::kOctahedral:
      return "OCTAHEDRAL";
    case Filter::kNone:
      break;
  }
  return nullptr;
}

// One element of N floats (`values`, updated) through a filter and back, until encoding the
// decoded integers (each taken as value * scale, as a reader and CompressBuffers read them)
// gives them back: a decoded unit vector or quaternion is unit only to rounding, so one round
// trip is not always a fixed point. Returns the decoded integers.
template <class T, std::size_t N>
std::array<T, N> RoundElement(float (&values)[N], int bits, double scale,
                              void (*encode)(void*, std::size_t, std::size_t, int, const float*),
                              void (*decode)(void*, std::size_t, std::size_t)) {
  std::array<T, N> stored{}, previous{};
  for (int pass = 0; pass < 8; ++pass) {
    encode(stored.data(), 1, sizeof stored, bits, values);
    DecodeFilter(decode, reinterpret_cast<unsigned char*>(stored.data()), 1, sizeof stored);
    if (pass > 0 && stored == previous) break;
    previous = stored;
    for (std::size_t c = 0; c < N; ++c) values[c] = Normalized(stored[c], scale);
  }
  return stored;
}

// `filter`: the filter's name, or null for none.
std::string Extension(std::size_t offset, std::size_t length, std::size_t stride, std::size_t count,
                      const char* mode, const char* filter) {
  nlohmann::json o = {{"buffer", 0},          {"byteOffset", offset}, {"byteLength", length},
                      {"byteStride", stride}, {"count", count},       {"mode", mode}};
  if (filter) o["filter"] = filter;
  return o.dump();
}

}  // namespace

void RoundLikeExpFilter(std::span<float> values, std::size_t components, int bits) {
  if (values.empty()) return;  // a mesh without normals or UVs
  const std::size_t count = values.size() / components;
  const std::size_t stride = components * sizeof(float);
  std::vector<unsigned char> encoded(values.size_bytes());
  // Until encoding gives the values back: a component rounded up to a power of two raises its
  // vector's exponent the next time, so one round trip is not always a fixed point.
  for (int pass = 0; pass < 8; ++pass) {
    meshopt_encodeFilterExp(encoded.data(), count, stride, bits, values.data());
    DecodeFilter(meshopt_decodeFilterExp, encoded.data(), count, stride);
    if (std::memcmp(values.data(), encoded.data(), values.size_bytes()) == 0) return;
    std::memcpy(values.data(), encoded.data(), values.size_bytes());
  }
}

int ExpFilterBits(double largest, double precision, int most) {
  // A vector's components are rounded to multiples of 2^(e + 1 - bits), where 2^e, the power of
  // two above its largest component, is at most 2 largest: within largest * 2^(1 - bits).
  if (!(largest > precision)) return 1;
  const double needed = 1.0 + std::ceil(std::log2(largest / precision));
  return static_cast<int>(std::clamp(needed, 1.0, static_cast<double>(most)));
}

void RoundLikeOctFilter(std::span<float> values, int bits) {
  for (std::size_t i = 0; i + 3 <= values.size(); i += 3) {
    float vector[4] = {values[i], values[i + 1], values[i + 2], 0.0f};  // w: kept as it is
    const std::array<std::int8_t, 4> stored = RoundElement<std::int8_t>(
        vector, bits, kByteScale, meshopt_encodeFilterOct, meshopt_decodeFilterOct);
    for (std::size_t c = 0; c < 3; ++c) values[i + c] = Normalized(stored[c], kByteScale);
  }
}

Eigen::Quaternionf RoundLikeQuatFilter(const Eigen::Quaternionf& q, int bits) {
  float values[4] = {q.x(), q.y(), q.z(), q.w()};
  const std::array<std::int16_t, 4> stored = RoundElement<std::int16_t>(
      values, bits, kShortScale, meshopt_encodeFilterQuat, meshopt_decodeFilterQuat);
  const auto value = [&stored](std::size_t c) { return Normalized(stored[c], kShortScale); };
  return Eigen::Quaternionf(value(3), value(0), value(1), value(2));
}

MeshoptJson CompressBuffers(tinygltf::Model& model, const StreamedTargets& tail) {
  MeshoptJson json;
  std::vector<unsigned char> data;
  if (!model.buffers.empty()) data = std::move(model.buffers[0].data);
  data.reserve(data.size() + tail.Size());
  tail.Write([&data](std::span<const unsigned char> block) {
    data.insert(data.end(), block.begin(), block.end());
    return true;
  });
  const std::map<int, ViewUse> uses = ViewUses(model);
  std::vector<unsigned char> packed;
  std::vector<unsigned char> scratch;
  for (std::size_t v = 0; v < model.bufferViews.size(); ++v) {
    tinygltf::BufferView& view = model.bufferViews[v];
    const std::span<const unsigned char> raw(data.data() + view.byteOffset, view.byteLength);
    packed.resize(Padded4(packed.size()), 0);
    const std::size_t offset = packed.size();
    const auto use = uses.find(static_cast<int>(v));
    const bool indices = view.target == TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER && use != uses.end() &&
                         (use->second.element == 2 || use->second.element == 4);
    const bool attributes = use != uses.end() && !indices && use->second.element % 4 == 0 &&
                            use->second.element <= 256 && raw.size() % use->second.element == 0;
    if (indices && raw.size() / use->second.element % 3 == 0) {
      const std::size_t count = raw.size() / use->second.element;
      std::vector<unsigned int> widened(count);
      for (std::size_t i = 0; i < count; ++i) {
        std::uint16_t narrow = 0;
        if (use->second.element == 2) {
          std::memcpy(&narrow, raw.data() + 2 * i, 2);
          widened[i] = narrow;
        } else {
          std::memcpy(&widened[i], raw.data() + 4 * i, 4);
        }
      }
      scratch.resize(meshopt_encodeIndexBufferBound(count, data.size()));
      scratch.resize(
          meshopt_encodeIndexBuffer(scratch.data(), scratch.size(), widened.data(), count));
      packed.insert(packed.end(), scratch.begin(), scratch.end());
      json.views.emplace_back(
          v, Extension(offset, scratch.size(), use->second.element, count, "TRIANGLES", nullptr));
    } else if (attributes) {
      const std::size_t element = use->second.element, count = raw.size() / element;
      const std::vector<unsigned char> filtered = Filtered(raw, use->second);
      const unsigned char* source = filtered.empty() ? raw.data() : filtered.data();
      scratch.resize(meshopt_encodeVertexBufferBound(count, element));
      scratch.resize(
          meshopt_encodeVertexBuffer(scratch.data(), scratch.size(), source, count, element));
      packed.insert(packed.end(), scratch.begin(), scratch.end());
      json.views.emplace_back(
          v, Extension(offset, scratch.size(), element, count, "ATTRIBUTES",
                       filtered.empty() ? nullptr : FilterName(use->second.filter.filter)));
    } else {
      // Read by no accessor (an embedded image), or not encodable: stored as it is.
      packed.insert(packed.end(), raw.begin(), raw.end());
      view.byteOffset = offset;
      continue;
    }
    view.buffer = 1;  // the fallback: its byte range, no data
  }
  packed.resize(Padded4(packed.size()), 0);
  model.buffers.resize(1);
  model.buffers[0].data = std::move(packed);
  RequireExtension(model, kExtension);
  json.fallback_bytes = data.size();
  return json;
}

}  // namespace wirerig::gltf
