#include "wirerig/viewer/picking.h"

#include <algorithm>
#include <cmath>

namespace wirerig {
namespace {

float PolylineLength(const RenderPolyline& line) {
  float length = 0.0f;
  const std::size_t n = line.points.size();
  for (std::size_t i = 1; i < n; ++i) length += (line.points[i] - line.points[i - 1]).norm();
  if (line.closed && n > 2) length += (line.points[0] - line.points[n - 1]).norm();
  return length;
}

}  // namespace

WirePick PickPolyline(std::span<const RenderPolyline> polylines, const Camera& camera, Size size,
                      const Vec2f& pixel, float max_pixels) {
  WirePick best;
  float best_depth = 0.0f;
  for (std::size_t l = 0; l < polylines.size(); ++l) {
    const RenderPolyline& line = polylines[l];
    const std::size_t n = line.points.size();
    if (!line.pickable || n < 2) continue;
    const std::size_t segments = line.closed && n > 2 ? n : n - 1;
    const float total = PolylineLength(line);
    float along = 0.0f;  // arc length at the segment start
    for (std::size_t s = 0; s < segments; ++s) {
      const Vec3f& a = line.points[s];
      const Vec3f& b = line.points[(s + 1) % n];
      const float segment_length = (b - a).norm();
      Vec2f pa, pb;
      float da = 0.0f, db = 0.0f;
      if (ProjectToPixel(camera, size, a, &pa, &da) && ProjectToPixel(camera, size, b, &pb, &db)) {
        const Vec2f ab = pb - pa;
        const float ab2 = ab.squaredNorm();
        const float t = ab2 > 1e-12f ? std::clamp((pixel - pa).dot(ab) / ab2, 0.0f, 1.0f) : 0.0f;
        const float distance = (pa + t * ab - pixel).norm();
        const float depth = da + t * (db - da);
        const bool closer = !best.hit || distance < best.pixel_distance - 0.5f ||
                            (distance < best.pixel_distance + 0.5f && depth < best_depth);
        if (distance <= max_pixels && closer) {
          best.hit = true;
          best.polyline = static_cast<int>(l);
          best.id = line.id;
          // Screen-space t is close enough to the 3D one for a segment a few pixels long.
          best.point = a + t * (b - a);
          best.parameter =
              total > 0.0f ? std::clamp((along + t * segment_length) / total, 0.0f, 1.0f) : 0.0f;
          best.pixel_distance = distance;
          best_depth = depth;
        }
      }
      along += segment_length;
    }
  }
  return best;
}

Vec3f PointAtParameter(const RenderPolyline& line, float v) {
  const std::size_t n = line.points.size();
  if (n == 0) return Vec3f::Zero();
  if (n == 1) return line.points[0];
  const float target = std::clamp(v, 0.0f, 1.0f) * PolylineLength(line);
  const std::size_t segments = line.closed && n > 2 ? n : n - 1;
  float along = 0.0f;
  for (std::size_t s = 0; s < segments; ++s) {
    const Vec3f& a = line.points[s];
    const Vec3f& b = line.points[(s + 1) % n];
    const float length = (b - a).norm();
    if (along + length >= target && length > 0.0f) return a + ((target - along) / length) * (b - a);
    along += length;
  }
  return line.closed ? line.points[0] : line.points[n - 1];
}

}  // namespace wirerig
