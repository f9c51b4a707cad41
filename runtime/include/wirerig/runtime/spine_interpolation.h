// Interpolation along a sampled spine (samples at v_k = k / (n - 1)): the point by linear
// interpolation, the frame by slerp between the neighbouring samples' frames. The same function
// serves rest and deformed spines, so rest geometry is reproduced exactly.
#pragma once

#include <span>

#include "wirerig/runtime/curve.h"

namespace wirerig {

// The rotation whose columns are the frame's (normal, binormal, tangent): local spine
// coordinates to world axes.
Mat3 FrameAxes(const Frame& frame);

// Needs points.size() == frames.size() >= 2; v is clamped to [0, 1].
Frame InterpolateSpine(std::span<const Vec3> points, std::span<const Frame> frames, double v,
                       Vec3* point);

// Rotation-minimizing frames along sampled `points` (double reflection between samples),
// starting from `start` turned minimally onto the first segment's direction. Rest and deformed
// spines both take their frames from here, so an undeformed spine keeps its frames exactly.
// Needs frames.size() == points.size() >= 2.
void PropagateSpineFrames(std::span<const Vec3> points, const Frame& start,
                          std::span<Frame> frames);

// Two planar profile loops along a spine, a before b (each with its plane's origin and normal,
// the normal pointing along the spine): they cross when a point of a lies beyond b's plane or a
// point of b lies behind a's.
bool ProfilesCross(std::span<const Vec3> a_points, const Vec3& a_origin, const Vec3& a_normal,
                   std::span<const Vec3> b_points, const Vec3& b_origin, const Vec3& b_normal);

}  // namespace wirerig
