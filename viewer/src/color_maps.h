// The colour-map stops shared by EvaluateColorMap (legend, CPU) and the mesh shader.
#pragma once

#include <array>

#include "wirerig/viewer/render_frame.h"

namespace wirerig {

inline constexpr int kColorMapStops = 5;

// Linear RGB stops at t = 0, 0.25, 0.5, 0.75, 1.
inline const std::array<Vec3f, kColorMapStops>& ColorMapStops(ColorMap map) {
  // sRGB values of Moreland's cool-warm and of matplotlib's viridis, converted to linear.
  static const std::array<Vec3f, kColorMapStops> kCoolWarm = {
      Vec3f(0.0437f, 0.0727f, 0.527f), Vec3f(0.266f, 0.434f, 0.991f), Vec3f(0.721f, 0.721f, 0.721f),
      Vec3f(0.909f, 0.324f, 0.197f), Vec3f(0.457f, 0.0012f, 0.0194f)};
  static const std::array<Vec3f, kColorMapStops> kViridis = {
      Vec3f(0.0578f, 0.0004f, 0.0887f), Vec3f(0.0437f, 0.0844f, 0.258f),
      Vec3f(0.0152f, 0.283f, 0.262f), Vec3f(0.112f, 0.584f, 0.122f),
      Vec3f(0.982f, 0.799f, 0.0185f)};
  return map == ColorMap::kViridis ? kViridis : kCoolWarm;
}

}  // namespace wirerig
