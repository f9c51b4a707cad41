// The float vertex stage with eight-float packs, for CPUs with AVX2 (chosen at run time by
// RunVertexStage). Every header is included before the AVX2 target region opens, so only the
// code defined inside it (this pack type and vertex_stage_passes.h, all with internal linkage)
// is compiled for AVX2. Each lane does the same IEEE operations as the SSE2 and scalar forms:
// the results are bit-identical to theirs.
#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "vertex_stage.h"
#include "wirerig/runtime/simd_pack.h"

namespace wirerig {

bool CpuHasAvx2() {
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return has;
}

}  // namespace wirerig

// GCC's target region; clang has no "#pragma GCC target" and takes the attribute on every
// function declared in the region instead.
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif

namespace wirerig::simd {
namespace {

struct F8 {
  __m256 v;
};
inline F8 operator+(F8 a, F8 b) { return {_mm256_add_ps(a.v, b.v)}; }
inline F8 operator-(F8 a, F8 b) { return {_mm256_sub_ps(a.v, b.v)}; }
inline F8 operator*(F8 a, F8 b) { return {_mm256_mul_ps(a.v, b.v)}; }
inline F8 operator/(F8 a, F8 b) { return {_mm256_div_ps(a.v, b.v)}; }

// simd_pack.h's pack interface, eight floats at a time.
struct Float8 {
  using Real = float;
  using Value = F8;
  using Mask = F8;  // all ones or all zeros per lane
  static constexpr int kWidth = 8;
  static F8 Load(const float* p) { return {_mm256_loadu_ps(p)}; }
  static void Store(float* p, F8 v) { _mm256_storeu_ps(p, v.v); }
  static F8 Gather(const float* base, const std::uint32_t* i) {
    return {_mm256_setr_ps(base[i[0]], base[i[1]], base[i[2]], base[i[3]], base[i[4]], base[i[5]],
                           base[i[6]], base[i[7]])};
  }
  static F8 Broadcast(float x) { return {_mm256_set1_ps(x)}; }
  static F8 Sqrt(F8 x) { return {_mm256_sqrt_ps(x.v)}; }
  static F8 Select(F8 m, F8 a, F8 b) { return {_mm256_blendv_ps(b.v, a.v, m.v)}; }
  // Ordered and signalling, as SSE2's _mm_cmpgt_ps.
  static F8 Greater(F8 a, F8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OS)}; }
  static F8 And(F8 a, F8 b) { return {_mm256_and_ps(a.v, b.v)}; }
  static int Bits(F8 m) { return _mm256_movemask_ps(m.v); }
  // Lane l's (x, y, z, 0) added into sums[4 i .. 4 i + 3] for i = i0[l], i1[l], i2[l], lanes in
  // order (the same additions in the same order as OneLane's).
  static void ScatterAdd4(float* sums, F8 x, F8 y, F8 z, const std::uint32_t* i0,
                          const std::uint32_t* i1, const std::uint32_t* i2) {
    for (int half = 0; half < 2; ++half) {
      __m128 lane[4] = {half ? _mm256_extractf128_ps(x.v, 1) : _mm256_castps256_ps128(x.v),
                        half ? _mm256_extractf128_ps(y.v, 1) : _mm256_castps256_ps128(y.v),
                        half ? _mm256_extractf128_ps(z.v, 1) : _mm256_castps256_ps128(z.v),
                        _mm_setzero_ps()};
      _MM_TRANSPOSE4_PS(lane[0], lane[1], lane[2], lane[3]);
      for (int l = 0; l < 4; ++l) {
        const int at = 4 * half + l;
        for (const std::uint32_t i : {i0[at], i1[at], i2[at]}) {
          float* sum = sums + 4 * std::size_t(i);
          _mm_storeu_ps(sum, _mm_add_ps(_mm_loadu_ps(sum), lane[l]));
        }
      }
    }
  }
  // Lanes x, y, z of the eight (x, y, z, w) quadruples from `sums`.
  static void Load4(const float* sums, F8* x, F8* y, F8* z) {
    __m128 half[2][3];
    for (int h = 0; h < 2; ++h) {
      const float* q = sums + 16 * h;
      __m128 a = _mm_loadu_ps(q), b = _mm_loadu_ps(q + 4), c = _mm_loadu_ps(q + 8),
             d = _mm_loadu_ps(q + 12);
      _MM_TRANSPOSE4_PS(a, b, c, d);
      half[h][0] = a, half[h][1] = b, half[h][2] = c;
    }
    x->v = _mm256_set_m128(half[1][0], half[0][0]);
    y->v = _mm256_set_m128(half[1][1], half[0][1]);
    z->v = _mm256_set_m128(half[1][2], half[0][2]);
  }
};

}  // namespace
}  // namespace wirerig::simd

#include "vertex_stage_passes.h"

namespace wirerig {

void RunVertexStageAvx2(const RigModel& model, RigWorkspace& w, VertexStage<float>& stage,
                        const StageOutput<float>& output, const ParallelFor* parallel) {
  RunStage<float, simd::Float8>(model, w, stage, output, parallel);
}

}  // namespace wirerig

#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
