// Picking wires with the mouse: the polyline nearest to a pixel, within a few pixels, and the
// parameter along it, so that a drag can apply a point force there.
#pragma once

#include <cstdint>
#include <span>

#include "wirerig/viewer/camera.h"
#include "wirerig/viewer/render_frame.h"

namespace wirerig {

struct WirePick {
  bool hit = false;
  int polyline = -1;     // index into the span searched
  std::uint32_t id = 0;  // RenderPolyline::id of that polyline
  // Wire parameter v in [0, 1] at the picked point, proportional to arc length from the first
  // point (for a closed polyline, along the loop back to the first point).
  float parameter = 0.0f;
  Vec3f point = Vec3f::Zero();  // the picked point on the polyline, m
  float pixel_distance = 0.0f;  // from the query pixel to the projected polyline
};

// The pickable polyline whose projection passes nearest to `pixel` (image of `size`, pixels
// from the top-left), if within `max_pixels`. Ties within half a pixel go to the polyline
// nearer the eye. Segments with an end behind the eye are skipped. Allocation-free.
WirePick PickPolyline(std::span<const RenderPolyline> polylines, const Camera& camera, Size size,
                      const Vec2f& pixel, float max_pixels = 6.0f);

// The point at parameter v in [0, 1] (by arc length) along a polyline: the inverse of the
// parameter PickPolyline returns. Returns the first point for a polyline of one point.
Vec3f PointAtParameter(const RenderPolyline& polyline, float v);

}  // namespace wirerig
