// BuildRigModel: turns a rig file's rig and its mesh into the runtime's RigModel (computed
// once): spines sampled at equal arc length with rotation-minimizing frames, profiles in their
// spine frames, mass properties from the closed surface the profiles span, and a binding for
// every welded vertex (between the two profiles around its projection on the spine, or
// rigidly to the end profile for the end caps).
#pragma once

#include "wirerig/rig/mesh.h"
#include "wirerig/rig/result.h"
#include "wirerig/rig/rig.h"
#include "wirerig/runtime/rig_model.h"

namespace wirerig {

struct RigModelOptions {
  int min_spine_samples = 16;  // samples per spine: max(this, 4 x profiles)
  SpineKind spine_kind = SpineKind::kDeformable;
};

struct RigModelReport {
  std::size_t cap_vertices = 0;       // beyond the first or last profile
  std::size_t fallback_vertices = 0;  // the pair binding refused: bound rigidly instead
  std::size_t flagged_vertices = 0;   // the pair binding used a documented fallback
};

struct BuiltRigModel {
  RigModel model;
  RigModelReport report;
};

// The mesh must be the one the rig was built on (same welded counts).
Result<BuiltRigModel> BuildRigModel(const Mesh& mesh, const Rig& rig,
                                    const RigModelOptions& options = {});

}  // namespace wirerig
