// Making and running the per-vertex stage (wirerig/runtime/vertex_stage.h) of EvaluateRigJob.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "wirerig/runtime/cofactors.h"
#include "wirerig/runtime/rig_evaluation.h"
#include "wirerig/runtime/vertex_stage.h"

namespace wirerig {

// Where the stage writes: output vertex i's position at positions[i * position_stride .. + 3)
// and, when normals is not null, its unit normal likewise (elements of Real). Output vertex i
// is welded vertex order[i], or welded vertex i when order is null.
template <class Real>
struct StageOutput {
  Real* positions = nullptr;
  std::size_t position_stride = 3;
  Real* normals = nullptr;
  std::size_t normal_stride = 3;
  const std::uint32_t* order = nullptr;
  std::size_t order_size = 0;
  bool allow_avx2 = true;  // float: eight lanes where the CPU has AVX2 (identical results)
  NormalMode normal_mode = NormalMode::kFromTriangles;
};

// Each slot's rest normal (area-weighted over the rest mesh's triangles, unit; zero where the
// sum vanishes) in the slot's rest frame: a pair slot's along its pair frame's axes
// (ApplyPairFrame: e_hat, m_hat, n_hat), a cap slot's along its cap frame's axes. By slot.
std::vector<Vec3> RestNormalsInSlotFrames(const RigModel& model, const RigEvaluationLayout& layout,
                                          std::span<const std::uint32_t> vertex_of_slot);

// The stage's plan for `model`; `layout` holds the joint entries and undo samples.
template <class Real>
void MakeVertexStagePlan(const RigModel& model, const RigEvaluationLayout& layout,
                         VertexStagePlan<Real>* plan);
// Per-frame buffers sized for `plan` (which must outlive the stage).
template <class Real>
void MakeVertexStage(const RigModel& model, const RigEvaluationLayout& layout,
                     const VertexStagePlan<Real>& plan, VertexStage<Real>* stage);

// Steps 6-8 of EvaluateRigJob::Run, after the spines and profiles of `w` are evaluated (and
// w.bridges and w.spine_undo made for this frame).
template <class Real>
void RunVertexStage(const RigModel& model, RigWorkspace& w, VertexStage<Real>& stage,
                    const StageOutput<Real>& output, const ParallelFor* parallel);

#if WIRERIG_HAVE_AVX2_STAGE
// Whether this CPU (and OS) runs AVX2, asked once.
bool CpuHasAvx2();
// RunVertexStage<float> with eight-float packs (vertex_stage_avx2.cpp); call only when
// CpuHasAvx2().
void RunVertexStageAvx2(const RigModel& model, RigWorkspace& w, VertexStage<float>& stage,
                        const StageOutput<float>& output, const ParallelFor* parallel);
#endif

}  // namespace wirerig
