#include "gltf_skin.h"

#include <algorithm>
#include <array>
#include <utility>

#include "gltf_buffers.h"
#include "gltf_skinning.h"

namespace wirerig::gltf {
namespace {

// A rigid transform in double.
struct Rigid {
  Quat rotation = Quat::Identity();
  Vec3 translation = Vec3::Zero();
  Rigid Compose(const Rigid& local) const {
    return {rotation * local.rotation, translation + rotation * local.translation};
  }
  // The transform `local` with Compose(local) == world.
  Rigid LocalOf(const Rigid& world) const {
    const Quat inverse = rotation.conjugate();
    return {inverse * world.rotation, inverse * (world.translation - translation)};
  }
};

// Float as stored, and back to double as read (rotation normalized).
std::pair<Vec3f, Quatf> Store(const Rigid& local) {
  return {local.translation.cast<float>(), local.rotation.normalized().cast<float>()};
}
Rigid Load(const Vec3f& t, const Quatf& q) {
  return {q.cast<double>().normalized(), t.cast<double>()};
}

// Locals of every joint for world transforms `world` (#J), parents first.
void StoreLocals(const std::vector<int>& parent, const std::vector<Rigid>& world,
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

Skeleton BuildSkeleton(const BakedAnimation& bake) {
  Skeleton skeleton;
  std::vector<std::size_t> first_joint;
  for (std::size_t i = 0; i < bake.spines.size(); ++i) {
    const BakedSpine& spine = bake.spines[i];
    first_joint.push_back(skeleton.parent.size());
    const std::string base = spine.name.empty() ? "spine" + std::to_string(i) : spine.name;
    for (std::size_t s = 0; s < spine.SampleCount(); ++s) {
      int parent = static_cast<int>(skeleton.parent.size()) - 1;
      if (s == 0) {
        parent = spine.parent < 0
                     ? -1
                     : static_cast<int>(first_joint[static_cast<std::size_t>(spine.parent)]) +
                           spine.parent_joint;
      }
      skeleton.parent.push_back(parent);
      std::string name = base;
      name.append("_").append(std::to_string(s));
      skeleton.names.push_back(std::move(name));
    }
  }
  const std::size_t joints = skeleton.JointCount();
  const std::size_t keys = bake.KeyCount();
  auto world_at = [&](bool rest, std::size_t k) {
    std::vector<Rigid> world;
    world.reserve(joints);
    for (const BakedSpine& spine : bake.spines) {
      const std::size_t n = spine.SampleCount();
      for (std::size_t s = 0; s < n; ++s) {
        world.push_back(
            rest ? Rigid{spine.rest_rotations[s].normalized(), spine.rest_points[s]}
                 : Rigid{spine.rotations[k * n + s].normalized(), spine.points[k * n + s]});
      }
    }
    return world;
  };
  StoreLocals(skeleton.parent, world_at(true, 0), &skeleton.rest_translations,
              &skeleton.rest_rotations);
  for (std::size_t k = 0; k < keys; ++k) {
    StoreLocals(skeleton.parent, world_at(false, k), &skeleton.translations, &skeleton.rotations);
  }
  // Consecutive keys of a joint in the same hemisphere, so that slerp takes the short way.
  for (std::size_t k = 1; k < keys; ++k) {
    for (std::size_t j = 0; j < joints; ++j) {
      const Quatf& previous = skeleton.rotations[(k - 1) * joints + j];
      Quatf& q = skeleton.rotations[k * joints + j];
      if (previous.dot(q) < 0.0f) q.coeffs() = -q.coeffs();
    }
  }
  const std::vector<Mat4d> rest =
      JointGlobals(skeleton, skeleton.rest_translations, skeleton.rest_rotations);
  for (const Mat4d& g : rest) {
    Mat4d inverse = Mat4d::Identity();
    const Mat3 r = g.topLeftCorner<3, 3>().transpose();
    inverse.topLeftCorner<3, 3>() = r;
    inverse.topRightCorner<3, 1>() = -r * g.topRightCorner<3, 1>();
    skeleton.inverse_bind.push_back(inverse.cast<float>());
  }
  return skeleton;
}

SkinInfluences MakeSkinInfluences(const BakedAnimation& bake) {
  SkinInfluences influences;
  std::vector<std::pair<double, std::uint32_t>> slots;  // (weight, joint), distinct joints
  for (std::size_t v = 0; v < bake.vertex_count; ++v) {
    slots.clear();
    double sum = 0.0;
    for (std::size_t c = 0; c < 4; ++c) {
      const double w = bake.skin_weights[v][static_cast<Eigen::Index>(c)];
      if (!(w > 0.0)) continue;
      const std::uint32_t joint = bake.skin_joints[v][c];
      auto same = std::find_if(slots.begin(), slots.end(),
                               [&](const auto& slot) { return slot.second == joint; });
      if (same != slots.end()) {
        same->first += w;
      } else {
        slots.emplace_back(w, joint);
      }
      sum += w;
    }
    std::sort(slots.begin(), slots.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    std::array<float, 4> weights{};
    float rest = 1.0f;
    for (std::size_t c = 1; c < slots.size(); ++c) {
      weights[c] = static_cast<float>(slots[c].first / sum);
      rest -= weights[c];
    }
    weights[0] = rest;
    for (std::size_t c = 0; c < 4; ++c) {
      influences.joints.push_back(c < slots.size() ? static_cast<std::uint16_t>(slots[c].second)
                                                   : std::uint16_t{0});
      influences.weights.push_back(weights[c]);
    }
  }
  return influences;
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
