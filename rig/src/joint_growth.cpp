#include "joint_growth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "joint_region.h"
#include "wirerig/rig/joint_sweep.h"
#include "wirerig/rig/skin_quality.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {
namespace {

// A scale above 1 is fitted only where 1 folds no edge; a fitted scale is taken back towards
// the tube's 1 (bisection, kBackOffSteps halvings) while it folds more edges than 1 does, stretches
// an edge beyond both kStretchAllowed and what 1 stretches, or narrows a cross-section below both
// kPerimeterAllowed and what 1 narrows it to.
constexpr double kStretchAllowed = 1.9;
constexpr double kPerimeterAllowed = 0.96;
constexpr int kBackOffSteps = 6;
// A direction whose volume the tube's growth changes by less than this is not fitted (its fit
// would be large and rest on noise): it keeps 1, or its opposite direction's scale.
constexpr double kLeastSensitivity = 0.01;

// The bend's direction in JointModel::growth_scales, or -1 for a twist or a two-axis pose.
int DirectionOf(const Vec3& degrees) {
  if (degrees.z() != 0.0 || (degrees.x() != 0.0) == (degrees.y() != 0.0)) return -1;
  if (degrees.x() != 0.0) return degrees.x() > 0.0 ? kGrowPlusX : kGrowMinusX;
  return degrees.y() > 0.0 ? kGrowPlusY : kGrowMinusY;
}

}  // namespace

void FitJointGrowth(std::span<const Vec3> rest, RigModel* model) {
  RigWorkspace workspace = MakeRigWorkspace(*model);
  std::vector<Vec3> posed(rest.size());
  std::vector<PartPose> poses(model->parts.size());
  const std::vector<std::uint32_t> surface_border = SurfaceBorder(model->triangles);
  const SkinQualityReference reference = MakeSkinQualityReference(rest, model->triangles);
  for (std::size_t c = 1; c < model->parts.size(); ++c) {
    JointModel& joint = model->parts[c].joint;
    if (model->parts[c].parent < 0 || !(joint.blend_length > 0.0)) continue;
    if (IsSkinless(model->parts[c])) continue;  // its bridge only blends: no growth
    const JointRegion region = MakeJointRegion(*model, c, rest, reference, surface_border);
    const double rest_volume = LimbVolume(region.limb, rest, model->triangles);
    if (!(std::abs(rest_volume) > 0.0)) continue;
    // The limb at a pose with the direction's growth scale set.
    auto measure = [&](const Vec3& degrees, int direction, double scale) {
      joint.growth_scales[direction] = scale;
      poses[c].rotation = JointRotation(joint, degrees);
      EvaluateRigJob job;
      job.model = model;
      job.poses = poses;
      job.workspace = &workspace;
      job.positions = posed;
      if (!job.Run().ok()) return SkinMeasures{};
      return MeasureJointRegion(reference, rest, posed, region, model->triangles);
    };
    const std::vector<JointSweepPose> sweep = JointSweep(joint);
    std::array<bool, 4> fitted_here = {false, false, false, false};
    for (int direction = 0; direction < 4; ++direction) {
      std::vector<Vec3> bends;
      for (const JointSweepPose& pose : sweep)
        if (DirectionOf(pose.degrees) == direction) bends.push_back(pose.degrees);
      if (bends.empty()) continue;
      // Volume at scale s: v0 + s (v1 - v0), per bend; least squares for v = rest.
      double numerator = 0.0, denominator = 0.0, sensitivity = 0.0;
      SkinMeasures tube;
      for (const Vec3& degrees : bends) {
        const double v0 = measure(degrees, direction, 0.0).volume_ratio;
        const SkinMeasures one = measure(degrees, direction, 1.0);
        numerator += (1.0 - one.volume_ratio) * (one.volume_ratio - v0);
        denominator += (one.volume_ratio - v0) * (one.volume_ratio - v0);
        sensitivity = std::max(sensitivity, std::abs(one.volume_ratio - v0));
        tube.Worst(one);
      }
      joint.growth_scales[direction] = 1.0;
      if (sensitivity < kLeastSensitivity) continue;
      fitted_here[std::size_t(direction)] = true;
      // More growth than the tube's where the tube already folds the skin would crowd it more
      // in poses the sweep does not hold (a bend with a twist: a shoulder in the mocap).
      const double most = tube.folded_edges > 0 ? 1.0 : kMaxGrowthScale;
      double fitted = std::clamp(1.0 + numerator / denominator, kMinGrowthScale, most);
      auto acceptable = [&](double scale) {
        for (const Vec3& degrees : bends) {
          const SkinMeasures m = measure(degrees, direction, scale);
          if (m.folded_edges > tube.folded_edges ||
              m.worst_stretch > std::max(kStretchAllowed, tube.worst_stretch) ||
              m.smallest_perimeter < std::min(kPerimeterAllowed, tube.smallest_perimeter))
            return false;
        }
        return true;
      };
      // Bisection between the tube's 1 (acceptable) and the fit.
      if (!acceptable(fitted)) {
        double good = 1.0, bad = fitted;
        for (int step = 0; step < kBackOffSteps; ++step) {
          const double middle = 0.5 * (good + bad);
          (acceptable(middle) ? good : bad) = middle;
        }
        fitted = good;
      }
      joint.growth_scales[direction] = fitted;
    }
    // A direction left unfitted takes its opposite's scale where that was fitted, so that the
    // scale does not jump as a bend passes through rest (an elbow swinging about its bent rest
    // pose in a walk).
    for (std::size_t d = 0; d < 4; ++d)
      if (!fitted_here[d] && fitted_here[d ^ 1])
        joint.growth_scales[d] = joint.growth_scales[d ^ 1];
    poses[c] = PartPose{};
  }
}

}  // namespace wirerig
