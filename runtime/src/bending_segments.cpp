// The point-load fast path of kExact mode (bending_internal.h). With point loads only, X is a
// cubic between consecutive load positions: on the segment that starts at s (0, or a load
// position), X(s + t) = a + t (b + t (c + t d)) with the Taylor coefficients at s
//   a = X(s), b = X'(s), c = X''(s)/2, d = X'''(s+)/6,
// each the cubic X0 + c1 v + c2 v^2 + c3 v^3 (or its derivative) at s plus, for every load
// P_j at v_j <= s (w = s - v_j >= 0), compliance P_j (w^3/6, w^2/2, w/2, 1/6): the expansion
// of P_j (w + t)^3 / 6 in t, whose terms share one sign (no cancellation). Each segment is built
// from the loads directly (O(J^2) once per Run), not shifted from its neighbour, so rounding
// does not accumulate along the wire. A sample then costs one Horner evaluation; the segment
// index follows the samples, so sorted samples advance it at most once per load.
#include <array>

#include "bending_internal.h"

namespace wirerig::detail {
namespace {

// X on one segment in normalised v: Taylor coefficients at start (see above).
struct Segment {
  double start;  // s: 0 or a load position
  Vec3 a, b, c, d;
};

// The segments of a job, in order along the wire, with bounds for the segment search:
// segment k holds the samples lower[k] < v <= upper[k].
struct Segments {
  std::array<Segment, kMaxSegmentLoads + 1> segment;
  std::array<double, kMaxSegmentLoads + 1> lower;  // lower[0] = -1: below every sample
  std::array<double, kMaxSegmentLoads + 1> upper;  // upper[last] = 2: above every sample
};

void BuildSegments(const BendingJob& job, const ExactPolynomial& poly, double compliance,
                   Segments* out) {
  // Load indices sorted by position (insertion sort: at most kMaxSegmentLoads).
  const int loads = static_cast<int>(job.point_loads.size());
  std::array<int, kMaxSegmentLoads> order;
  for (int i = 0; i < loads; ++i) {
    int j = i;
    while (j > 0 && job.point_loads[order[j - 1]].at > job.point_loads[i].at) {
      order[j] = order[j - 1];
      --j;
    }
    order[j] = i;
  }
  // P/6 of each load, once.
  std::array<Vec3, kMaxSegmentLoads> sixth;
  for (int i = 0; i < loads; ++i) sixth[i] = job.point_loads[i].force / 6.0;
  const Vec3 x0 = job.start_displacement;
  for (int k = 0; k <= loads; ++k) {
    const double s = k == 0 ? 0.0 : job.point_loads[order[k - 1]].at;
    Vec3 ma = Vec3::Zero(), mb = Vec3::Zero(), mc = Vec3::Zero(), md = Vec3::Zero();
    for (int j = 0; j < k; ++j) {
      const PointLoad& load = job.point_loads[order[j]];
      const double w = s - load.at;  // >= 0
      ma += sixth[order[j]] * (w * w * w);
      mb += load.force * (w * w / 2.0);
      mc += load.force * (w / 2.0);
      md += sixth[order[j]];
    }
    Segment& seg = out->segment[k];
    seg.start = s;
    seg.a = x0 + s * (poly.c1 + s * (poly.c2 + s * poly.c3)) + compliance * ma;
    seg.b = poly.c1 + s * (2.0 * poly.c2 + 3.0 * s * poly.c3) + compliance * mb;
    seg.c = poly.c2 + 3.0 * s * poly.c3 + compliance * mc;
    seg.d = poly.c3 + compliance * md;
    out->lower[k] = k == 0 ? -1.0 : s;
    out->upper[k] = k == loads ? 2.0 : job.point_loads[order[k]].at;
  }
}

// Derivatives are converted to arc length on output. The samples are taken in runs that lie
// in one segment, whose coefficients stay in registers; templated so the displacement-only
// loop carries no branches but the run's bounds.
template <bool kSlope, bool kCurvature>
void EvaluateSegments(const BendingJob& job, const Segments& segments) {
  const double inv_length = 1.0 / job.length;
  const double inv_length2 = inv_length * inv_length;
  const double* v = job.samples.data();
  const std::size_t count = job.samples.size();
  Vec3* x = job.displacement.data();
  Vec3* dx = job.slope.data();
  Vec3* ddx = job.curvature.data();
  int k = 0;
  std::size_t i = 0;
  while (i < count) {
    // Samples lie in [0, 1] (validated), so the sentinels end both searches.
    while (v[i] > segments.upper[k]) ++k;
    while (v[i] <= segments.lower[k]) --k;
    const Segment seg = segments.segment[k];
    const double lower = segments.lower[k], upper = segments.upper[k];
    do {
      const double t = v[i] - seg.start;
      x[i] = seg.a + t * (seg.b + t * (seg.c + t * seg.d));
      if constexpr (kSlope) dx[i] = (seg.b + t * (2.0 * seg.c + 3.0 * t * seg.d)) * inv_length;
      if constexpr (kCurvature) ddx[i] = (2.0 * seg.c + 6.0 * t * seg.d) * inv_length2;
      ++i;
    } while (i < count && v[i] > lower && v[i] <= upper);
  }
}

}  // namespace

void RunSegmentedBending(const BendingJob& job, const ExactPolynomial& poly, double compliance) {
  Segments segments;
  BuildSegments(job, poly, compliance, &segments);
  const bool slope = !job.slope.empty(), curvature = !job.curvature.empty();
  if (slope && curvature)
    EvaluateSegments<true, true>(job, segments);
  else if (slope)
    EvaluateSegments<true, false>(job, segments);
  else if (curvature)
    EvaluateSegments<false, true>(job, segments);
  else
    EvaluateSegments<false, false>(job, segments);
}

}  // namespace wirerig::detail
