// Constants and helpers shared by TriangleBvh's source files (triangle_bvh.cpp: build, Raycast,
// Closest; triangle_bvh_fan.cpp: RaycastFan). Internal to the rig library.
#pragma once

#include <bit>
#include <cstdint>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace wirerig::bvh_shared {

// Deepest possible binary node: 48 SAH levels, then median splits of < 2^31 triangles.
inline constexpr int kStackSize = 48 + 40;
// order_ entries carry this bit for triangles too thin to hit.
inline constexpr std::uint32_t kDegenerateBit = 0x80000000u;
inline constexpr std::uint32_t kIndexMask = ~kDegenerateBit;
inline constexpr double kEps = std::numeric_limits<double>::epsilon();
inline constexpr double kHuge = std::numeric_limits<double>::max();
inline constexpr double kMaxT = 1e300;            // hits beyond this distance are ignored
inline constexpr double kTinyDirection = 1e-150;  // directions below this hit nothing
// Ray tree child reference: a leaf, whose index is in the lower bits.
inline constexpr std::uint32_t kLeafRef = 0x80000000u;

// 2^exponent for exponent in [-1022, 1023], exactly.
inline double PowerOfTwo(int exponent) {
  return std::bit_cast<double>(static_cast<std::uint64_t>(exponent + 1023) << 52);
}

#if defined(__SSE2__)
// A product rounded on its own: the empty asm makes it opaque, so the compiler cannot contract
// it with a following subtraction into a fused multiply-add.
inline __m128d RoundedProduct(__m128d a, __m128d b) {
  __m128d product = _mm_mul_pd(a, b);
  asm("" : "+x"(product));
  return product;
}

// Edge for two lanes at once. With both products rounded separately, p0 q1 - p1 q0 is exactly
// antisymmetric (and 0 for p == q) as it stands: it equals Edge's value in each lane.
inline __m128d EdgePair(__m128d px, __m128d py, __m128d qx, __m128d qy) {
  return _mm_sub_pd(RoundedProduct(px, qy), RoundedProduct(py, qx));
}
#endif

}  // namespace wirerig::bvh_shared
