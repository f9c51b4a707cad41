// Packs of lanes for the per-vertex passes: one kernel, written once against a pack type P,
// runs as plain double or float (one lane) or as four floats at once (SSE2, x86-64's baseline).
// Every operation is IEEE-exact per lane (+, -, *, /, sqrt are correctly rounded in both the
// scalar and the SSE2 forms), so a lane's result does not depend on its pack's width.
//
// A pack type P provides: Real (the lane type), Value (the pack), Mask, kWidth, and static
// Load/Store (contiguous lanes), Gather (lanes from base[index[l]]), Broadcast, Sqrt, Select
// (mask ? a : b), Greater, And, Bits (one bit per lane of a mask), and ScatterAdd4/Load4 on
// (x, y, z, w) quadruples. Value supports
// +, -, * and / with other Values.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#define WIRERIG_HAVE_SSE2 1
#endif

namespace wirerig::simd {

template <class T>
struct OneLane {
  using Real = T;
  using Value = T;
  using Mask = bool;
  static constexpr int kWidth = 1;
  static T Load(const T* p) { return *p; }
  static void Store(T* p, T v) { *p = v; }
  static T Gather(const T* base, const std::uint32_t* index) { return base[index[0]]; }
  static T Broadcast(T x) { return x; }
  static T Sqrt(T x) { return std::sqrt(x); }
  static T Select(bool m, T a, T b) { return m ? a : b; }
  static bool Greater(T a, T b) { return a > b; }
  static bool And(bool a, bool b) { return a && b; }
  static int Bits(bool m) { return m ? 1 : 0; }
  // (x, y, z, 0) added into sums[4 i .. 4 i + 3] for i = i0[0], i1[0], i2[0] in that order.
  static void ScatterAdd4(T* sums, T x, T y, T z, const std::uint32_t* i0, const std::uint32_t* i1,
                          const std::uint32_t* i2) {
    for (const std::uint32_t i : {i0[0], i1[0], i2[0]})
      sums[4 * i] += x, sums[4 * i + 1] += y, sums[4 * i + 2] += z;
  }
  // x, y, z of the (x, y, z, w) quadruple at `sums`.
  static void Load4(const T* sums, T* x, T* y, T* z) { *x = sums[0], *y = sums[1], *z = sums[2]; }
};

#if WIRERIG_HAVE_SSE2
struct F4 {
  __m128 v;
};
inline F4 operator+(F4 a, F4 b) { return {_mm_add_ps(a.v, b.v)}; }
inline F4 operator-(F4 a, F4 b) { return {_mm_sub_ps(a.v, b.v)}; }
inline F4 operator*(F4 a, F4 b) { return {_mm_mul_ps(a.v, b.v)}; }
inline F4 operator/(F4 a, F4 b) { return {_mm_div_ps(a.v, b.v)}; }
inline F4& operator+=(F4& a, F4 b) { return a = a + b; }

struct Float4 {
  using Real = float;
  using Value = F4;
  using Mask = F4;  // all ones or all zeros per lane
  static constexpr int kWidth = 4;
  static F4 Load(const float* p) { return {_mm_loadu_ps(p)}; }
  static void Store(float* p, F4 v) { _mm_storeu_ps(p, v.v); }
  static F4 Gather(const float* base, const std::uint32_t* index) {
    return {_mm_setr_ps(base[index[0]], base[index[1]], base[index[2]], base[index[3]])};
  }
  static F4 Broadcast(float x) { return {_mm_set1_ps(x)}; }
  static F4 Sqrt(F4 x) { return {_mm_sqrt_ps(x.v)}; }
  static F4 Select(F4 m, F4 a, F4 b) {
    return {_mm_or_ps(_mm_and_ps(m.v, a.v), _mm_andnot_ps(m.v, b.v))};
  }
  static F4 Greater(F4 a, F4 b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
  static F4 And(F4 a, F4 b) { return {_mm_and_ps(a.v, b.v)}; }
  static int Bits(F4 m) { return _mm_movemask_ps(m.v); }
  // Lane l's (x, y, z, 0) added into sums[4 i .. 4 i + 3] for i = i0[l], i1[l], i2[l], lanes in
  // order: per element the same additions, in the same order, as OneLane's.
  static void ScatterAdd4(float* sums, F4 x, F4 y, F4 z, const std::uint32_t* i0,
                          const std::uint32_t* i1, const std::uint32_t* i2) {
    __m128 lane[4] = {x.v, y.v, z.v, _mm_setzero_ps()};
    _MM_TRANSPOSE4_PS(lane[0], lane[1], lane[2], lane[3]);
    for (int l = 0; l < 4; ++l)
      for (const std::uint32_t i : {i0[l], i1[l], i2[l]}) {
        float* sum = sums + 4 * std::size_t(i);
        _mm_storeu_ps(sum, _mm_add_ps(_mm_loadu_ps(sum), lane[l]));
      }
  }
  // Lanes x, y, z of the four (x, y, z, w) quadruples from `sums`.
  static void Load4(const float* sums, F4* x, F4* y, F4* z) {
    __m128 a = _mm_loadu_ps(sums), b = _mm_loadu_ps(sums + 4), c = _mm_loadu_ps(sums + 8),
           d = _mm_loadu_ps(sums + 12);
    _MM_TRANSPOSE4_PS(a, b, c, d);
    x->v = a, y->v = b, z->v = c;
  }
};
#endif

// The helpers below are always inlined into the pass that uses them, so a pass compiled for a
// wider instruction set (vertex_stage_avx2.cpp) never calls an out-of-line copy compiled
// without it.
#define WIRERIG_SIMD_INLINE [[gnu::always_inline]] inline

// A 3-vector of lanes (x, y, z each a pack or a scalar).
template <class T>
struct V3 {
  T x, y, z;
};
template <class T>
WIRERIG_SIMD_INLINE V3<T> operator+(const V3<T>& a, const V3<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
WIRERIG_SIMD_INLINE V3<T> operator-(const V3<T>& a, const V3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
WIRERIG_SIMD_INLINE V3<T> operator*(const T& s, const V3<T>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class T>
WIRERIG_SIMD_INLINE T Dot(const V3<T>& a, const V3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
WIRERIG_SIMD_INLINE V3<T> Cross(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Broadcasts of a scalar vector and matrix (Eigen, column-major) into packs.
template <class P, class Vector>
WIRERIG_SIMD_INLINE V3<typename P::Value> Splat(const Vector& v) {
  return {P::Broadcast(v.x()), P::Broadcast(v.y()), P::Broadcast(v.z())};
}
template <class P>
struct M3 {
  typename P::Value m[3][3];  // m[row][column]
  template <class Matrix>
  [[gnu::always_inline]] static M3 Splat(const Matrix& a) {
    M3 out;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out.m[r][c] = P::Broadcast(a(r, c));
    return out;
  }
  [[gnu::always_inline]] V3<typename P::Value> operator*(const V3<typename P::Value>& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
};

}  // namespace wirerig::simd
