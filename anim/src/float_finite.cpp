#include "float_finite.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace wirerig::detail {
namespace {

constexpr std::uint32_t kExponent = 0x7F800000u;

bool NonFinite(const float* v) {
  std::uint32_t bad = 0;
  for (int c = 0; c < 3; ++c) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, v + c, sizeof bits);
    bad |= static_cast<std::uint32_t>((bits & kExponent) == kExponent);
  }
  return bad != 0;
}

}  // namespace

std::size_t FirstNonFiniteFloat3(std::span<const float> values, std::size_t count,
                                 std::size_t stride) {
  if (stride != 3) {
    for (std::size_t i = 0; i < count; ++i)
      if (NonFinite(values.data() + i * stride)) return i;
    return kAllFinite;
  }
  // Contiguous (#K x #V bakes, ~10^7 values): bits scanned in blocks for an all-ones exponent
  // (infinity or NaN) so that the loop vectorizes; the vector is then located in its block.
  constexpr std::size_t kBlock = 3 * 1024;
  const std::size_t floats = 3 * count;
  for (std::size_t first = 0; first < floats; first += kBlock) {
    const std::size_t last = std::min(floats, first + kBlock);
    std::uint32_t bad = 0;
    for (std::size_t i = first; i < last; ++i) {
      std::uint32_t bits = 0;
      std::memcpy(&bits, values.data() + i, sizeof bits);
      bad |= static_cast<std::uint32_t>((bits & kExponent) == kExponent);
    }
    if (bad != 0) {
      for (std::size_t i = first / 3; i < last / 3; ++i)
        if (NonFinite(values.data() + 3 * i)) return i;
    }
  }
  return kAllFinite;
}

std::size_t FirstNotFloatFinite(std::span<const Vec3> values) {
  constexpr double kMax = std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double x = values[i][c];
      if (!std::isfinite(x) || std::abs(x) > kMax) return i;
    }
  }
  return kAllFinite;
}

}  // namespace wirerig::detail
