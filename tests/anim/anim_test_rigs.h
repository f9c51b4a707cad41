// Small rigs for the anim tests: a procedural cylinder standing on +Y rigged as one part.
#pragma once

#include <gtest/gtest.h>

#include "wirerig/rig/procedural_mesh.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_model_builder.h"

namespace wirerig::testing {

struct TestRig {
  Mesh mesh;
  Rig rig;
  RigModel model;
};

// A cylinder of radius 0.1 m and height 1 m along +Y, one part "beam" from its base up.
inline TestRig MakeCylinderRig(SpineKind kind) {
  TestRig out;
  out.mesh = MakeCylinder(0.1, 1.0, 32, 24);
  RigDescription description;
  PartDescription part;
  part.name = "beam";
  part.central_curve = {Vec3(0, 0, 0), Vec3(0, 1, 0)};
  part.profile_count = 10;
  part.points_per_profile = 32;
  description.parts.push_back(part);
  Result<BuiltRig> built = BuildRig(out.mesh, description, "cylinder");
  EXPECT_TRUE(built.ok()) << built.error();
  out.rig = built.value().rig;
  RigModelOptions options;
  options.spine_kind = kind;
  Result<BuiltRigModel> model = BuildRigModel(out.mesh, out.rig, options);
  EXPECT_TRUE(model.ok()) << model.error();
  out.model = std::move(model).value().model;
  return out;
}

}  // namespace wirerig::testing

namespace wirerig::testing {

// The same cylinder as two parts: "base", the root, from the top (y = 1) down to the middle,
// and "arm", its child, from the middle down to the bottom.
inline TestRig MakeJointedCylinderRig(SpineKind kind) {
  TestRig out;
  out.mesh = MakeCylinder(0.1, 1.0, 32, 24);
  RigDescription description;
  PartDescription base;
  base.name = "base";
  base.central_curve = {Vec3(0, 1, 0), Vec3(0, 0.5, 0)};
  base.profile_count = 6;
  base.points_per_profile = 32;
  PartDescription arm = base;
  arm.name = "arm";
  arm.parent = "base";
  arm.central_curve = {Vec3(0, 0.5, 0), Vec3(0, 0, 0)};
  description.parts = {base, arm};
  Result<BuiltRig> built = BuildRig(out.mesh, description, "cylinder");
  EXPECT_TRUE(built.ok()) << built.error();
  out.rig = built.value().rig;
  RigModelOptions options;
  options.spine_kind = kind;
  Result<BuiltRigModel> model = BuildRigModel(out.mesh, out.rig, options);
  EXPECT_TRUE(model.ok()) << model.error();
  out.model = std::move(model).value().model;
  return out;
}

}  // namespace wirerig::testing
