// A clip played offline (Playback: keyed forces, joint angles, articulated dynamics, rigid
// bodies) and sampled at a fixed rate into the runtime's clip asset (runtime/clip_asset.h), so
// an engine replays it with the runtime alone.
#pragma once

#include <string>
#include <vector>

#include "wirerig/anim/playback.h"
#include "wirerig/io/result.h"
#include "wirerig/runtime/clip_asset.h"

namespace wirerig {

// The most frames a sampled clip may have (each is a full evaluation; ~1 GB of asset).
inline constexpr double kMaxClipAssetFrames = 1e6;

// Frames at k / fps for k = 0 .. ceil(duration * fps), the last at the clip's end. Errors name
// the option, a clip of more than kMaxClipAssetFrames frames (refused before any work) or the
// playback's failure. With wire dynamics (playback.wires), each wire's motion
// beyond its static shape is recorded per frame (SampledClip::wires, wire_motion), so the
// engine replays what the bake shows; between frames it is interpolated linearly.
// `warnings`, if given, gets each part's worst deflection beyond its length (DeflectionWarning),
// as a bake reports them.
Result<SampledClip> SampleClipForRuntime(const RigModel& model, const Clip& clip,
                                         const PlaybackOptions& playback, double fps,
                                         std::vector<std::string>* warnings = nullptr);

}  // namespace wirerig
