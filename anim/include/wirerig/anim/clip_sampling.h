// Sampling a clip: every pose and load of the rig at one clip-local time, into buffers made
// once per (model, clip). SampleClip never allocates; the spans in `poses` and
// `profile_loads` point into the sample's own buffers and stay valid until the next call.
#pragma once

#include <span>

#include <vector>

#include "wirerig/anim/clip.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {

struct ClipSample {
  const RigModel* model = nullptr;  // the model the buffers were made for
  std::vector<PartPose> poses;      // one per part, for EvaluateRigJob
  std::vector<ProfileLoads> profile_loads;
  // Backing storage for the spans above.
  std::vector<std::vector<PointLoad>> point_loads;  // per part, then per profile group
  std::vector<std::vector<LineLoad>> line_loads;
  std::vector<std::vector<AxialPointLoad>> axial_point_loads;  // per part
  std::vector<std::vector<AxialLineLoad>> axial_line_loads;
};

// Buffers sized for the clip on its model (which must outlive the sample).
ClipSample MakeClipSample(const Clip& clip, const RigModel& model);

// Fills `sample` with the clip's inputs at clip-local time t (s; see Clip::LocalTime):
//  * point loads: force = magnitude * direction / |direction| at v = clamp(at, 0, 1); a zero
//    direction or magnitude gives no force; world directions turn into the rest frame of the
//    spine sample (or profile) nearest the load;
//  * line loads: the stretch [clamp(from), clamp(to)]; a stretch of zero width is skipped;
//  * the boundary family of the last boundary key at or before t (cantilever_free if none);
//    a tip force only reaches cantilevers;
//  * pose: rotation exp(axis-angle), translation.
// Rigid parts' poses are left to the caller (Playback sets them from their bodies).
void SampleClip(const Clip& clip, double t, ClipSample* sample);

// Every part's rigid placement for `poses` (each relative to its parent, as the rig composes
// them; parents come before their children): rest world point x -> rotations[p] x +
// translations[p] in the world. The spans hold one element per part of `model`.
void ComposePlacements(const RigModel& model, std::span<const PartPose> poses,
                       std::span<Mat3> rotations, std::span<Vec3> translations);

}  // namespace wirerig
