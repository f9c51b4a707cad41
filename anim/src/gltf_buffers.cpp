#include "gltf_buffers.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

namespace wirerig::gltf {
namespace {

int Components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

}  // namespace

int AddBufferView(tinygltf::Model& model, const void* bytes, std::size_t size, int target) {
  AlignedBufferEnd(model);
  std::vector<unsigned char>& data = model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  data.resize(data.size() + size);
  if (size > 0) std::memcpy(data.data() + view.byteOffset, bytes, size);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

std::size_t AlignedBufferEnd(tinygltf::Model& model) {
  if (model.buffers.empty()) model.buffers.emplace_back();
  std::vector<unsigned char>& data = model.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4, 0);
  return data.size();
}

int AddReservedView(tinygltf::Model& model, std::size_t offset, std::size_t size,
                    std::size_t stride, int target) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = size;
  view.byteStride = stride;
  view.target = target;
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

int AddAccessor(tinygltf::Model& model, int view, int component_type, int type, std::size_t count,
                bool normalized, std::size_t byte_offset) {
  tinygltf::Accessor accessor;
  accessor.bufferView = view;
  accessor.byteOffset = byte_offset;
  accessor.componentType = component_type;
  accessor.type = type;
  accessor.count = count;
  accessor.normalized = normalized;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size()) - 1;
}

int AddFloatAccessor(tinygltf::Model& model, std::span<const float> values, int type, int target,
                     bool min_max) {
  const auto components = static_cast<std::size_t>(Components(type));
  const std::size_t count = values.size() / components;
  const int view = AddBufferView(model, values.data(), values.size_bytes(), target);
  const int index = AddAccessor(model, view, TINYGLTF_COMPONENT_TYPE_FLOAT, type, count);
  if (min_max && count > 0) {
    std::vector<double> low(components, std::numeric_limits<double>::max());
    std::vector<double> high(components, std::numeric_limits<double>::lowest());
    for (std::size_t i = 0; i < values.size(); ++i) {
      low[i % components] = std::min(low[i % components], static_cast<double>(values[i]));
      high[i % components] = std::max(high[i % components], static_cast<double>(values[i]));
    }
    model.accessors[static_cast<std::size_t>(index)].minValues = std::move(low);
    model.accessors[static_cast<std::size_t>(index)].maxValues = std::move(high);
  }
  return index;
}

void RequireExtension(tinygltf::Model& model, const std::string& name) {
  for (auto* list : {&model.extensionsUsed, &model.extensionsRequired})
    if (std::find(list->begin(), list->end(), name) == list->end()) list->push_back(name);
}

int AddNormalizedByteVec3Accessor(tinygltf::Model& model, std::span<const float> values,
                                  int target) {
  const std::size_t count = values.size() / 3;
  std::vector<std::int8_t> padded(4 * count, 0);
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t c = 0; c < 3; ++c)
      padded[4 * i + c] = static_cast<std::int8_t>(
          std::lround(std::clamp(values[3 * i + c], -1.0f, 1.0f) * float(kByteScale)));
  const int view = AddBufferView(model, padded.data(), padded.size(), target);
  model.bufferViews[static_cast<std::size_t>(view)].byteStride = 4;
  RequireExtension(model, kMeshQuantization);
  return AddAccessor(model, view, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC3, count, true);
}

int AddBytesView(tinygltf::Model& model, std::span<const unsigned char> bytes) {
  return AddBufferView(model, bytes.data(), bytes.size(), 0);
}

int AddNormalizedShortAccessor(tinygltf::Model& model, std::span<const std::int16_t> values,
                               int type, int target) {
  const int view = AddBufferView(model, values.data(), values.size_bytes(), target);
  return AddAccessor(model, view, TINYGLTF_COMPONENT_TYPE_SHORT, type,
                     values.size() / static_cast<std::size_t>(Components(type)), true);
}

int AddNormalizedShortAccessor(tinygltf::Model& model, std::span<const std::uint16_t> values,
                               int type, int target) {
  const int view = AddBufferView(model, values.data(), values.size_bytes(), target);
  return AddAccessor(model, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, type,
                     values.size() / static_cast<std::size_t>(Components(type)), true);
}

int AddNormalizedByteAccessor(tinygltf::Model& model, std::span<const std::uint8_t> values,
                              int type, int target) {
  const int view = AddBufferView(model, values.data(), values.size_bytes(), target);
  return AddAccessor(model, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, type,
                     values.size() / static_cast<std::size_t>(Components(type)), true);
}

int AddIndexAccessor(tinygltf::Model& model, std::span<const std::uint32_t> indices,
                     std::uint32_t vertex_count) {
  const int target = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;
  if (vertex_count <= std::numeric_limits<std::uint16_t>::max()) {
    std::vector<std::uint16_t> narrow(indices.begin(), indices.end());
    const int view =
        AddBufferView(model, narrow.data(), narrow.size() * sizeof(std::uint16_t), target);
    return AddAccessor(model, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR,
                       indices.size());
  }
  const int view = AddBufferView(model, indices.data(), indices.size_bytes(), target);
  return AddAccessor(model, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                     indices.size());
}

int AddJointAccessor(tinygltf::Model& model, std::span<const std::uint16_t> joints,
                     std::size_t joint_count) {
  const int target = TINYGLTF_TARGET_ARRAY_BUFFER;
  const std::size_t count = joints.size() / 4;
  if (joint_count <= 256) {
    std::vector<std::uint8_t> narrow(joints.size());
    std::transform(joints.begin(), joints.end(), narrow.begin(),
                   [](std::uint16_t j) { return static_cast<std::uint8_t>(j); });
    const int view = AddBufferView(model, narrow.data(), narrow.size(), target);
    return AddAccessor(model, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4,
                       count);
  }
  const int view = AddBufferView(model, joints.data(), joints.size_bytes(), target);
  return AddAccessor(model, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4,
                     count);
}

double JsonFloat(float value) {
  if (!std::isfinite(value)) return double(value);
  char text[32];
  const std::to_chars_result end = std::to_chars(text, text + sizeof text, value);
  double shortest = double(value);
  std::from_chars(text, end.ptr, shortest);  // locale-independent, as to_chars
  return shortest;
}

}  // namespace wirerig::gltf
