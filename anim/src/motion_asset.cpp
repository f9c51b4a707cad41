// Animations stored in skinned assets (Assimp), played through the rig built from the asset's
// own skeleton (motion_import.h).
#include <algorithm>
#include <cfenv>
#include <cmath>
#include <map>
#include <unordered_map>

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <nlohmann/json.hpp>

#include "motion_rotation.h"
#include "wirerig/anim/clip_json.h"
#include "wirerig/anim/motion_import.h"
#include "wirerig/io/floating_point_hold.h"
#include "wirerig/io/json_text.h"
#include "wirerig/rig/isolated_process.h"

namespace wirerig {
namespace {

using Mat4 = Eigen::Matrix4d;

constexpr double kMaxEntry = 1e9;          // larger transform entries are refused as absurd
constexpr std::size_t kMaxKeys = 100'000;  // distinct key times of one animation

Mat4 ToMat4(const aiMatrix4x4& m) {
  Mat4 out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return out;
}

bool Finite(const aiVector3D& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) &&
         std::abs(v.x) <= kMaxEntry && std::abs(v.y) <= kMaxEntry && std::abs(v.z) <= kMaxEntry;
}
bool Finite(const aiQuaternion& q) {
  return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) &&
         std::abs(q.w) + std::abs(q.x) + std::abs(q.y) + std::abs(q.z) > 1e-12 &&
         std::abs(q.w) <= kMaxEntry && std::abs(q.x) <= kMaxEntry && std::abs(q.y) <= kMaxEntry &&
         std::abs(q.z) <= kMaxEntry;
}
bool Finite(const Mat4& m) {
  for (int i = 0; i < 16; ++i)
    if (!std::isfinite(m.data()[i]) || std::abs(m.data()[i]) > kMaxEntry) return false;
  return true;
}

std::string Metadata(const aiMetadata* metadata, const char* key) {
  aiString value;
  if (metadata != nullptr && metadata->Get(key, value)) return value.C_Str();
  return {};
}

std::optional<double> MetadataNumber(const aiMetadata* metadata, const char* key) {
  if (metadata == nullptr) return std::nullopt;
  for (unsigned i = 0; i < metadata->mNumProperties; ++i) {
    if (std::string_view(metadata->mKeys[i].C_Str()) != key) continue;
    const aiMetadataEntry& entry = metadata->mValues[i];
    if (entry.mData == nullptr) return std::nullopt;
    switch (entry.mType) {
      case AI_INT32:
        return double(*static_cast<const int32_t*>(entry.mData));
      case AI_UINT64:
        return double(*static_cast<const uint64_t*>(entry.mData));
      case AI_FLOAT:
        return double(*static_cast<const float*>(entry.mData));
      case AI_DOUBLE:
        return *static_cast<const double*>(entry.mData);
      default:
        return std::nullopt;
    }
  }
  return std::nullopt;
}

// The conversion mesh import applies to the file (mesh_import.h): rotation R and scale s with
// x_wirerig = s R x_file (Collada's up axis and unit are applied by Assimp itself).
struct Conversion {
  Mat3 rotation = Mat3::Identity();
  double scale = 1.0;
};

Conversion ChooseConversion(const aiScene& scene, const ImportOptions& options) {
  Conversion c;
  const std::string format = Metadata(scene.mMetaData, "SourceAsset_Format");
  const bool collada = format.find("Collada") != std::string::npos;
  const bool fbx = format.find("FBX") != std::string::npos;
  double collada_scale = 1.0;
  if (collada && scene.mRootNode != nullptr) {
    const double s = ToMat4(scene.mRootNode->mTransformation).block<3, 1>(0, 0).norm();
    if (std::isfinite(s) && s > 0.0) collada_scale = s;
  }
  if (options.up_axis) {
    c.rotation = SourceUpRotation(*options.up_axis);
  } else if (fbx) {
    const std::optional<double> axis = MetadataNumber(scene.mMetaData, "UpAxis");
    if (axis && (*axis == 0.0 || *axis == 2.0)) {
      const UpAxis up = *axis == 0.0 ? UpAxis::kX : UpAxis::kZ;
      c.rotation = SourceUpRotation(up);
      const std::optional<double> sign = MetadataNumber(scene.mMetaData, "UpAxisSign");
      if (sign && *sign < 0.0) {
        const Vec3 flip = up == UpAxis::kX ? Vec3(-1, -1, 1) : Vec3(1, -1, -1);
        c.rotation = c.rotation * flip.asDiagonal();
      }
    } else if (axis && *axis == 1.0) {
      const std::optional<double> sign = MetadataNumber(scene.mMetaData, "UpAxisSign");
      if (sign && *sign < 0.0) c.rotation = Vec3(1, -1, -1).asDiagonal();
    }
  }
  if (options.unit_scale) {
    c.scale = collada ? *options.unit_scale / collada_scale : *options.unit_scale;
  } else if (const std::optional<double> factor =
                 MetadataNumber(scene.mMetaData, "UnitScaleFactor");
             fbx && factor && *factor > 0.0) {
    c.scale = *factor * 0.01;
  }
  return c;
}

struct Node {
  const aiNode* node = nullptr;
  int parent = -1;
  const aiNodeAnim* channel = nullptr;
};

void Flatten(const aiNode* node, int parent, std::vector<Node>& out) {
  if (node == nullptr) return;
  const int index = static_cast<int>(out.size());
  out.push_back({node, parent, nullptr});
  for (unsigned c = 0; c < node->mNumChildren; ++c) Flatten(node->mChildren[c], index, out);
}

// Index of the last key at or before `time` (0 when before the first).
template <typename Key>
std::size_t KeyBefore(const Key* keys, unsigned count, double time) {
  const Key* end = keys + count;
  const Key* it =
      std::upper_bound(keys, end, time, [](double t, const Key& key) { return t < key.mTime; });
  return it == keys ? 0 : std::size_t(it - keys - 1);
}

aiVector3D SampleVector(const aiVectorKey* keys, unsigned count, double time) {
  const std::size_t i = KeyBefore(keys, count, time);
  if (i + 1 >= count || time <= keys[i].mTime) return keys[i].mValue;
  const double span = keys[i + 1].mTime - keys[i].mTime;
  const ai_real u = span > 0.0 ? ai_real((time - keys[i].mTime) / span) : ai_real(0);
  return keys[i].mValue + (keys[i + 1].mValue - keys[i].mValue) * u;
}

aiQuaternion SampleRotation(const aiQuatKey* keys, unsigned count, double time) {
  const std::size_t i = KeyBefore(keys, count, time);
  if (i + 1 >= count || time <= keys[i].mTime) return keys[i].mValue;
  const double span = keys[i + 1].mTime - keys[i].mTime;
  const ai_real u = span > 0.0 ? ai_real((time - keys[i].mTime) / span) : ai_real(0);
  aiQuaternion out;
  aiQuaternion::Interpolate(out, keys[i].mValue, keys[i + 1].mValue, u);
  return out.Normalize();
}

// The node's local transform at `time` (ticks): its channel's keys, the node's own transform
// for what the channel does not key.
Mat4 LocalTransform(const Node& node, double time) {
  const aiNodeAnim* channel = node.channel;
  if (channel == nullptr) return ToMat4(node.node->mTransformation);
  aiVector3D scaling, position;
  aiQuaternion rotation;
  node.node->mTransformation.Decompose(scaling, rotation, position);
  if (channel->mNumPositionKeys > 0)
    position = SampleVector(channel->mPositionKeys, channel->mNumPositionKeys, time);
  if (channel->mNumRotationKeys > 0)
    rotation = SampleRotation(channel->mRotationKeys, channel->mNumRotationKeys, time);
  if (channel->mNumScalingKeys > 0)
    scaling = SampleVector(channel->mScalingKeys, channel->mNumScalingKeys, time);
  return ToMat4(aiMatrix4x4(scaling, rotation, position));
}

// The node's key times, checked: finite, increasing, values finite.
template <typename Key>
std::string CheckKeys(const Key* keys, unsigned count, const char* what,
                      std::vector<double>& times) {
  for (unsigned k = 0; k < count; ++k) {
    if (!std::isfinite(keys[k].mTime) || std::abs(keys[k].mTime) > 1e12)
      return std::string(what) + " key " + std::to_string(k) + ": its time is not finite";
    if (k > 0 && !(keys[k].mTime > keys[k - 1].mTime))
      return std::string(what) + " key " + std::to_string(k) + ": times must increase";
    if (!Finite(keys[k].mValue))
      return std::string(what) + " key " + std::to_string(k) +
             ": its value is not finite (or absurd)";
    times.push_back(keys[k].mTime);
  }
  return {};
}

// The joint of a part of a skeleton rig (skeleton_description.h names parts after their
// joints: the name, "bone_<j>" when empty, "<name>_<k>" for the k-th repeat of a name).
int JointOfPart(const Mesh& mesh, const std::string& part) {
  for (std::size_t j = 0; j < mesh.joints.size(); ++j)
    if (mesh.joints[j].name == part) return static_cast<int>(j);
  if (part.starts_with("bone_")) {
    const std::string digits = part.substr(5);
    if (!digits.empty() && digits.size() < 9 &&
        std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      const std::size_t j = std::stoul(digits);
      if (j < mesh.joints.size() && mesh.joints[j].name.empty()) return static_cast<int>(j);
    }
  }
  const std::size_t underscore = part.rfind('_');
  if (underscore != std::string::npos && underscore + 1 < part.size()) {
    const std::string base = part.substr(0, underscore), digits = part.substr(underscore + 1);
    if (digits.size() < 9 &&
        std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      std::size_t k = std::stoul(digits), seen = 0;
      for (std::size_t j = 0; j < mesh.joints.size(); ++j)
        if (mesh.joints[j].name == base && ++seen == k) return static_cast<int>(j);
    }
  }
  return -1;
}

Mat4 RigidInverse(const Mat4& m) {
  Mat4 out = Mat4::Identity();
  out.topLeftCorner<3, 3>() = m.topLeftCorner<3, 3>().transpose();
  out.topRightCorner<3, 1>() = -(out.topLeftCorner<3, 3>() * m.topRightCorner<3, 1>());
  return out;
}

std::string AnimationName(const aiAnimation& animation, unsigned index) {
  std::string name = animation.mName.C_Str();
  if (name.empty()) name.append("#").append(std::to_string(index));
  return name;
}

}  // namespace

Result<RawClip> ClipFromAssetAnimation(const std::filesystem::path& file, const Mesh& mesh,
                                       const RigModel& model,
                                       const AssetAnimationOptions& options) {
  const std::string name = file.string();
  auto fail = [&](const std::string& reason) { return Error{name + ": " + reason}; };
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return fail("no such motion file");
  if (!std::filesystem::is_regular_file(file, ec))
    return fail(std::filesystem::is_directory(file, ec)
                    ? "is a directory, not a motion file"
                    : "is not a regular file (a device, FIFO or socket), not a motion file");
  if (options.import.isolation) {
    // Assimp reads the file in a child process; the clip comes back in its JSON form (which
    // ReadClip reads back exactly).
    AssetAnimationOptions in_child = options;
    in_child.import.isolation.reset();
    Result<std::string> answer =
        RunIsolated(file, *options.import.isolation, [&]() -> Result<std::string> {
          Result<RawClip> clip = ClipFromAssetAnimation(file, mesh, model, in_child);
          if (!clip) return Error{clip.error()};
          return DumpJson(ClipToJson(clip.value()));
        });
    if (!answer) return Error{answer.error()};
    const nlohmann::json document = nlohmann::json::parse(answer.value(), nullptr, false);
    try {
      if (document.is_discarded()) throw FieldError("", "not JSON");
      return ReadClip(JsonObject(document, ""));
    } catch (const FieldError& e) {
      return fail(std::string("the importer process answered badly: ") + e.what());
    }
  }

  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  if (options.import.up_axis)
    importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene = nullptr;
  {
    const ScopedFloatingPointHold hold;
    try {
      scene = importer.ReadFile(name, aiProcess_ValidateDataStructure);
    } catch (const std::exception& e) {
      return fail(std::string("cannot import: ") + e.what());
    }
  }
  if (scene == nullptr) return fail(std::string("cannot import: ") + importer.GetErrorString());
  if (scene->mRootNode == nullptr) return fail("holds no node hierarchy");
  if (scene->mNumAnimations == 0) return fail("holds no animation");

  // Which animation.
  std::string names;
  for (unsigned a = 0; a < scene->mNumAnimations; ++a)
    names.append(a == 0 ? "" : ", ").append(AnimationName(*scene->mAnimations[a], a));
  unsigned selected = 0;
  if (!options.animation_name.empty()) {
    bool found = false;
    for (unsigned a = 0; a < scene->mNumAnimations && !found; ++a)
      if (options.animation_name == scene->mAnimations[a]->mName.C_Str()) {
        selected = a;
        found = true;
      }
    if (!found)
      return fail("no animation named \"" + options.animation_name + "\" (it holds: " + names +
                  ")");
  } else {
    if (options.animation_index < 0 ||
        options.animation_index >= static_cast<int>(scene->mNumAnimations))
      return fail("animation index " + std::to_string(options.animation_index) +
                  " is out of range: it holds " + std::to_string(scene->mNumAnimations) +
                  (scene->mNumAnimations == 1 ? " animation (" : " animations (") + names + ")");
    selected = static_cast<unsigned>(options.animation_index);
  }
  const aiAnimation& animation = *scene->mAnimations[selected];
  const std::string animation_where = "animation \"" + AnimationName(animation, selected) + "\"";

  // Nodes and their channels; the key times.
  std::vector<Node> nodes;
  Flatten(scene->mRootNode, -1, nodes);
  std::unordered_map<std::string, int> node_of_name;
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    if (!Finite(ToMat4(nodes[n].node->mTransformation)))
      return fail("node \"" + std::string(nodes[n].node->mName.C_Str()) +
                  "\": its transform is not finite (or absurd)");
    node_of_name.try_emplace(nodes[n].node->mName.C_Str(), static_cast<int>(n));
  }
  std::vector<double> ticks;
  for (unsigned c = 0; c < animation.mNumChannels; ++c) {
    const aiNodeAnim* channel = animation.mChannels[c];
    const std::string where =
        animation_where + ", channel \"" + std::string(channel->mNodeName.C_Str()) + "\": ";
    for (const std::string& error :
         {CheckKeys(channel->mPositionKeys, channel->mNumPositionKeys, "position", ticks),
          CheckKeys(channel->mRotationKeys, channel->mNumRotationKeys, "rotation", ticks),
          CheckKeys(channel->mScalingKeys, channel->mNumScalingKeys, "scaling", ticks)})
      if (!error.empty()) return fail(where + error);
    const auto it = node_of_name.find(channel->mNodeName.C_Str());
    if (it != node_of_name.end()) nodes[std::size_t(it->second)].channel = channel;
  }
  std::sort(ticks.begin(), ticks.end());
  ticks.erase(std::unique(ticks.begin(), ticks.end()), ticks.end());
  if (ticks.empty()) return fail(animation_where + " has no keys");
  if (ticks.size() > kMaxKeys) return fail(animation_where + " has more than 100000 key times");
  const double ticks_per_second =
      std::isfinite(animation.mTicksPerSecond) && animation.mTicksPerSecond > 0.0
          ? animation.mTicksPerSecond
          : 25.0;  // Assimp's convention when the file states none

  // Parts -> nodes.
  const std::size_t part_count = model.parts.size();
  std::vector<int> node_of_part(part_count, -1);
  std::vector<Mat4> bind_inverse(part_count, Mat4::Identity());
  bool any = false;
  for (std::size_t p = 0; p < part_count; ++p) {
    const int joint = JointOfPart(mesh, model.parts[p].name);
    if (joint < 0) continue;
    const auto it = node_of_name.find(mesh.joints[std::size_t(joint)].name);
    if (it == node_of_name.end()) continue;
    node_of_part[p] = it->second;
    bind_inverse[p] = RigidInverse(mesh.joints[std::size_t(joint)].bind_global);
    any = any || nodes[std::size_t(it->second)].channel != nullptr;
  }
  if (!any) return fail(animation_where + ": none of its channels moves a part of the rig");

  const Conversion conversion = ChooseConversion(*scene, options.import);
  double extent = 0.0;
  for (const PartModel& part : model.parts)
    for (const Vec3& p : part.spine_points)
      extent = std::max(extent, (p - model.parts.front().spine_points.front()).norm());

  RawClip clip;
  clip.name = options.clip_name;
  clip.duration =
      ticks.size() > 1 ? (ticks.back() - ticks.front()) / ticks_per_second : 1.0 / ticks_per_second;
  std::vector<RawPartTracks> tracks(part_count);
  std::vector<std::optional<Vec3>> previous(part_count);
  std::vector<double> largest_shift(part_count, 0.0);
  std::vector<Mat4> global(nodes.size()), motion(part_count);
  for (const double tick : ticks) {
    for (std::size_t n = 0; n < nodes.size(); ++n) {
      const Mat4 local = LocalTransform(nodes[n], tick);
      global[n] = nodes[n].parent < 0 ? local : Mat4(global[std::size_t(nodes[n].parent)] * local);
    }
    const double time = (tick - ticks.front()) / ticks_per_second;
    for (std::size_t p = 0; p < part_count; ++p) {
      const PartModel& part = model.parts[p];
      const Mat4 parent = part.parent < 0 ? Mat4::Identity() : motion[std::size_t(part.parent)];
      if (node_of_part[p] < 0) {
        motion[p] = parent;
        continue;
      }
      const Mat4& g = global[std::size_t(node_of_part[p])];
      if (!Finite(g))
        return fail(animation_where + ": node \"" +
                    std::string(nodes[std::size_t(node_of_part[p])].node->mName.C_Str()) +
                    "\" is not finite (or absurd) at tick " + std::to_string(tick));
      Mat4 converted = Mat4::Identity();
      converted.topLeftCorner<3, 3>() = NearestRotation(
          conversion.rotation * g.topLeftCorner<3, 3>() * conversion.rotation.transpose());
      converted.topRightCorner<3, 1>() =
          conversion.scale * (conversion.rotation * g.topRightCorner<3, 1>());
      motion[p] = converted * bind_inverse[p];
      const Mat4 own = RigidInverse(parent) * motion[p];
      const Mat3 turn = own.topLeftCorner<3, 3>();
      const Vec3 root = part.spine_points.front();
      const Vec3 shift = turn * root + own.topRightCorner<3, 1>() - root;
      const Vec3 vector = ContinuousRotationVector(turn, previous[p]);
      previous[p] = vector;
      tracks[p].channels.rotation.keys.push_back({time, vector, Interpolation::kLinear});
      tracks[p].channels.translation.keys.push_back({time, shift, Interpolation::kLinear});
      largest_shift[p] = std::max(largest_shift[p], shift.norm());
    }
  }
  for (std::size_t p = 0; p < part_count; ++p) {
    if (tracks[p].channels.rotation.keys.empty()) continue;
    tracks[p].part = model.parts[p].name;
    if (model.parts[p].parent >= 0 && largest_shift[p] <= 1e-9 * extent)
      tracks[p].channels.translation.keys.clear();  // the joint stays where the parent puts it
    clip.parts.push_back(std::move(tracks[p]));
  }
  if (std::string error = ValidateRawClip(clip); !error.empty())
    return fail(animation_where + ": the clip made from it is not valid: " + error);
  return clip;
}

}  // namespace wirerig
