// The check that geometry can be handed to float consumers (glTF export, the renderer): every
// coordinate finite, finite once rounded to float, and within kMaxGeometryCoordinate. Shared by
// Playback::Evaluate (so render, view and bake fail alike on a deformation that overflowed),
// ExportGltf's input check and glTF input. None of these raise floating-point exceptions: they
// look at bits or compare.
#pragma once

#include <cstddef>
#include <limits>
#include <span>

#include "wirerig/runtime/conventions.h"

namespace wirerig::detail {

inline constexpr std::size_t kAllFinite = static_cast<std::size_t>(-1);

// The largest coordinate (m) a posed vertex may have: beyond it a float normal (the squared
// length of a vertex's sum of triangle cross products) can overflow, so the double and float
// evaluations would disagree on what is drawable. 1e7 m: a planet's radius, far beyond any rig.
inline constexpr float kMaxGeometryCoordinate = 1e7f;

// The first of `count` 3-float vectors (vector i at values[i * stride .. + 3), stride >= 3)
// with a component that is NaN or whose magnitude exceeds `bound`, or kAllFinite. The default
// bound finds infinities and NaNs only.
std::size_t FirstNonFiniteFloat3(std::span<const float> values, std::size_t count,
                                 std::size_t stride = 3,
                                 float bound = std::numeric_limits<float>::max());

// The first vector with a component that is NaN or whose magnitude exceeds `bound`, or
// kAllFinite.
std::size_t FirstBeyond(std::span<const Vec3> values, double bound);

}  // namespace wirerig::detail
