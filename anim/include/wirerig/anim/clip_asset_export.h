// A clip played offline (Playback: keyed forces, joint angles, articulated dynamics, rigid
// bodies) and sampled at a fixed rate into the runtime's clip asset (runtime/clip_asset.h), so
// an engine replays it with the runtime alone.
#pragma once

#include "wirerig/anim/playback.h"
#include "wirerig/rig/result.h"
#include "wirerig/runtime/clip_asset.h"

namespace wirerig {

// Frames at k / fps for k = 0 .. ceil(duration * fps), the last at the clip's end. Errors name
// the option or the playback's failure. Wire dynamics (playback.wires) is not in the asset
// format yet: the clip is sampled with static wires (the keyed loads, the rigid bodies' motion),
// as the engine replays it; `wirerig build` says so.
Result<SampledClip> SampleClipForRuntime(const RigModel& model, const Clip& clip,
                                         const PlaybackOptions& playback, double fps);

}  // namespace wirerig
