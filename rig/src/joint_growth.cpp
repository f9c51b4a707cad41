#include "joint_growth.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "limb_volume.h"
#include "wirerig/rig/skin_quality.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {
namespace {

constexpr double kFitDegrees = 90.0;
constexpr double kSmallestBend = 30.0;

// The joint's bends the fit weighs: per bend axis and direction, kFitDegrees or the limit.
std::vector<Vec3> FitBends(const JointModel& joint) {
  std::vector<Vec3> out;
  if (joint.type == JointType::kFixed) return out;
  const int axes = joint.type == JointType::kHinge ? 1 : 2;
  for (int axis = 0; axis < axes; ++axis)
    for (double sign : {1.0, -1.0}) {
      const double limit = sign > 0 ? joint.max_degrees[axis] : -joint.min_degrees[axis];
      const double degrees = std::min(kFitDegrees, limit);
      if (!(degrees >= kSmallestBend)) continue;
      Vec3 angles = Vec3::Zero();
      angles[axis] = sign * degrees;
      out.push_back(angles);
    }
  return out;
}

}  // namespace

void FitJointGrowth(std::span<const Vec3> rest, RigModel* model) {
  RigWorkspace workspace = MakeRigWorkspace(*model);
  std::vector<Vec3> posed(rest.size());
  std::vector<PartPose> poses(model->parts.size());
  const std::vector<std::uint32_t> surface_border = SurfaceBorder(model->triangles);
  for (std::size_t c = 1; c < model->parts.size(); ++c) {
    JointModel& joint = model->parts[c].joint;
    if (model->parts[c].parent < 0 || !(joint.blend_length > 0.0)) continue;
    if (IsSkinless(model->parts[c])) continue;  // its bridge only blends: no growth
    const std::vector<Vec3> bends = FitBends(joint);
    if (bends.empty()) continue;
    const Limb limb = LimbOf(*model, c, surface_border);
    const double rest_volume = LimbVolume(limb, rest, model->triangles);
    if (!(std::abs(rest_volume) > 0.0)) continue;
    // Volume at growth_scale s: v0 + s (v1 - v0), per bend; least squares for v = rest.
    auto volume = [&](const Vec3& degrees, double scale) {
      joint.growth_scale = scale;
      poses[c].rotation = JointRotation(joint, degrees);
      EvaluateRigJob job;
      job.model = model;
      job.poses = poses;
      job.workspace = &workspace;
      job.positions = posed;
      const bool ok = job.Run().ok();
      return ok ? LimbVolumeRatio(limb, rest, posed, model->triangles) : 1.0;
    };
    double numerator = 0.0, denominator = 0.0;
    for (const Vec3& degrees : bends) {
      const double v0 = volume(degrees, 0.0), v1 = volume(degrees, 1.0);
      numerator += (1.0 - v0) * (v1 - v0);
      denominator += (v1 - v0) * (v1 - v0);
    }
    poses[c] = PartPose{};
    joint.growth_scale =
        denominator > 1e-12 ? std::clamp(numerator / denominator, 0.0, kMaxGrowthScale) : 1.0;
  }
}

}  // namespace wirerig
