// The check that geometry can be handed to float consumers (glTF export, the renderer): every
// coordinate finite, and finite once rounded to float. Shared by Playback::Evaluate (so render,
// view and bake fail alike on a deformation that overflowed) and ExportGltf's input check.
// None of these raise floating-point exceptions: they look at bits or call std::isfinite.
#pragma once

#include <cstddef>
#include <span>

#include "wirerig/runtime/conventions.h"

namespace wirerig::detail {

inline constexpr std::size_t kAllFinite = static_cast<std::size_t>(-1);

// The first of `count` 3-float vectors (vector i at values[i * stride .. + 3), stride >= 3)
// with an infinite or NaN component, or kAllFinite.
std::size_t FirstNonFiniteFloat3(std::span<const float> values, std::size_t count,
                                 std::size_t stride = 3);

// The first vector with a component that is not finite, or beyond the float range (it would
// round to infinity), or kAllFinite.
std::size_t FirstNotFloatFinite(std::span<const Vec3> values);

}  // namespace wirerig::detail
