#include "wirerig/anim/bake.h"

#include "wirerig/anim/spine_skin.h"
#include "wirerig/runtime/spine_interpolation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace wirerig {
namespace {

// The rotation whose columns are the frame's (normal, binormal, tangent).
Quat FrameRotation(const Frame& f) { return Quat(FrameAxes(f)).normalized(); }

void AddSpines(const RigModel& model, std::size_t keys, BakedAnimation& bake) {
  for (const PartModel& part : model.parts) {
    BakedSpine spine;
    spine.name = part.name;
    spine.parent = part.parent;
    if (part.parent >= 0) {
      const std::size_t n = model.parts[part.parent].spine_points.size();
      spine.parent_joint =
          static_cast<int>(std::lround(part.attachment * static_cast<double>(n - 1)));
    }
    spine.rest_points = part.spine_points;
    for (const Frame& f : part.spine_frames) spine.rest_rotations.push_back(FrameRotation(f));
    spine.points.reserve(keys * part.spine_points.size());
    spine.rotations.reserve(keys * part.spine_points.size());
    bake.spines.push_back(std::move(spine));
  }
}

}  // namespace

std::string DeflectionWarning(const PartModel& part, const PartWarnings& warning, double t) {
  if (!(warning.max_deflection_ratio > 1.0)) return {};
  char text[320];
  std::snprintf(text, sizeof text,
                "part \"%s\": its deflection reached %.3g m (%.3g x its length %.3g m) at t = "
                "%.3g s: linear beam theory no longer holds (the loads are far too large for its "
                "stiffness)",
                part.name.c_str(), warning.max_deflection_ratio * part.spine_length,
                warning.max_deflection_ratio, part.spine_length, t);
  return text;
}

double BakeKeyCount(double duration, double fps) {
  // As BakeKeyTimes counts: whole frames from 0, plus the end when no frame sits on it.
  const double whole = std::floor(duration * fps + 1e-9);
  return whole + 1.0 + (duration - whole / fps > 1e-6 / fps ? 1.0 : 0.0);
}

double EstimateBakeBytes(const Mesh& mesh, const RigModel& model, double keys,
                         const BakeOptions& options) {
  const double vertex = sizeof(Vec3f) * (options.normals ? 2.0 : 1.0);
  double spine_samples = 0.0;
  for (const PartModel& part : model.parts) spine_samples += double(part.spine_points.size());
  const double per_key = vertex * double(mesh.positions.size()) +
                         (sizeof(Vec3) + sizeof(Quat)) * spine_samples + sizeof(double);
  return keys * per_key;
}

std::string KeyCountText(double keys) {
  char text[32];
  std::snprintf(text, sizeof text, keys < 1e15 ? "%.0f" : "%.3g", keys);
  return text;
}

std::vector<double> BakeKeyTimes(double duration, double fps) {
  std::vector<double> times;
  const auto whole = static_cast<std::size_t>(std::floor(duration * fps + 1e-9));
  for (std::size_t k = 0; k <= whole; ++k) times.push_back(static_cast<double>(k) / fps);
  // The clip's end, unless a frame already sits on it (or a hair before it).
  if (duration - times.back() > 1e-6 / fps) times.push_back(duration);
  return times;
}

Result<BakedAnimation> BakeClip(const Mesh& mesh, const RigModel& model, const Clip& clip,
                                const PlaybackOptions& playback, const BakeOptions& options) {
  if (!(std::isfinite(options.fps) && options.fps >= 1.0 && options.fps <= 1000.0))
    return Error{"fps: must be in [1, 1000] keys per second"};
  if (mesh.weld_map.size() != mesh.positions.size() ||
      mesh.welded_positions.size() != model.vertices.size())
    return Error{"mesh: is not the mesh the rig model was built on (vertex counts differ)"};
  // The size first: a clip of 1e5 s must be refused here, not by std::bad_alloc below.
  const double key_count = BakeKeyCount(clip.duration, options.fps);
  if (const double bytes = EstimateBakeBytes(mesh, model, key_count, options);
      !(bytes <= options.max_bytes)) {
    char message[320];
    std::snprintf(message, sizeof message,
                  "the bake would hold %s keys (%g s at %g keys/s) x %zu vertices = %.3g GB, "
                  "more than the %.3g GB a bake may take; bake a shorter clip or fewer keys per "
                  "second",
                  KeyCountText(key_count).c_str(), clip.duration, options.fps,
                  mesh.positions.size(), bytes / 1e9, options.max_bytes / 1e9);
    return Error{message};
  }
  SpineSkin skin;
  if (options.skin) {
    SpineSkinOptions skin_options;
    skin_options.spread = options.skin_spread;
    Result<SpineSkin> built = BuildSpineSkin(model, mesh, skin_options);
    if (!built) return Error{"skin: " + built.error()};
    skin = std::move(built).value();
  }
  Result<Playback> made = Playback::Make(model, clip, playback);
  if (!made) return Error{made.error()};
  Playback& player = made.value();

  BakedAnimation bake;
  bake.name = clip.name;
  bake.fps = options.fps;
  bake.times = BakeKeyTimes(clip.duration, options.fps);
  const std::size_t keys = bake.times.size(), render = mesh.positions.size();
  bake.vertex_count = render;
  bake.positions.resize(keys * render);
  if (options.normals) bake.normals.resize(keys * render);
  AddSpines(model, keys, bake);
  bake.skin_joints = std::move(skin.joints);
  bake.skin_weights = std::move(skin.weights);

  // Per part: the frame's warnings, and the worst deflection over the keys (ratio, time).
  std::vector<PartWarnings> frame(model.parts.size());
  std::vector<std::pair<PartWarnings, double>> worst(model.parts.size());
  for (std::size_t k = 0; k < keys; ++k) {
    const double t = bake.times[k];
    // The key's vertices straight into the bake, in the mesh's own (unwelded) order.
    auto key = [&](std::vector<Vec3f>& all) {
      return all.empty() ? std::span<float>()
                         : std::span<float>(all.data()->data() + 3 * k * render, 3 * render);
    };
    Playback::FloatOutput output;
    output.positions = key(bake.positions);
    if (options.normals) output.normals = key(bake.normals);
    output.vertex_order = mesh.weld_map;
    // Clip-local time of the key: a baked clip covers [0, duration] once, whatever its loop.
    if (Status s =
            player.Evaluate(std::min(t, clip.duration - 1e-12 * clip.duration), output, frame);
        !s) {
      // A part's failure by its name rather than its index.
      const bool part =
          s.field == "parts" && s.index >= 0 && std::size_t(s.index) < model.parts.size();
      return Error{"key at t = " + std::to_string(t) + " s: " +
                   (part ? "part \"" + model.parts[std::size_t(s.index)].name + "\" (" +
                               std::string(s.member) + "): " + std::string(s.reason)
                         : ToString(s))};
    }
    for (std::size_t p = 0; p < frame.size(); ++p)
      if (frame[p].max_deflection_ratio > worst[p].first.max_deflection_ratio)
        worst[p] = {frame[p], t};
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
      BakedSpine& spine = bake.spines[p];
      const std::vector<Vec3>& points = player.workspace().spine_points[p];
      const std::vector<Frame>& frames = player.workspace().spine_frames[p];
      spine.points.insert(spine.points.end(), points.begin(), points.end());
      for (const Frame& f : frames) spine.rotations.push_back(FrameRotation(f));
    }
    if (options.progress) options.progress(k + 1, keys);
  }
  for (std::size_t p = 0; p < worst.size(); ++p)
    if (std::string w = DeflectionWarning(model.parts[p], worst[p].first, worst[p].second);
        !w.empty())
      bake.warnings.push_back(std::move(w));
  return bake;
}

}  // namespace wirerig
