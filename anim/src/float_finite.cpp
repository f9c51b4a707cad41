#include "float_finite.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace wirerig::detail {
namespace {

// A float's magnitude as bits: ordered like the magnitudes, with infinity above every finite
// value and NaN above infinity, so one unsigned comparison finds both.
std::uint32_t MagnitudeBits(const float* v) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, v, sizeof bits);
  return bits & 0x7FFFFFFFu;
}

bool Beyond(const float* v, std::uint32_t bound) {
  std::uint32_t bad = 0;
  for (int c = 0; c < 3; ++c) bad |= static_cast<std::uint32_t>(MagnitudeBits(v + c) > bound);
  return bad != 0;
}

}  // namespace

std::size_t FirstNonFiniteFloat3(std::span<const float> values, std::size_t count,
                                 std::size_t stride, float bound) {
  const std::uint32_t limit = MagnitudeBits(&bound);
  if (stride != 3) {
    for (std::size_t i = 0; i < count; ++i)
      if (Beyond(values.data() + i * stride, limit)) return i;
    return kAllFinite;
  }
  // Contiguous (#K x #V bakes, ~10^7 values): magnitudes scanned in blocks so that the loop
  // vectorizes; the vector is then located in its block.
  constexpr std::size_t kBlock = 3 * 1024;
  const std::size_t floats = 3 * count;
  for (std::size_t first = 0; first < floats; first += kBlock) {
    const std::size_t last = std::min(floats, first + kBlock);
    std::uint32_t bad = 0;
    for (std::size_t i = first; i < last; ++i)
      bad |= static_cast<std::uint32_t>(MagnitudeBits(values.data() + i) > limit);
    if (bad != 0) {
      for (std::size_t i = first / 3; i < last / 3; ++i)
        if (Beyond(values.data() + 3 * i, limit)) return i;
    }
  }
  return kAllFinite;
}

std::size_t FirstBeyond(std::span<const Vec3> values, double bound) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double x = values[i][c];
      if (!std::isfinite(x) || std::abs(x) > bound) return i;  // isfinite first: no FE_INVALID
    }
  }
  return kAllFinite;
}

}  // namespace wirerig::detail
