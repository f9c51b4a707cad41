#include "motion_floor.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "wirerig/anim/clip_sampling.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {
namespace {

// The lowest skin point's height for `poses`, or nothing when the evaluation fails.
std::optional<double> LowestPoint(const RigModel& model, std::span<const PartPose> poses,
                                  RigWorkspace* workspace, std::vector<Vec3>* positions) {
  EvaluateRigJob job;
  job.model = &model;
  job.poses = poses;
  job.workspace = workspace;
  job.positions = *positions;
  if (!job.Run()) return std::nullopt;
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vec3& p : *positions) lowest = std::min(lowest, p.y());
  return lowest;
}

}  // namespace

Result<double> LiftAboveFloor(const RigModel& model, const std::string& root_part, RawClip* clip) {
  auto root = std::find_if(clip->parts.begin(), clip->parts.end(),
                           [&](const RawPartTracks& t) { return t.part == root_part; });
  if (root == clip->parts.end() || model.vertices.empty()) return 0.0;
  Result<Clip> built = BuildClip(*clip, model);
  if (!built) return Error{"keeping the skin above the floor: " + built.error()};
  RigWorkspace workspace = MakeRigWorkspace(model);
  std::vector<Vec3> positions(model.vertices.size());
  const std::vector<PartPose> rest_poses(model.parts.size());
  const std::optional<double> floor = LowestPoint(model, rest_poses, &workspace, &positions);
  if (!floor) return Error{"keeping the skin above the floor: the rest pose does not evaluate"};
  ClipSample sample = MakeClipSample(built.value(), model);
  double largest = 0.0;
  for (RawKey<Vec3>& key : root->channels.translation.keys) {
    SampleClip(built.value(), key.time, &sample);
    const std::optional<double> lowest = LowestPoint(model, sample.poses, &workspace, &positions);
    if (!lowest)
      return Error{"keeping the skin above the floor: the pose at " + std::to_string(key.time) +
                   " s does not evaluate"};
    const double lift = std::max(0.0, *floor - *lowest);
    key.value.y() += lift;
    largest = std::max(largest, lift);
  }
  return largest;
}

}  // namespace wirerig
