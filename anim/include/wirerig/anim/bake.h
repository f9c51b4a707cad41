// Baking: a clip played on a scene's rig, sampled at a fixed frame rate into positions and
// normals per render vertex and the deformed spine frames per key (BakedAnimation), ready for
// ExportGltf. Keys sit at k / fps from 0, plus the clip's end when the duration is not a whole
// number of frames; rigid-body dynamics is integrated once, in order.
#pragma once

#include <cstddef>
#include <functional>

#include "wirerig/anim/baked_animation.h"
#include "wirerig/anim/clip.h"
#include "wirerig/anim/playback.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/rig/result.h"
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
};

// The key times of a clip of `duration` seconds at `fps`.
std::vector<double> BakeKeyTimes(double duration, double fps);

// `mesh` must be the mesh `model` was built on (its weld map gives the render vertices).
// Errors name the option, or the key time at which evaluation failed and why.
Result<BakedAnimation> BakeClip(const Mesh& mesh, const RigModel& model, const Clip& clip,
                                const PlaybackOptions& playback, const BakeOptions& options = {});

}  // namespace wirerig
