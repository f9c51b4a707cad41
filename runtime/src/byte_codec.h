// Little-endian byte writing and bounds-checked reading for the runtime's binary assets.
#pragma once

#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "wirerig/runtime/conventions.h"

namespace wirerig::bytes {

class Writer {
 public:
  void U8(std::uint8_t v) { out_.push_back(v); }
  void U32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out_.push_back(std::uint8_t(v >> (8 * i)));
  }
  void U64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) out_.push_back(std::uint8_t(v >> (8 * i)));
  }
  void I32(std::int32_t v) { U32(std::bit_cast<std::uint32_t>(v)); }
  void F64(double v) { U64(std::bit_cast<std::uint64_t>(v)); }
  void V3(const Vec3& v) { F64(v.x()), F64(v.y()), F64(v.z()); }
  void M3(const Mat3& m) {
    for (int c = 0; c < 3; ++c) V3(m.col(c));
  }
  void Count(std::size_t n) { U32(std::uint32_t(n)); }
  void String(const std::string& s) {
    Count(s.size());
    for (char c : s)
      U8(static_cast<std::uint8_t>(c));  // (insert trips GCC 12's -Wstringop-overflow)
  }
  std::vector<std::uint8_t>& bytes() { return out_; }

 private:
  std::vector<std::uint8_t> out_;
};

// Reads stop at the first overrun: every later read yields zero and ok() stays false.
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> in) : in_(in) {}
  bool ok() const { return ok_; }
  std::size_t left() const { return in_.size() - at_; }

  std::uint8_t U8() { return std::uint8_t(Take(1)); }
  std::uint32_t U32() { return std::uint32_t(Take(4)); }
  std::uint64_t U64() { return Take(8); }
  std::int32_t I32() { return std::bit_cast<std::int32_t>(U32()); }
  double F64() { return std::bit_cast<double>(U64()); }
  Vec3 V3() {
    const double x = F64(), y = F64(), z = F64();
    return {x, y, z};
  }
  Mat3 M3() {
    Mat3 m;
    for (int c = 0; c < 3; ++c) m.col(c) = V3();
    return m;
  }
  // An element count, refused (0 and not ok) when the elements, at least `min_bytes` each,
  // cannot fit in what is left: a corrupt count never drives a large allocation.
  std::size_t Count(std::size_t min_bytes) {
    const std::size_t n = U32();
    if (ok_ && n > left() / std::max<std::size_t>(min_bytes, 1)) ok_ = false;
    return ok_ ? n : 0;
  }
  std::string String() {
    const std::size_t n = Count(1);
    std::string s(reinterpret_cast<const char*>(in_.data() + at_), n);
    at_ += n;
    return s;
  }

 private:
  std::uint64_t Take(std::size_t n) {
    if (!ok_ || left() < n) {
      ok_ = false;
      return 0;
    }
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i) v |= std::uint64_t(in_[at_ + i]) << (8 * i);
    at_ += n;
    return v;
  }
  std::span<const std::uint8_t> in_;
  std::size_t at_ = 0;
  bool ok_ = true;
};

}  // namespace wirerig::bytes
