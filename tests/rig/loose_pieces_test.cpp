// Loose pieces (eyes, teeth, buttons) ride rigidly on the part they sit on: a capsule rigged as
// an upper and a lower segment with a small sphere (a separate piece) beside the lower one; with
// the joint bent by 60 degrees the sphere keeps every distance between its vertices (a rigid
// motion) and moves with the lower segment, while the capsule's own skin bends.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/evaluate_rig.h"
#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_model_builder.h"
#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(LoosePieces, ASeparateSphereRidesRigidlyOnTheLimbItSitsOn) {
  Mesh mesh = MakeCapsule(0.1, 1.0, 32, 40, 8);
  const std::size_t body_vertices = mesh.welded_positions.size();
  Mesh sphere = MakeCapsule(0.03, 0.0, 8, 1, 3);  // under 5% of the vertices: loose
  const Vec3 offset(0.13, 0.25, 0.0);             // beside the lower segment, off its surface
  for (Vec3& p : sphere.positions) p += offset;
  for (Vec3& p : sphere.welded_positions) p += offset;
  AppendMesh(mesh, sphere);
  const std::size_t sphere_vertices = mesh.welded_positions.size() - body_vertices;

  RigDescription description;
  PartDescription upper, lower;
  upper.name = "upper";
  upper.central_curve = {Vec3(0, 1.05, 0), Vec3(0, 0.5, 0)};
  lower.name = "lower";
  lower.parent = "upper";
  lower.central_curve = {Vec3(0, 0.5, 0), Vec3(0, -0.05, 0)};
  lower.joint.type = JointType::kHinge;
  lower.joint.axis = Vec3::UnitZ();
  description.parts = {upper, lower};
  const Result<BuiltRig> rig = BuildRig(mesh, description, "capsule and sphere");
  ASSERT_TRUE(rig.ok()) << rig.error();
  RigModelOptions options;
  options.spine_kind = SpineKind::kRigid;
  const Result<BuiltRigModel> built = BuildRigModel(mesh, rig.value().rig, options);
  ASSERT_TRUE(built.ok()) << built.error();
  EXPECT_EQ(built.value().report.loose_pieces, 1u);
  EXPECT_EQ(built.value().report.loose_vertices, sphere_vertices);
  const RigModel& model = built.value().model;

  std::vector<PartPose> poses(2);
  poses[1].rotation = JointRotation(model.parts[1].joint, Vec3(60, 0, 0));
  const std::vector<Vec3> positions = testing::EvaluatePose(model, poses);

  const std::vector<Vec3>& rest = mesh.welded_positions;
  double worst = 0.0;
  Vec3 moved = Vec3::Zero();
  for (std::size_t a = body_vertices; a < rest.size(); ++a) {
    EXPECT_EQ(model.vertices[a].part, 1u);
    moved += positions[a] - rest[a];
    for (std::size_t b = a + 1; b < rest.size(); ++b)
      worst = std::max(worst,
                       std::abs((positions[a] - positions[b]).norm() - (rest[a] - rest[b]).norm()));
  }
  EXPECT_LT(worst, 1e-9);                                   // rigid
  EXPECT_GT(moved.norm() / double(sphere_vertices), 0.05);  // with the lower segment
  double body_change = 0.0;                                 // the capsule itself bends
  for (std::size_t a = 0; a + 1 < body_vertices; ++a)
    body_change = std::max(body_change, std::abs((positions[a] - positions[a + 1]).norm() -
                                                 (rest[a] - rest[a + 1]).norm()));
  EXPECT_GT(body_change, 1e-4);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
