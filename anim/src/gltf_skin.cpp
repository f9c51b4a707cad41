#include "gltf_skin.h"

#include <algorithm>
#include <array>
#include <utility>

#include "gltf_buffers.h"
#include "gltf_skinning.h"

namespace wirerig::gltf {
namespace {

using Rigid = RigidTransform;

// Float as stored, and back to double as read (rotation normalized).
std::pair<Vec3f, Quatf> Store(const Rigid& local) {
  return {local.translation.cast<float>(), local.rotation.normalized().cast<float>()};
}
Rigid Load(const Vec3f& t, const Quatf& q) {
  return {q.cast<double>().normalized(), t.cast<double>()};
}

// Locals of every joint for world transforms `world` (#J), parents first.
void StoreLocals(const std::vector<int>& parent, std::span<const Rigid> world,
                 std::vector<Vec3f>* translations, std::vector<Quatf>* rotations) {
  std::vector<Rigid> stored_world(world.size());
  for (std::size_t j = 0; j < world.size(); ++j) {
    const int p = parent[j];
    const Rigid parent_world = p < 0 ? Rigid{} : stored_world[static_cast<std::size_t>(p)];
    const auto [t, q] = Store(parent_world.LocalOf(world[j]));
    translations->push_back(t);
    rotations->push_back(q);
    stored_world[j] = parent_world.Compose(Load(t, q));
  }
}

}  // namespace

Skeleton MakeSkeleton(std::vector<int> parent, std::vector<std::string> names,
                      std::span<const RigidTransform> rest, std::span<const RigidTransform> keyed) {
  Skeleton skeleton;
  skeleton.parent = std::move(parent);
  skeleton.names = std::move(names);
  const std::size_t joints = skeleton.JointCount();
  const std::size_t keys = joints == 0 ? 0 : keyed.size() / joints;
  StoreLocals(skeleton.parent, rest, &skeleton.rest_translations, &skeleton.rest_rotations);
  for (std::size_t k = 0; k < keys; ++k) {
    StoreLocals(skeleton.parent, keyed.subspan(k * joints, joints), &skeleton.translations,
                &skeleton.rotations);
  }
  for (std::size_t k = 1; k < keys; ++k) {
    for (std::size_t j = 0; j < joints; ++j) {
      const Quatf& previous = skeleton.rotations[(k - 1) * joints + j];
      Quatf& q = skeleton.rotations[k * joints + j];
      if (previous.dot(q) < 0.0f) q.coeffs() = -q.coeffs();
    }
  }
  const std::vector<Mat4d> rest_globals =
      JointGlobals(skeleton, skeleton.rest_translations, skeleton.rest_rotations);
  for (const Mat4d& g : rest_globals) {
    Mat4d inverse = Mat4d::Identity();
    const Mat3 r = g.topLeftCorner<3, 3>().transpose();
    inverse.topLeftCorner<3, 3>() = r;
    inverse.topRightCorner<3, 1>() = -r * g.topRightCorner<3, 1>();
    skeleton.inverse_bind.push_back(inverse.cast<float>());
  }
  return skeleton;
}

void AppendInfluences(std::vector<std::pair<std::uint32_t, double>> pairs,
                      SkinInfluences* influences) {
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  });
  if (pairs.size() > 4) pairs.resize(4);
  double sum = 0.0;
  for (const auto& pair : pairs) sum += pair.second;
  std::array<float, 4> weights{};
  float rest = 1.0f;
  for (std::size_t c = 1; c < pairs.size(); ++c) {
    weights[c] = static_cast<float>(pairs[c].second / sum);
    rest -= weights[c];
  }
  weights[0] = rest;
  for (std::size_t c = 0; c < 4; ++c) {
    influences->joints.push_back(c < pairs.size() ? static_cast<std::uint16_t>(pairs[c].first)
                                                  : std::uint16_t{0});
    influences->weights.push_back(weights[c]);
  }
}

int AddSkeleton(tinygltf::Model& model, tinygltf::Animation& animation, const Skeleton& skeleton,
                int time_accessor, std::vector<int>* roots) {
  const std::size_t joints = skeleton.JointCount();
  const std::size_t keys = skeleton.translations.size() / joints;
  const int first_node = static_cast<int>(model.nodes.size());
  tinygltf::Skin skin;
  for (std::size_t j = 0; j < joints; ++j) {
    tinygltf::Node node;
    node.name = skeleton.names[j];
    const Vec3f& t = skeleton.rest_translations[j];
    const Quatf& q = skeleton.rest_rotations[j];
    node.translation = {t.x(), t.y(), t.z()};
    node.rotation = {q.x(), q.y(), q.z(), q.w()};
    model.nodes.push_back(std::move(node));
    const int index = first_node + static_cast<int>(j);
    skin.joints.push_back(index);
    if (skeleton.parent[j] < 0) {
      roots->push_back(index);
    } else {
      model.nodes[static_cast<std::size_t>(first_node + skeleton.parent[j])].children.push_back(
          index);
    }
  }
  std::vector<float> matrices;
  for (const Mat4f& m : skeleton.inverse_bind)
    matrices.insert(matrices.end(), m.data(), m.data() + 16);
  skin.inverseBindMatrices = AddFloatAccessor(model, matrices, TINYGLTF_TYPE_MAT4, 0, false);
  if (std::count(skeleton.parent.begin(), skeleton.parent.end(), -1) == 1)
    skin.skeleton = first_node;
  model.skins.push_back(std::move(skin));

  for (std::size_t j = 0; j < joints; ++j) {
    std::vector<float> translation;
    std::vector<float> rotation;
    for (std::size_t k = 0; k < keys; ++k) {
      const Vec3f& t = skeleton.translations[k * joints + j];
      const Quatf& q = skeleton.rotations[k * joints + j];
      translation.insert(translation.end(), {t.x(), t.y(), t.z()});
      rotation.insert(rotation.end(), {q.x(), q.y(), q.z(), q.w()});
    }
    const std::pair<const char*, const std::vector<float>*> paths[] = {
        {"translation", &translation}, {"rotation", &rotation}};
    for (const auto& [path, values] : paths) {
      tinygltf::AnimationSampler sampler;
      sampler.input = time_accessor;
      sampler.output = AddFloatAccessor(
          model, *values, values == &translation ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4, 0,
          false);
      sampler.interpolation = "LINEAR";
      animation.samplers.push_back(sampler);
      tinygltf::AnimationChannel channel;
      channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
      channel.target_node = first_node + static_cast<int>(j);
      channel.target_path = path;
      animation.channels.push_back(channel);
    }
  }
  return static_cast<int>(model.skins.size()) - 1;
}

void AddSkinAttributes(tinygltf::Model& model, int mesh_index, const SkinInfluences& influences,
                       std::size_t joint_count) {
  const int joints = AddJointAccessor(model, influences.joints, joint_count);
  const int weights = AddFloatAccessor(model, influences.weights, TINYGLTF_TYPE_VEC4,
                                       TINYGLTF_TARGET_ARRAY_BUFFER, false);
  for (tinygltf::Primitive& primitive :
       model.meshes[static_cast<std::size_t>(mesh_index)].primitives) {
    primitive.attributes["JOINTS_0"] = joints;
    primitive.attributes["WEIGHTS_0"] = weights;
  }
}

}  // namespace wirerig::gltf
