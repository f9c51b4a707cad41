#include "wirerig/rig/spine_curves.h"

#include <cmath>
#include <vector>

namespace wirerig {

std::vector<Vec3> SpinePoints(std::span<const ProfileCurve> profiles,
                              std::span<const std::size_t> foreign_points) {
  std::vector<Vec3> points;
  for (std::size_t k = 0; k < profiles.size(); ++k) {
    const bool junction = k < foreign_points.size() && foreign_points[k] > 0;
    points.push_back(junction ? profiles[k].origin : ProfileCentroid(profiles[k]));
  }
  return points;
}

Result<Curve> BuildSpineCurve(std::span<const Vec3> spine_points) {
  if (spine_points.size() < 2) return Error{"a spine needs at least 2 profiles"};
  Curve spine;
  const auto interpolation =
      spine_points.size() >= 3 ? CurveInterpolation::kCubic : CurveInterpolation::kLinear;
  if (const Status status = Curve::Build(spine_points, false, interpolation, &spine); !status)
    return Error{"spine through the profile centroids: " + ToString(status)};
  return spine;
}

double ClosestParameter(const Curve& spine, const Vec3& point) {
  // Dense scan, then golden-section refinement in the best bracket.
  constexpr int kSamples = 256;
  int best = 0;
  double best_distance = (spine.Position(0.0) - point).squaredNorm();
  for (int i = 1; i <= kSamples; ++i) {
    const double d = (spine.Position(double(i) / kSamples) - point).squaredNorm();
    if (d < best_distance) best = i, best_distance = d;
  }
  double lo = std::max(0, best - 1) / double(kSamples);
  double hi = std::min(kSamples, best + 1) / double(kSamples);
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double a = hi - ratio * (hi - lo), b = lo + ratio * (hi - lo);
    if ((spine.Position(a) - point).squaredNorm() < (spine.Position(b) - point).squaredNorm())
      hi = b;
    else
      lo = a;
  }
  return 0.5 * (lo + hi);
}

}  // namespace wirerig
