#include "gltf_morph.h"

#include <string>
#include <vector>

#include "gltf_buffers.h"

namespace wirerig::gltf {

void AddMorphTargets(tinygltf::Model& model, int mesh_index, std::span<const float> position_deltas,
                     std::span<const float> normal_deltas, std::size_t key_count) {
  const std::size_t per_key = position_deltas.size() / key_count;
  std::vector<std::map<std::string, int>> targets(key_count);
  std::vector<tinygltf::Value> names;
  for (std::size_t k = 0; k < key_count; ++k) {
    targets[k]["POSITION"] = AddFloatAccessor(model, position_deltas.subspan(k * per_key, per_key),
                                              TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER,
                                              /*min_max=*/true);
    if (!normal_deltas.empty()) {
      targets[k]["NORMAL"] =
          AddFloatAccessor(model, normal_deltas.subspan(k * per_key, per_key), TINYGLTF_TYPE_VEC3,
                           TINYGLTF_TARGET_ARRAY_BUFFER, false);
    }
    names.emplace_back("key_" + std::to_string(k));
  }
  tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(mesh_index)];
  for (tinygltf::Primitive& primitive : mesh.primitives) primitive.targets = targets;
  mesh.weights.assign(key_count, 0.0);
  tinygltf::Value::Object extras;
  extras["targetNames"] = tinygltf::Value(std::move(names));
  mesh.extras = tinygltf::Value(std::move(extras));
}

void AddKeyWeightsChannel(tinygltf::Model& model, tinygltf::Animation& animation, int node,
                          int time_accessor, std::size_t key_count) {
  std::vector<float> weights(key_count * key_count, 0.0f);
  for (std::size_t k = 0; k < key_count; ++k) weights[k * key_count + k] = 1.0f;
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
