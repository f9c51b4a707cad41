#include "gltf_skin.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include "gltf_buffers.h"
#include "gltf_meshopt.h"
#include "gltf_skinning.h"

namespace wirerig::gltf {
namespace {

using Rigid = RigidTransform;

// A unit quaternion as stored: each component a normalized signed short.
Quatf StoreRotation(const Quat& q) {
  const auto store = [](double c) {
    return static_cast<float>(std::round(c * kShortScale) / kShortScale);
  };
  return Quatf(store(q.w()), store(q.x()), store(q.y()), store(q.z()));
}

// The locals of a rest pose (float, rotations unquantized: node values are JSON numbers).
void StoreRestLocals(const std::vector<int>& parent, std::span<const Rigid> world,
                     std::vector<Vec3f>* translations, std::vector<Quatf>* rotations) {
  std::vector<Rigid> stored_world(world.size());
  for (std::size_t j = 0; j < world.size(); ++j) {
    const int p = parent[j];
    const Rigid parent_world = p < 0 ? Rigid{} : stored_world[static_cast<std::size_t>(p)];
    const Rigid local = parent_world.LocalOf(world[j]);
    translations->push_back(local.translation.cast<float>());
    rotations->push_back(local.rotation.normalized().cast<float>());
    stored_world[j] = parent_world.Compose(
        {rotations->back().cast<double>().normalized(), translations->back().cast<double>()});
  }
}

// One joint's track: the keys it stores, and the locals a reader has at every key (#K).
struct Track {
  std::vector<std::uint32_t> keys;
  std::vector<Vec3f> translations;
  std::vector<Quatf> rotations;
};

// The track of a joint whose wanted locals are `exact` (#K): every key stored (translation
// float, rotation shorts), then thinned within `tolerance` (KeyThinning).
Track ThinTrack(std::span<const Rigid> exact, std::span<const float> times, double tolerance,
                double reach, int translation_bits, int rotation_bits) {
  const std::size_t count = exact.size();
  double largest = 0.0;  // of the translations' components
  for (const Rigid& r : exact) largest = std::max(largest, r.translation.cwiseAbs().maxCoeff());
  if (translation_bits > 0)
    translation_bits = ExpFilterBits(largest, kTranslationPrecision, translation_bits);
  std::vector<Vec3f> stored_t(count);
  std::vector<Quatf> stored_q(count);
  Quat previous = Quat::Identity();
  for (std::size_t k = 0; k < count; ++k) {
    Quat q = exact[k].rotation.normalized();
    if (k > 0 && previous.dot(q) < 0.0) q.coeffs() = -q.coeffs();
    previous = q;
    stored_t[k] = exact[k].translation.cast<float>();
    if (translation_bits > 0) RoundLikeExpFilter({stored_t[k].data(), 3}, 3, translation_bits);
    stored_q[k] =
        rotation_bits > 0 ? RoundLikeQuatFilter(q.cast<float>(), rotation_bits) : StoreRotation(q);
  }
  // What a reader has at key i between stored keys a and b.
  const auto interpolate = [&](std::size_t a, std::size_t b, std::size_t i) {
    const double u = (double(times[i]) - times[a]) / (double(times[b]) - times[a]);
    const Vec3 t = (1.0 - u) * stored_t[a].cast<double>() + u * stored_t[b].cast<double>();
    const Quat q =
        stored_q[a].cast<double>().normalized().slerp(u, stored_q[b].cast<double>().normalized());
    return Rigid{q.normalized(), t};
  };
  const auto within = [&](std::size_t a, std::size_t b) {
    for (std::size_t i = a + 1; i < b; ++i) {
      const Rigid r = interpolate(a, b, i);
      const double error = (r.translation - exact[i].translation).norm() +
                           reach * r.rotation.angularDistance(exact[i].rotation);
      if (!(error <= tolerance)) return false;
    }
    return true;
  };
  Track track;
  track.keys.push_back(0);
  for (std::size_t a = 0; a + 1 < count;) {
    std::size_t b = a + 1;
    while (tolerance > 0.0 && b + 1 < count && within(a, b + 1)) ++b;
    track.keys.push_back(static_cast<std::uint32_t>(b));
    a = b;
  }
  track.translations.resize(count);
  track.rotations.resize(count);
  for (std::size_t n = 0; n < track.keys.size(); ++n) {
    const std::size_t a = track.keys[n];
    track.translations[a] = stored_t[a];
    track.rotations[a] = stored_q[a];
    if (n + 1 == track.keys.size()) break;
    for (std::size_t i = a + 1; i < track.keys[n + 1]; ++i) {
      const Rigid r = interpolate(a, track.keys[n + 1], i);
      track.translations[i] = r.translation.cast<float>();
      track.rotations[i] = r.rotation.cast<float>();
    }
  }
  return track;
}

}  // namespace

std::size_t Skeleton::StoredKeyCount() const {
  std::size_t count = 0;
  for (const auto& joint_keys : keys) count += joint_keys.size();
  return count;
}

Skeleton MakeSkeleton(std::vector<int> parent, std::vector<std::string> names,
                      std::span<const RigidTransform> rest, std::span<const RigidTransform> keyed,
                      const KeyThinning& thinning) {
  Skeleton skeleton;
  skeleton.parent = std::move(parent);
  skeleton.names = std::move(names);
  const std::size_t joints = skeleton.JointCount();
  const std::size_t keys = joints == 0 ? 0 : keyed.size() / joints;
  StoreRestLocals(skeleton.parent, rest, &skeleton.rest_translations, &skeleton.rest_rotations);
  skeleton.translations.resize(keys * joints);
  skeleton.rotations.resize(keys * joints);
  skeleton.keys.resize(joints);
  // Joint worlds as a reader reconstructs them (#J x #K, joint-major), parents first.
  std::vector<Rigid> world(joints * keys);
  std::vector<Rigid> exact(keys);
  for (std::size_t j = 0; j < joints; ++j) {
    const int p = skeleton.parent[j];
    for (std::size_t k = 0; k < keys; ++k) {
      const Rigid parent_world = p < 0 ? Rigid{} : world[static_cast<std::size_t>(p) * keys + k];
      exact[k] = parent_world.LocalOf(keyed[k * joints + j]);
    }
    const double reach = j < thinning.reach.size() ? thinning.reach[j] : 0.0;
    Track track = ThinTrack(exact, thinning.times, thinning.tolerance, reach,
                            thinning.translation_bits, thinning.rotation_bits);
    for (std::size_t k = 0; k < keys; ++k) {
      skeleton.translations[k * joints + j] = track.translations[k];
      skeleton.rotations[k * joints + j] = track.rotations[k];
      const Rigid parent_world = p < 0 ? Rigid{} : world[static_cast<std::size_t>(p) * keys + k];
      world[j * keys + k] = parent_world.Compose(
          {track.rotations[k].cast<double>().normalized(), track.translations[k].cast<double>()});
    }
    skeleton.keys[j] = std::move(track.keys);
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
  const std::size_t slots = influences->slots;
  if (pairs.size() > slots) pairs.resize(slots);
  double sum = 0.0;
  for (const auto& pair : pairs) sum += pair.second;
  // Integers summing to exactly the total; the largest takes what rounding leaves.
  const std::uint32_t total = influences->WeightTotal();
  std::array<std::uint32_t, kMaxInfluences> quantized{};
  std::uint32_t rest = total;
  for (std::size_t c = 1; c < pairs.size(); ++c) {
    quantized[c] = static_cast<std::uint32_t>(std::lround(pairs[c].second / sum * total));
    rest -= quantized[c];
  }
  quantized[0] = rest;
  for (std::size_t c = 0; c < slots; ++c) {
    // A slot whose weight rounded to zero is unused (joint 0), as glTF asks.
    const bool used = c < pairs.size() && quantized[c] > 0;
    influences->joints.push_back(used ? static_cast<std::uint16_t>(pairs[c].first)
                                      : std::uint16_t{0});
    influences->weights.push_back(static_cast<float>(double(quantized[c]) / total));
  }
}

int AddSkeleton(tinygltf::Model& model, tinygltf::Animation& animation, const Skeleton& skeleton,
                std::span<const float> times, int time_accessor, std::vector<int>* roots,
                const Eigen::Matrix4d& stored_to_rest) {
  const std::size_t joints = skeleton.JointCount();
  const std::size_t keys = skeleton.translations.size() / joints;
  const int first_node = static_cast<int>(model.nodes.size());
  tinygltf::Skin skin;
  for (std::size_t j = 0; j < joints; ++j) {
    tinygltf::Node node;
    node.name = skeleton.names[j];
    const Vec3f& t = skeleton.rest_translations[j];
    const Quatf& q = skeleton.rest_rotations[j];
    node.translation = {JsonFloat(t.x()), JsonFloat(t.y()), JsonFloat(t.z())};
    node.rotation = {JsonFloat(q.x()), JsonFloat(q.y()), JsonFloat(q.z()), JsonFloat(q.w())};
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
  for (const Mat4f& inverse_bind : skeleton.inverse_bind) {
    const Mat4f m = (inverse_bind.cast<double>() * stored_to_rest).cast<float>();
    matrices.insert(matrices.end(), m.data(), m.data() + 16);
  }
  skin.inverseBindMatrices = AddFloatAccessor(model, matrices, TINYGLTF_TYPE_MAT4, 0, false);
  if (std::count(skeleton.parent.begin(), skeleton.parent.end(), -1) == 1)
    skin.skeleton = first_node;
  model.skins.push_back(std::move(skin));

  // Every joint's translation keys in one view and its rotation keys in another, an accessor
  // per joint at its offset: two views for the whole skeleton rather than two per joint.
  std::map<std::vector<std::uint32_t>, int> inputs;  // stored keys -> their times' accessor
  std::vector<int> input(joints, time_accessor);
  std::vector<float> translation;
  std::vector<std::int16_t> rotation;
  for (std::size_t j = 0; j < joints; ++j) {
    const std::vector<std::uint32_t>& stored = skeleton.keys[j];
    if (stored.size() != keys) {
      auto [it, added] = inputs.try_emplace(stored, -1);
      if (added) {
        std::vector<float> kept_times;
        for (std::uint32_t k : stored) kept_times.push_back(times[k]);
        it->second = AddFloatAccessor(model, kept_times, TINYGLTF_TYPE_SCALAR, 0, true);
      }
      input[j] = it->second;
    }
    for (std::uint32_t k : stored) {
      const Vec3f& t = skeleton.translations[k * joints + j];
      const Quatf& q = skeleton.rotations[k * joints + j];
      translation.insert(translation.end(), {t.x(), t.y(), t.z()});
      for (float c : {q.x(), q.y(), q.z(), q.w()})
        rotation.push_back(static_cast<std::int16_t>(std::lround(c * kShortScale)));
    }
  }
  const auto bytes = [](const auto& values) {
    return std::span(reinterpret_cast<const unsigned char*>(values.data()),
                     values.size() * sizeof(values[0]));
  };
  const int translation_view = AddBytesView(model, bytes(translation));
  const int rotation_view = AddBytesView(model, bytes(rotation));
  std::size_t first_key = 0;
  for (std::size_t j = 0; j < joints; ++j) {
    const std::size_t count = skeleton.keys[j].size();
    const int outputs[] = {
        AddAccessor(model, translation_view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                    count, false, first_key * 3 * sizeof(float)),
        AddAccessor(model, rotation_view, TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC4, count,
                    true, first_key * 4 * sizeof(std::int16_t))};
    first_key += count;
    const char* paths[] = {"translation", "rotation"};
    for (int c = 0; c < 2; ++c) {
      tinygltf::AnimationSampler sampler;
      sampler.input = input[j];
      sampler.output = outputs[c];
      sampler.interpolation = "LINEAR";
      animation.samplers.push_back(sampler);
      tinygltf::AnimationChannel channel;
      channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
      channel.target_node = first_node + static_cast<int>(j);
      channel.target_path = paths[c];
      animation.channels.push_back(channel);
    }
  }
  return static_cast<int>(model.skins.size()) - 1;
}

void AddSkinAttributes(tinygltf::Model& model, int mesh_index, const SkinInfluences& influences,
                       std::size_t joint_count) {
  const std::size_t slots = influences.slots, vertices = influences.joints.size() / slots;
  for (std::size_t set = 0; set * 4 < slots; ++set) {
    std::vector<std::uint16_t> set_joints, set_weights;
    for (std::size_t v = 0; v < vertices; ++v) {
      for (std::size_t c = set * 4; c < set * 4 + 4; ++c) {
        set_joints.push_back(influences.joints[v * slots + c]);
        set_weights.push_back(static_cast<std::uint16_t>(
            std::lround(double(influences.weights[v * slots + c]) * influences.WeightTotal())));
      }
    }
    const int joints = AddJointAccessor(model, set_joints, joint_count);
    const int target = TINYGLTF_TARGET_ARRAY_BUFFER;
    const int weights =
        influences.byte_weights
            ? AddNormalizedByteAccessor(
                  model, std::vector<std::uint8_t>(set_weights.begin(), set_weights.end()),
                  TINYGLTF_TYPE_VEC4, target)
            : AddNormalizedShortAccessor(model, set_weights, TINYGLTF_TYPE_VEC4, target);
    const std::string suffix = std::to_string(set);
    for (tinygltf::Primitive& primitive :
         model.meshes[static_cast<std::size_t>(mesh_index)].primitives) {
      primitive.attributes["JOINTS_" + suffix] = joints;
      primitive.attributes["WEIGHTS_" + suffix] = weights;
    }
  }
}

}  // namespace wirerig::gltf
