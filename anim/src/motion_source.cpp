// A scene clip's motion: reading and writing its JSON form, and making the clip it plays.
#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "wirerig/anim/motion_import.h"

namespace wirerig {
namespace {

using nlohmann::json;

std::size_t ReadFrame(const json& value, const std::string& path) {
  if (!value.is_number_integer() || value.get<long long>() < 0 ||
      value.get<long long>() > 100'000'000LL)
    throw FieldError(path, "must be a frame index (0, 1, ...)");
  return static_cast<std::size_t>(value.get<long long>());
}

// Puts the motion's tracks of a part into the clip's own tracks of that part; refuses a channel
// both give.
std::string MergeMotionTracks(const PartChannels<RawTrack>& motion, const std::string& where,
                              PartChannels<RawTrack>& own) {
  const std::pair<const RawTrack<Vec3>*, RawTrack<Vec3>*> channels[] = {
      {&motion.rotation, &own.rotation},
      {&motion.translation, &own.translation},
      {&motion.joint_angles, &own.joint_angles}};
  const char* names[] = {"rotation", "translation", "joint_angles"};
  for (std::size_t i = 0; i < 3; ++i) {
    if (channels[i].first->keys.empty()) continue;
    if (!channels[i].second->keys.empty())
      return where + "/" + names[i] + ": the motion drives this part's " + names[i];
    *channels[i].second = *channels[i].first;
  }
  return {};
}

}  // namespace

MotionSource ReadMotionSource(const JsonObject& o) {
  o.RejectUnknownKeys({"file", "mapping", "frames", "animation"});
  MotionSource source;
  source.file = o.String("file");
  if (source.file.empty()) throw FieldError(o.PathOf("file"), "must name the motion file");
  if (IsBvhFile(source.file)) {
    if (o.Has("animation"))
      throw FieldError(o.PathOf("animation"),
                       "a BVH file holds one motion (\"animation\" is for skinned assets)");
    if (!o.Has("mapping"))
      throw FieldError(o.path(), "a BVH motion needs \"mapping\" (a wirerig.motion_mapping file)");
    source.mapping = o.String("mapping");
    if (o.Has("frames")) {
      const std::string path = o.PathOf("frames");
      const json& frames = RequireArray(o.Required("frames"), path);
      if (ArraySize(frames) != 2) throw FieldError(path, "must be [first, last]");
      source.first_frame = ReadFrame(ArrayElement(frames, 0), path + "/0");
      source.last_frame = ReadFrame(ArrayElement(frames, 1), path + "/1");
      if (*source.first_frame > *source.last_frame)
        throw FieldError(path, "the first frame must not come after the last");
    }
  } else {
    for (const char* key : {"mapping", "frames"})
      if (o.Has(key))
        throw FieldError(o.PathOf(key),
                         "is for BVH motion captures (\"file\" names no .bvh file); a skinned "
                         "asset plays on its own skeleton");
    if (o.Has("animation")) {
      const json& value = o.Required("animation");
      if (value.is_string()) {
        source.animation_name = value.get<std::string>();
        if (source.animation_name.empty())
          throw FieldError(o.PathOf("animation"), "must be an index (0, 1, ...) or a name");
      } else if (value.is_number_integer() && value.get<long long>() >= 0 &&
                 value.get<long long>() <= 1'000'000LL) {
        source.animation_index = static_cast<int>(value.get<long long>());
      } else {
        throw FieldError(o.PathOf("animation"), "must be an index (0, 1, ...) or a name");
      }
    }
  }
  return source;
}

nlohmann::json MotionSourceToJson(const MotionSource& source) {
  json out = {{"file", source.file.generic_string()}};
  if (!source.mapping.empty()) out["mapping"] = source.mapping.generic_string();
  if (source.first_frame && source.last_frame)
    out["frames"] = json::array({*source.first_frame, *source.last_frame});
  if (!source.animation_name.empty()) {
    out["animation"] = source.animation_name;
  } else if (source.animation_index) {
    out["animation"] = *source.animation_index;
  }
  return out;
}

bool IsBvhFile(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".bvh";
}

Result<RawClip> MakeMotionClip(const MotionSource& source, const RawClip& clip,
                               const std::filesystem::path& folder, const Mesh& mesh,
                               const std::filesystem::path& mesh_file,
                               const ImportOptions& mesh_import, const RigModel& model) {
  auto resolve = [&](const std::filesystem::path& p) { return p.is_absolute() ? p : folder / p; };
  const std::filesystem::path file = resolve(source.file);
  RawClip made;
  if (IsBvhFile(file)) {
    Result<MotionCapture> motion = LoadBvh(file);
    if (!motion) return Error{"/motion/file: " + motion.error()};
    Result<MotionMapping> mapping = LoadMotionMapping(resolve(source.mapping));
    if (!mapping) return Error{"/motion/mapping: " + mapping.error()};
    RetargetOptions options;
    options.clip_name = clip.name;
    options.first_frame = source.first_frame.value_or(0);
    options.last_frame = source.last_frame;
    Result<RetargetedMotion> retargeted =
        RetargetMotion(motion.value(), mapping.value(), model, options);
    if (!retargeted) {
      const std::string& e = retargeted.error();
      return Error{(e.starts_with("frames: ") ? "/motion/" : "/motion/mapping: ") + e};
    }
    made = std::move(retargeted.value().clip);
  } else {
    AssetAnimationOptions options;
    options.clip_name = clip.name;
    options.animation_name = source.animation_name;
    options.animation_index = source.animation_index.value_or(0);
    std::error_code ec;
    if (!mesh_file.empty() && std::filesystem::equivalent(file, mesh_file, ec))
      options.import = mesh_import;
    options.import.isolation = mesh_import.isolation;  // every Assimp read of the scene's files
    Result<RawClip> animation = ClipFromAssetAnimation(file, mesh, model, options);
    if (!animation) {
      const std::string& e = animation.error();
      const bool about_animation = e.find(": animation index ") != std::string::npos ||
                                   e.find(": no animation named ") != std::string::npos;
      return Error{(about_animation ? "/motion/animation: " : "/motion/file: ") + e};
    }
    made = std::move(animation).value();
  }
  made.name = clip.name;
  made.loop = clip.loop;

  // The clip's own tracks: loads and boundaries on top of the motion, first checked alone
  // against the motion's duration so that an error names the clip's own index.
  RawClip own_tracks = clip;
  own_tracks.duration = made.duration;
  if (std::string e = ValidateRawClip(own_tracks); !e.empty()) {
    char seconds[48];
    std::snprintf(seconds, sizeof seconds, "%.6g", made.duration);
    return Error{": " + e + " (the motion lasts " + seconds + " s)"};
  }
  for (std::size_t i = 0; i < clip.parts.size(); ++i) {
    const RawPartTracks& own = clip.parts[i];
    const auto it = std::find_if(made.parts.begin(), made.parts.end(),
                                 [&](const RawPartTracks& t) { return t.part == own.part; });
    if (it == made.parts.end()) {
      made.parts.push_back(own);
      continue;
    }
    RawPartTracks merged = own;
    if (std::string e =
            MergeMotionTracks(it->channels, "/parts/" + std::to_string(i), merged.channels);
        !e.empty())
      return Error{e};
    *it = std::move(merged);
  }
  made.profiles.insert(made.profiles.end(), clip.profiles.begin(), clip.profiles.end());
  return made;
}

}  // namespace wirerig
