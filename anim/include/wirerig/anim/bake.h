// Baking: a clip played on a scene's rig, sampled at a fixed frame rate into positions and
// normals per render vertex and the deformed spine frames per key (BakedAnimation), ready for
// ExportGltf. Keys sit at k / fps from 0, plus the clip's end when the duration is not a whole
// number of frames; rigid-body dynamics is integrated once, in order.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "wirerig/anim/baked_animation.h"
#include "wirerig/anim/clip.h"
#include "wirerig/anim/playback.h"
#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/runtime/rig_model.h"

namespace wirerig {

struct BakeOptions {
  double fps = 30.0;    // keys per second, in [1, 1000]
  bool normals = true;  // bake normals too
  // Fill the skin (BakedAnimation::skin_joints, skin_weights) for skin-mode export, from the
  // rig's binding (BuildSpineSkin with this tent spread).
  bool skin = false;
  double skin_spread = 1.0;
  // Called after every key with (keys done, keys in all); may be empty.
  std::function<void(std::size_t, std::size_t)> progress;
  // Largest bake held in memory (EstimateBakeBytes), bytes: a longer clip is refused with the
  // numbers before anything is allocated.
  double max_bytes = 4.0 * 1024 * 1024 * 1024;
};

// "part \"arm\": its deflection reached 3e+24 m (1.5e+24 x its length 2 m) at t = 0.5 s: ...",
// when `warning.max_deflection_ratio` exceeds 1 (linear beam theory no longer holds), else empty.
std::string DeflectionWarning(const PartModel& part, const PartWarnings& warning, double t);

// The key times of a clip of `duration` seconds at `fps`.
std::vector<double> BakeKeyTimes(double duration, double fps);
// How many key times BakeKeyTimes gives, without making them; a double, since a long clip at a
// high rate can have more keys than memory holds (or than size_t counts).
// A key count for messages: exact below 1e15 ("100000001"), else in scientific form.
std::string KeyCountText(double keys);

double BakeKeyCount(double duration, double fps);
// The bytes a bake of `keys` keys holds: float positions (and normals) per render vertex and
// the spine points and rotations per key.
double EstimateBakeBytes(const Mesh& mesh, const RigModel& model, double keys,
                         const BakeOptions& options);

// `mesh` must be the mesh `model` was built on (its weld map gives the render vertices).
// Parts whose deflection exceeds their length at some key are listed in the bake's warnings
// (the worst key of each). Errors name the option, a bake larger than options.max_bytes (with its
// keys, vertices and bytes; refused before anything is allocated), or the key time at which
// evaluation failed and why.
Result<BakedAnimation> BakeClip(const Mesh& mesh, const RigModel& model, const Clip& clip,
                                const PlaybackOptions& playback, const BakeOptions& options = {});

}  // namespace wirerig
