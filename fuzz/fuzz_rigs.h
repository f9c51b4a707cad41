// A small rig for the fuzz targets that need a model (clips): a procedural cylinder 1 m tall
// along +Y, radius 0.1 m, rigged as two parts, "base" (the root, from the top down to the
// middle) and "arm" (its child, from the middle down), with deformable or rigid spines. The
// seed corpora's clips name these parts.
#pragma once

#include <cstdio>
#include <cstdlib>

#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_model_builder.h"

namespace wirerig::fuzz {

inline RigModel MakeJointedCylinderModel(SpineKind kind) {
  const Mesh mesh = MakeCylinder(0.1, 1.0, 16, 12);
  RigDescription description;
  PartDescription base;
  base.name = "base";
  base.central_curve = {Vec3(0, 1, 0), Vec3(0, 0.5, 0)};
  base.profile_count = 4;
  base.points_per_profile = 12;
  PartDescription arm = base;
  arm.name = "arm";
  arm.central_curve = {Vec3(0, 0.5, 0), Vec3(0, 0, 0)};
  arm.parent = "base";
  description.parts = {base, arm};
  Result<BuiltRig> rig = BuildRig(mesh, description, "cylinder");
  if (!rig) {
    std::fprintf(stderr, "fuzz rig: %s\n", rig.error().c_str());
    std::abort();
  }
  RigModelOptions options;
  options.spine_kind = kind;
  Result<BuiltRigModel> model = BuildRigModel(mesh, rig.value().rig, options);
  if (!model) {
    std::fprintf(stderr, "fuzz rig model: %s\n", model.error().c_str());
    std::abort();
  }
  return std::move(model).value().model;
}

}  // namespace wirerig::fuzz
