// BuildRigModel's refusals: a rig for another mesh (counts differ), and rig-file geometry far
// outside the mesh's box (a rig file point of 2e9 m was accepted).
#include "wirerig/rig/rig_model_builder.h"

#include <gtest/gtest.h>

#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/rig/rig_builder.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

struct Capsule {
  Mesh mesh;
  Rig rig;
};

const Capsule& RiggedCapsule() {
  static const Capsule capsule = [] {
    Capsule c;
    c.mesh = MakeCapsule(0.1, 1.0, 24, 10, 4);
    RigDescription description;
    description.parts.push_back({"body", {Vec3(0, 0, 0), Vec3(0, 1, 0)}, 6, 16, "", {}, {}});
    c.rig = BuildRig(c.mesh, description, "capsule").value().rig;
    return c;
  }();
  return capsule;
}

TEST(BuildRigModel, TheRigOfItsMeshBuilds) {
  const Capsule& c = RiggedCapsule();
  const Result<BuiltRigModel> built = BuildRigModel(c.mesh, c.rig);
  EXPECT_TRUE(built.ok()) << built.error();
}

TEST(BuildRigModel, RefusesAProfilePointFarOutsideTheMeshsBox) {
  const Capsule& c = RiggedCapsule();
  Rig rig = c.rig;
  ASSERT_GT(rig.parts[0].profiles.size(), 2u);
  rig.parts[0].profiles[2].points[5] = Vec3(2e9, 0.5, 0);
  const Result<BuiltRigModel> built = BuildRigModel(c.mesh, rig);
  ASSERT_FALSE(built.ok());
  EXPECT_EQ(built.error().rfind("part 'body': profiles[2].points[5]: (2e+09, 0.5, 0) m lies far "
                                "outside the mesh's box",
                                0),
            0u)
      << built.error();
}

TEST(BuildRigModel, RefusesSpineAndCurvePointsFarOutsideButNotNearTheBox) {
  const Capsule& c = RiggedCapsule();
  const double diagonal = ComputeBounds(c.mesh).Diagonal();
  Rig rig = c.rig;
  rig.parts[0].spine_points.back().x() += 3.0 * diagonal;
  Result<BuiltRigModel> built = BuildRigModel(c.mesh, rig);
  ASSERT_FALSE(built.ok());
  EXPECT_NE(built.error().find("spine_points["), std::string::npos) << built.error();
  rig = c.rig;
  rig.parts[0].central_curve[0] = Vec3(0, -1e9, 0);
  built = BuildRigModel(c.mesh, rig);
  ASSERT_FALSE(built.ok());
  EXPECT_NE(built.error().find("central_curve[0]"), std::string::npos) << built.error();
  // Half a diagonal outside the box is within reach (a curve may stick out of the surface).
  rig = c.rig;
  rig.parts[0].central_curve[0] = Vec3(0, -0.5 * diagonal, 0);
  EXPECT_TRUE(BuildRigModel(c.mesh, rig).ok());
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
