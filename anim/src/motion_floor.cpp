#include "motion_floor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "wirerig/anim/clip_sampling.h"
#include "wirerig/runtime/parallel.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {
namespace {

// One thread's scratch: a workspace, a clip sample and float positions.
struct LowestPointScratch {
  RigWorkspace workspace;
  ClipSample sample;
  std::vector<float> positions;
};

// The lowest skin point's height for `poses` (the float evaluation, positions only), or
// nothing when the evaluation fails.
std::optional<double> LowestPoint(const RigModel& model, std::span<const PartPose> poses,
                                  LowestPointScratch* scratch) {
  EvaluateRigJob job;
  job.model = &model;
  job.poses = poses;
  job.workspace = &scratch->workspace;
  job.float_positions = scratch->positions;
  if (!job.Run()) return std::nullopt;
  float lowest = std::numeric_limits<float>::infinity();
  for (std::size_t i = 1; i < scratch->positions.size(); i += 3)
    lowest = std::min(lowest, scratch->positions[i]);
  return double(lowest);
}

}  // namespace

Result<double> LiftAboveFloor(const RigModel& model, const std::string& root_part, RawClip* clip) {
  auto root = std::find_if(clip->parts.begin(), clip->parts.end(),
                           [&](const RawPartTracks& t) { return t.part == root_part; });
  if (root == clip->parts.end() || model.vertices.empty()) return 0.0;
  Result<Clip> built = BuildClip(*clip, model);
  if (!built) return Error{"keeping the skin above the floor: " + built.error()};
  std::vector<RawKey<Vec3>>& keys = root->channels.translation.keys;
  // One task per thread, each with its own scratch over a run of consecutive keys (poses of a
  // capture cost alike); everything allocated here, before the tasks (which must not throw).
  const std::size_t tasks = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1,
                                                    std::max<std::size_t>(keys.size(), 1));
  std::vector<LowestPointScratch> scratch;
  for (std::size_t i = 0; i < tasks; ++i)
    scratch.push_back({MakeRigWorkspace(model), MakeClipSample(built.value(), model),
                       std::vector<float>(3 * model.vertices.size())});
  const std::vector<PartPose> rest_poses(model.parts.size());
  const std::optional<double> floor = LowestPoint(model, rest_poses, &scratch[0]);
  if (!floor) return Error{"keeping the skin above the floor: the rest pose does not evaluate"};

  // Each key's lowest point (NaN where the pose does not evaluate).
  std::vector<double> lowest(keys.size(), std::numeric_limits<double>::quiet_NaN());
  const ThreadPool pool(tasks);
  RunEach(&pool, tasks, [&](std::size_t k) {
    LowestPointScratch& s = scratch[k];
    for (std::size_t i = k * keys.size() / tasks; i < (k + 1) * keys.size() / tasks; ++i) {
      SampleClip(built.value(), keys[i].time, &s.sample);
      if (const std::optional<double> y = LowestPoint(model, s.sample.poses, &s)) lowest[i] = *y;
    }
  });
  double largest = 0.0;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (std::isnan(lowest[i]))
      return Error{"keeping the skin above the floor: the pose at " + std::to_string(keys[i].time) +
                   " s does not evaluate"};
    const double lift = std::max(0.0, *floor - lowest[i]);
    keys[i].value.y() += lift;
    largest = std::max(largest, lift);
  }
  return largest;
}

}  // namespace wirerig
