// Internal to the runtime: the normalised bending problem shared by the exact and series
// evaluators. In normalised form v in [0,1] and EI_n = EI / L^3 (PHYSICS.md section 0):
// point forces keep their value in N, a line load q (N/m) becomes q L per unit v, and the
// tip shear is Q = -F_tip / EI_n.
#pragma once

#include "wirerig/runtime/bending_job.h"

namespace wirerig::detail {

// 1 / EI_n = L^3 / EI, in m/N.
inline double NormalizedCompliance(const BendingJob& job) {
  return job.length * job.length * job.length / job.bending_stiffness;
}

// Fills the outputs of a validated job.
void RunExactBending(const BendingJob& job);
void RunSeriesBending(const BendingJob& job);

}  // namespace wirerig::detail
