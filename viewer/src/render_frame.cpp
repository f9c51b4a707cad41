#include "wirerig/viewer/render_frame.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "color_maps.h"

namespace wirerig {

Vec3f EvaluateColorMap(ColorMap map, float t) {
  const auto& stops = ColorMapStops(map);
  if (std::isnan(t) || t <= 0.0f) return stops[0];
  if (t >= 1.0f) return stops[kColorMapStops - 1];
  const float x = t * float(kColorMapStops - 1);
  const int i = std::min(int(x), kColorMapStops - 2);
  const float f = x - float(i);
  return (1.0f - f) * stops[i] + f * stops[i + 1];
}

FrameBounds ComputeFrameBounds(const RenderFrame& frame) {
  FrameBounds b;
  b.min = Vec3f::Constant(std::numeric_limits<float>::max());
  b.max = Vec3f::Constant(std::numeric_limits<float>::lowest());
  auto add = [&b](const Vec3f& p) {
    if (!p.allFinite()) return;
    b.min = b.min.cwiseMin(p);
    b.max = b.max.cwiseMax(p);
    b.empty = false;
  };
  for (const RenderMesh& mesh : frame.meshes) {
    for (const Vec3f& p : mesh.positions) add(p);
  }
  for (const RenderPolyline& line : frame.polylines) {
    for (const Vec3f& p : line.points) add(p);
  }
  if (b.empty) return FrameBounds{};
  // Arrows are scaled by the frame size, so they join the bounds only by their origins.
  for (const RenderArrow& arrow : frame.arrows) add(arrow.origin);
  return b;
}

void ComputeVertexNormals(std::span<const Vec3f> positions, std::span<const Triangle> triangles,
                          std::span<Vec3f> normals) {
  const std::size_t n = std::min(positions.size(), normals.size());
  for (std::size_t i = 0; i < n; ++i) normals[i].setZero();
  for (const Triangle& t : triangles) {
    if (t[0] >= n || t[1] >= n || t[2] >= n) continue;
    const Vec3f& a = positions[t[0]];
    const Vec3f& b = positions[t[1]];
    const Vec3f& c = positions[t[2]];
    const Vec3f area_normal = (b - a).cross(c - a);  // |.| = twice the area
    normals[t[0]] += area_normal;
    normals[t[1]] += area_normal;
    normals[t[2]] += area_normal;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const float length = normals[i].norm();
    normals[i] = length > 1e-20f ? Vec3f(normals[i] / length) : Vec3f::UnitY();
  }
}

}  // namespace wirerig
