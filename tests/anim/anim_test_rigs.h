// Small rigs and raw tracks for the anim tests: a procedural cylinder standing on +Y rigged as
// one part or as two, and helpers that write keyed tracks briefly.
#pragma once

#include <gtest/gtest.h>

#include "wirerig/anim/track.h"
#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_model_builder.h"

namespace wirerig::testing {

struct TestRig {
  Mesh mesh;
  Rig rig;
  RigModel model;
};

// Rigs `mesh` by `description` and builds its runtime model with spines of `kind`.
inline TestRig RigMesh(Mesh mesh, const RigDescription& description, SpineKind kind) {
  TestRig out;
  out.mesh = std::move(mesh);
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

inline PartDescription AxisPart(const char* name, const Vec3& from, const Vec3& to, int profiles) {
  PartDescription part;
  part.name = name;
  part.central_curve = {from, to};
  part.profile_count = profiles;
  part.points_per_profile = 32;
  return part;
}

// A cylinder of radius 0.1 m and height 1 m along +Y, one part "beam" from its base up.
inline TestRig MakeCylinderRig(SpineKind kind) {
  RigDescription description;
  description.parts = {AxisPart("beam", Vec3(0, 0, 0), Vec3(0, 1, 0), 10)};
  return RigMesh(MakeCylinder(0.1, 1.0, 32, 24), description, kind);
}

// MakeCylinderRig(kDeformable), built once per test program.
inline const TestRig& Beam() {
  static const TestRig rig = MakeCylinderRig(SpineKind::kDeformable);
  return rig;
}

// The same cylinder as two parts: "base", the root, from the top (y = 1) down to the middle,
// and "arm", its child, from the middle down to the bottom.
inline TestRig MakeJointedCylinderRig(SpineKind kind) {
  RigDescription description;
  PartDescription arm = AxisPart("arm", Vec3(0, 0.5, 0), Vec3(0, 0, 0), 6);
  arm.parent = "base";
  description.parts = {AxisPart("base", Vec3(0, 1, 0), Vec3(0, 0.5, 0), 6), arm};
  return RigMesh(MakeCylinder(0.1, 1.0, 32, 24), description, kind);
}

// Raw tracks: keys (time, value) with one interpolation, and a constant vector.
inline RawScalarTrack Keys(std::initializer_list<std::pair<double, double>> keys,
                           Interpolation interpolation = Interpolation::kLinear) {
  RawScalarTrack raw;
  for (auto [t, v] : keys) raw.keys.push_back({t, v, interpolation});
  return raw;
}

inline RawVectorTrack Constant(const Vec3& v) {
  RawVectorTrack raw;
  raw.keys.push_back({0.0, v, Interpolation::kStep});
  return raw;
}

}  // namespace wirerig::testing
