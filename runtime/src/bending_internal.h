// Internal to the runtime: the normalised bending problem shared by the exact and series
// evaluators. In normalised form v in [0,1] and EI_n = EI / L^3 (PHYSICS.md section 0):
// point forces keep their value in N, a line load q (N/m) becomes q L per unit v, and the
// tip shear is Q = -F_tip / EI_n.
#pragma once

#include <cstddef>

#include "wirerig/runtime/bending_job.h"

namespace wirerig::detail {

// 1 / EI_n = L^3 / EI, in m/N.
inline double NormalizedCompliance(const BendingJob& job) {
  return job.length * job.length * job.length / job.bending_stiffness;
}

// The cubic of an exact-mode solution X(v) = X0 + c1 v + c2 v^2 + c3 v^3 + compliance * M(v),
// M the loads' Macaulay particular solution (PHYSICS.md section 2): it meets the end conditions.
struct ExactPolynomial {
  Vec3 c1, c2, c3;  // m (normalised v)
};
// c1, c2, c3 of a validated job; compliance = NormalizedCompliance(job).
ExactPolynomial SolveExactPolynomial(const BendingJob& job, double compliance);

// Fills the outputs of a validated job.
void RunExactBending(const BendingJob& job);
void RunSeriesBending(const BendingJob& job);

// The point-load fast path of kExact (bending_segments.cpp): a job with point loads only (any
// boundary family, tip force and couple included) and at most kMaxSegmentLoads of them is a
// cubic on each interval between sorted load positions, evaluated by Horner's rule.
inline constexpr std::size_t kMaxSegmentLoads = 16;
inline bool FitsSegmentedBending(const BendingJob& job) {
  return job.line_loads.empty() && job.linear_line_loads.empty() &&
         job.point_loads.size() <= kMaxSegmentLoads;
}
// Fills the outputs of a validated job that FitsSegmentedBending; poly from SolveExactPolynomial.
void RunSegmentedBending(const BendingJob& job, const ExactPolynomial& poly, double compliance);

}  // namespace wirerig::detail
