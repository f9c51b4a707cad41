// The per-vertex stage of EvaluateRigJob (rig_evaluation.h, steps 6-8): vertices from the
// profile wires, then the skin bridges at joints, then normals, over flat arrays with one array
// per coordinate, in Real: double where a tool needs it, float for engine buffers (four
// vertices at a time with SSE2). Its plan (VertexStagePlan) is made once per model and shared by
// every workspace of that model (RigEvaluationPlan); each workspace holds its own per-frame
// buffers (VertexStage). Internal to the evaluation (its fields may change).
//
// Vertices are held in "slots": the pair-bound vertices first, in vertex order, then the
// capped ones; slot_of_vertex maps a vertex to its slot.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "wirerig/runtime/joint_bridge.h"

namespace wirerig {

template <class Real>
struct StageCoordinates {  // one array per coordinate
  std::vector<Real> x, y, z;
  void resize(std::size_t n) { x.resize(n), y.resize(n), z.resize(n); }
};

// The stage's layout, constant per model.
template <class Real>
struct VertexStagePlan {
  using Coordinates = StageCoordinates<Real>;
  std::vector<std::uint32_t> slot_of_vertex;  // #W
  std::vector<std::uint32_t> vertex_of_slot;  // #W
  std::size_t pair_count = 0;
  // Pair slots [0, pair_count): PHYSICS.md section 6 with the wire points resolved to indices
  // into `wire`: p1 = (1 - lambda1) wire[a0] + lambda1 wire[a1], p2 likewise on (b0, b1),
  // centre pair_centre[profile] (global profile).
  std::vector<std::uint32_t> a0, a1, b0, b1, profile;
  std::vector<Real> lambda1, lambda2, alpha, beta, gamma;
  // Cap slots [pair_count, #W): origin + axes * local of their global profile's cap frame.
  std::vector<std::uint32_t> cap_profile;
  Coordinates cap_local;
  // Bridged vertices (on at least one skin bridge), in vertex order: their slot, the undo
  // sample (RigEvaluationLayout::undo_samples) that takes their own part's motion back to rest,
  // and their entries' corrections [entry_offsets[b], entry_offsets[b + 1]) of `entry_of`.
  std::vector<std::uint32_t> bridged_slot, bridged_undo, entry_offsets, entry_of;
  // Bridge entries sorted into buckets of one joint's segment each, every bucket padded to a
  // multiple of four entries (padding: weight 0, never summed).
  struct Bucket {
    std::uint32_t joint = 0;  // the joint's child part
    std::int32_t segment = 0;
    std::uint32_t begin = 0, end = 0;
  };
  std::vector<Bucket> buckets;
  std::vector<std::uint32_t> bucket_task_starts;  // tasks of whole buckets
  std::vector<std::uint32_t> entry_bridged;       // the entry's bridged vertex
  std::vector<std::uint32_t> entry_slot;          // its slot
  // entry_base: RigEvaluationLayout::JointBase as a number (0 parent, 1 own, 2 child).
  std::vector<Real> entry_f, entry_u, entry_fraction, entry_section, entry_weight, entry_base;
  // Normals: triangles by slot, and each slot's triangles in increasing order,
  // slot_triangles[slot_triangle_offsets[i] .. slot_triangle_offsets[i + 1]).
  std::vector<std::uint32_t> t0, t1, t2;
  std::vector<std::uint32_t> slot_triangle_offsets, slot_triangles;
  // Rotated normals (NormalMode::kRotated): by slot, the rest normal in the slot's rest frame
  // (RestNormalsInSlotFrames: pair slots along e_hat, m_hat, n_hat; caps in their cap axes).
  // Bridged slots take theirs from their triangles instead: the triangles with a bridged
  // vertex in increasing order, as their corners' slots (bt0, bt1, bt2; "bridged triangle" j),
  // and each bridged vertex's triangles as increasing j, bridged_triangles[
  // bridged_triangle_offsets[b] .. bridged_triangle_offsets[b + 1]).
  Coordinates rest_normal_local;
  std::vector<std::uint32_t> bt0, bt1, bt2;
  std::vector<std::uint32_t> bridged_triangle_offsets, bridged_triangles;
  std::vector<std::uint32_t> bridged_corners;  // every corner of those, once, increasing
};

// The stage's per-frame buffers, one set per workspace.
template <class Real>
struct VertexStage {
  using V = Eigen::Matrix<Real, 3, 1>;
  using M = Eigen::Matrix<Real, 3, 3>;
  using Coordinates = StageCoordinates<Real>;
  using Bucket = typename VertexStagePlan<Real>::Bucket;
  const VertexStagePlan<Real>* plan = nullptr;  // owned by the workspace's RigEvaluationPlan

  Coordinates position;     // by slot
  Coordinates wire;         // every profile's world points, by RigEvaluationLayout::point_base
  Coordinates pair_centre;  // (c_g + c_g+1) / 2 by global profile
  Coordinates cap_origin;   // by global profile
  std::vector<M> cap_axes;  // by global profile
  Coordinates rest;         // by bridged vertex: its point undone into rest space
  Coordinates correction;   // by entry: weight * (bridge image - own side's motion)
  Coordinates face_normal;  // by triangle: (p1 - p0) x (p2 - p0)
  // By slot (padded to whole packs): (x, y, z, 0), the sum of its triangles' normals.
  std::vector<Real> normal_sum;
  Coordinates unit_normal;  // by slot (padded): unit normals, for an output order
  // Rotated normals: by slot (padded; padding stays zero), each slot's normal before
  // normalisation, and by global profile the cofactors of cap_axes (det(A) A^-T: what turns a
  // cap's normals).
  Coordinates rotated_normal;
  std::vector<M> cap_normal_axes;
  std::vector<M> undo;  // by undo sample: rest axes times transposed deformed axes
  std::vector<V> undo_rest_point, undo_point;
  std::vector<BasicBridgeSamples<Real>> bridges;  // by part (float stage only)
};

}  // namespace wirerig
