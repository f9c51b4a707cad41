// The rig-building pipeline on real meshes (ASSETS.md) and on a procedural gap case:
// every profile point lies on the surface, every spine point inside the closed mesh (winding
// number), no ray misses on closed parts, and the expected parts exist.
#include "wirerig/rig/rig_builder.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/curve_skeleton.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/mesh_statistics.h"
#include "wirerig/rig/skeleton_description.h"
#include "wirerig/rig/triangle_bvh.h"

#ifndef WIRERIG_ASSET_DIR
#error "the tests need WIRERIG_ASSET_DIR (set by CMake)"
#endif
#ifndef WIRERIG_SAMPLES_DIR
#error "the tests need WIRERIG_SAMPLES_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

std::string Asset(const std::string& name) { return std::string(WIRERIG_ASSET_DIR) + "/" + name; }

Mesh Import(const std::string& path) {
  Result<ImportedMesh> imported = ImportMesh(path);
  EXPECT_TRUE(imported.ok()) << imported.error();
  return imported.ok() ? std::move(imported).value().mesh : Mesh{};
}

// Triangles of mesh parts that are closed on their own (the body, not the eyes).
std::vector<Triangle> ClosedPartTriangles(const Mesh& mesh) {
  std::vector<Triangle> closed;
  for (const MeshPart& part : mesh.parts) {
    Mesh piece;
    piece.welded_positions = mesh.welded_positions;
    piece.positions = mesh.welded_positions;
    for (std::uint32_t f = 0; f < part.triangle_count; ++f)
      piece.welded_triangles.push_back(mesh.welded_triangles[part.first_triangle + f]);
    piece.triangles = piece.welded_triangles;
    if (ComputeMeshStatistics(piece).closed())
      closed.insert(closed.end(), piece.welded_triangles.begin(), piece.welded_triangles.end());
  }
  return closed;
}

void ExpectRigFitsMesh(const Mesh& mesh, const BuiltRig& built) {
  const double diagonal = ComputeBounds(mesh).Diagonal();
  const TriangleBvh surface = TriangleBvh::Build(mesh.welded_positions, mesh.welded_triangles);
  const std::vector<Triangle> closed = ClosedPartTriangles(mesh);
  ASSERT_FALSE(closed.empty());
  for (std::size_t i = 0; i < built.rig.parts.size(); ++i) {
    const RigPart& part = built.rig.parts[i];
    SCOPED_TRACE("part " + part.name);
    if (!part.skin) {  // a skinless bone: its 2 spine points inside the body, no profiles
      EXPECT_TRUE(part.profiles.empty());
      EXPECT_EQ(part.spine_points.size(), 2u);
      for (const Vec3& s : part.spine_points)
        EXPECT_GT(WindingNumber(mesh.welded_positions, closed, s), 0.5) << s.transpose();
      continue;
    }
    EXPECT_EQ(built.report.parts[i].profiles.misses, 0u);
    EXPECT_GE(part.profiles.size(), 2u);
    for (const ProfileCurve& profile : part.profiles) {
      EXPECT_TRUE(profile.closed);
      for (const Vec3& p : profile.points) EXPECT_LE(surface.Closest(p)->distance, 1e-5 * diagonal);
    }
    for (const Vec3& s : part.spine_points)
      EXPECT_GT(WindingNumber(mesh.welded_positions, closed, s), 0.5) << s.transpose();
  }
}

bool HasPart(const Rig& rig, const std::string& name) {
  return std::any_of(rig.parts.begin(), rig.parts.end(),
                     [&](const RigPart& p) { return p.name == name; });
}

// A part whose central curve lies outside the mesh has no profiles: the rig fails naming it,
// unless such parts may be dropped (automatic descriptions), when its skin and children go to
// its parent and a warning says so.
TEST(RigBuilder, PartWithoutProfilesFailsOrIsDroppedToItsParent) {
  const Mesh mesh = MakeCapsule(0.1, 1.0, 24, 20, 6);
  RigDescription description;
  PartDescription body, fin, tip;
  body.name = "body";
  body.central_curve = {Vec3(0, 1.05, 0), Vec3(0, -0.05, 0)};
  fin.name = "fin";  // beside the capsule, outside it
  fin.parent = "body";
  fin.central_curve = {Vec3(0.5, 0.3, 0), Vec3(0.9, 0.3, 0)};
  tip = fin;
  tip.name = "tip";
  tip.parent = "fin";
  tip.central_curve = {Vec3(0.9, 0.3, 0), Vec3(1.2, 0.3, 0)};
  description.parts = {body, fin, tip};
  const Result<BuiltRig> strict = BuildRig(mesh, description, "capsule");
  ASSERT_FALSE(strict.ok());
  EXPECT_EQ(strict.error().rfind("part 'fin': 0 of 12 profiles hit its surface", 0), 0u)
      << strict.error();
  RigBuildOptions options;
  options.drop_parts_without_profiles = true;
  const Result<BuiltRig> dropped = BuildRig(mesh, description, "capsule", options);
  ASSERT_TRUE(dropped.ok()) << dropped.error();
  ASSERT_EQ(dropped.value().rig.parts.size(), 1u);
  EXPECT_EQ(dropped.value().rig.parts[0].name, "body");
  const std::vector<std::string>& warnings = dropped.value().report.warnings;
  const auto said = [&](const std::string& text) {
    return std::any_of(warnings.begin(), warnings.end(),
                       [&](const std::string& w) { return w.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(said("part 'fin': 0 of 12 profiles hit its surface"));
  EXPECT_TRUE(said("dropped: its skin follows 'body'"));
  EXPECT_TRUE(said("part 'tip': 0 of 12 profiles hit its surface"));  // then its child
}

// A root that misses the surface (the faerie's automatic torso did) gives its place to its
// child with the largest subtree, which takes the root's skin and other children; a root
// without children still fails.
TEST(RigBuilder, RootWithoutProfilesGivesItsPlaceToItsLargestChild) {
  const Mesh mesh = MakeCapsule(0.1, 1.0, 24, 20, 6);
  RigDescription description;
  PartDescription stray, upper, lower, stub;
  stray.name = "stray";  // beside the capsule, outside it
  stray.central_curve = {Vec3(0.5, 0.9, 0), Vec3(0.9, 0.9, 0)};
  upper.name = "upper";
  upper.parent = "stray";
  upper.central_curve = {Vec3(0, 1.05, 0), Vec3(0, 0.5, 0)};
  lower = upper;
  lower.name = "lower";
  lower.parent = "upper";
  lower.central_curve = {Vec3(0, 0.5, 0), Vec3(0, -0.05, 0)};
  stub = stray;  // another child of the root, outside too: dropped in turn
  stub.name = "stub";
  stub.parent = "stray";
  stub.central_curve = {Vec3(0.9, 0.9, 0), Vec3(1.2, 0.9, 0)};
  description.parts = {stray, stub, upper, lower};
  RigBuildOptions options;
  options.drop_parts_without_profiles = true;
  const Result<BuiltRig> built = BuildRig(mesh, description, "capsule", options);
  ASSERT_TRUE(built.ok()) << built.error();
  const Rig& rig = built.value().rig;
  ASSERT_EQ(rig.parts.size(), 2u);
  EXPECT_EQ(rig.parts[0].name, "upper");
  EXPECT_EQ(rig.parts[0].parent, -1);
  EXPECT_EQ(rig.parts[1].name, "lower");
  EXPECT_EQ(rig.parts[1].parent, 0);
  const std::vector<std::string>& warnings = built.value().report.warnings;
  EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(), [](const std::string& w) {
    return w.find("part 'stray': 0 of 12 profiles hit its surface") != std::string::npos &&
           w.find("dropped: its skin follows 'upper', the new root") != std::string::npos;
  }));
  // Every vertex is bound: the capsule's skin went to the two parts left.
  EXPECT_EQ(built.value().report.parts[0].vertices + built.value().report.parts[1].vertices,
            mesh.welded_positions.size());
  description.parts = {stray};
  const Result<BuiltRig> alone = BuildRig(mesh, description, "capsule", options);
  ASSERT_FALSE(alone.ok());
  EXPECT_EQ(alone.error().rfind("part 'stray': 0 of 12 profiles hit its surface", 0), 0u)
      << alone.error();
}

TEST(RigBuilder, HumanFromItsDescription) {
  const Mesh mesh = Import(Asset("assimp/Collada/human.zae"));
  const Result<RigDescription> description =
      LoadRigDescription(std::string(WIRERIG_SAMPLES_DIR) + "/rigs/human.description.json");
  ASSERT_TRUE(description.ok()) << description.error();
  const Result<BuiltRig> built = BuildRig(mesh, description.value(), "human.zae");
  ASSERT_TRUE(built.ok()) << built.error();
  // A bone chain like a game skeleton's.
  for (const char* name : {"pelvis",     "spine_1",     "spine_2",     "chest",     "neck",
                           "head",       "clavicle_l",  "upper_arm_l", "forearm_l", "hand_l",
                           "clavicle_r", "upper_arm_r", "forearm_r",   "hand_r",    "thigh_l",
                           "shin_l",     "foot_l",      "thigh_r",     "shin_r",    "foot_r"})
    EXPECT_TRUE(HasPart(built.value().rig, name)) << name;
  ExpectRigFitsMesh(mesh, built.value());
  // Clavicles hang from the chest beside its middle (the shoulder joints lie below the top of
  // the chest's loops), upper arms from the clavicles' ends, thighs from the bottom of the
  // pelvis, and each segment of a chain from the end of the one before.
  for (const RigPart& part : built.value().rig.parts) {
    if (part.name.starts_with("clavicle")) {
      EXPECT_GT(part.attachment, 0.2) << part.name;
      EXPECT_EQ(built.value().rig.parts[part.parent].name, "chest");
    }
    if (part.name.starts_with("upper_arm")) {
      EXPECT_GT(part.attachment, 0.9) << part.name;
      EXPECT_TRUE(built.value().rig.parts[part.parent].name.starts_with("clavicle"));
    }
    if (part.name.starts_with("thigh")) {
      EXPECT_LT(part.attachment, 0.3) << part.name;
    }
    if (part.name.starts_with("forearm") || part.name.starts_with("shin") || part.name == "neck" ||
        part.name == "head") {
      EXPECT_GT(part.attachment, 0.9) << part.name;
    }
  }
}

TEST(RigBuilder, CowFromItsCurveSkeleton) {
  const Mesh mesh = Import(Asset("cow.off"));
  const Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_TRUE(skeleton.ok()) << skeleton.error();
  const Result<RigDescription> description = DescribeFromCurveSkeleton(mesh, skeleton.value());
  ASSERT_TRUE(description.ok()) << description.error();
  const Result<BuiltRig> built = BuildRig(mesh, description.value(), "cow.off");
  ASSERT_TRUE(built.ok()) << built.error();
  const Rig& rig = built.value().rig;
  EXPECT_TRUE(HasPart(rig, "torso"));
  EXPECT_TRUE(HasPart(rig, "head"));
  EXPECT_TRUE(HasPart(rig, "tail"));
  EXPECT_EQ(std::count_if(rig.parts.begin(), rig.parts.end(),
                          [](const RigPart& p) { return p.name.starts_with("leg"); }),
            8);  // four legs, each an upper and a lower segment
  ExpectRigFitsMesh(mesh, built.value());
}

TEST(RigBuilder, ElephantFromItsCurveSkeleton) {
  const Mesh mesh = Import(Asset("elephant.off"));
  const Result<CurveSkeleton> skeleton = ExtractCurveSkeleton(mesh);
  ASSERT_TRUE(skeleton.ok()) << skeleton.error();
  const Result<RigDescription> description = DescribeFromCurveSkeleton(mesh, skeleton.value());
  ASSERT_TRUE(description.ok()) << description.error();
  const Result<BuiltRig> built = BuildRig(mesh, description.value(), "elephant.off");
  ASSERT_TRUE(built.ok()) << built.error();
  EXPECT_GE(built.value().rig.parts.size(), 6u);
  ExpectRigFitsMesh(mesh, built.value());
}

TEST(RigBuilder, TestwusonFromItsSkeletonWithNoHandInput) {
  const Mesh mesh = Import(Asset("assimp/X/Testwuson.X"));
  ASSERT_FALSE(mesh.joints.empty());
  const Result<RigDescription> description = DescribeFromSkeleton(mesh);
  ASSERT_TRUE(description.ok()) << description.error();
  EXPECT_GE(description.value().parts.size(), 5u);
  const Result<BuiltRig> built = BuildRig(mesh, description.value(), "Testwuson.X");
  ASSERT_TRUE(built.ok()) << built.error();
  const Rig& rig = built.value().rig;
  EXPECT_EQ(rig.parts.size(), description.value().parts.size());
  EXPECT_EQ(rig.parts[0].parent, -1);
  for (std::size_t i = 1; i < rig.parts.size(); ++i) EXPECT_GE(rig.parts[i].parent, 0);
  // Skin weights decided the assignment: every part that owns vertices got some profiles.
  std::size_t with_profiles = 0;
  for (const RigPart& part : rig.parts) with_profiles += part.profiles.size() >= 2;
  EXPECT_EQ(with_profiles, rig.parts.size());
}

// Appends `b` to `a` as a second mesh part.
Mesh Combine(Mesh a, const Mesh& b, const std::string& name_a, const std::string& name_b) {
  const auto offset = std::uint32_t(a.welded_positions.size());
  const auto first = std::uint32_t(a.welded_triangles.size());
  a.parts = {{name_a, 0, first, -1}, {name_b, first, std::uint32_t(b.welded_triangles.size()), -1}};
  for (const Vec3& p : b.welded_positions) a.welded_positions.push_back(p);
  for (Triangle t : b.welded_triangles) {
    for (auto& i : t) i += offset;
    a.welded_triangles.push_back(t);
  }
  a.positions = a.welded_positions;
  a.triangles = a.welded_triangles;
  a.weld_map.resize(a.positions.size());
  for (std::uint32_t i = 0; i < a.weld_map.size(); ++i) a.weld_map[i] = i;
  a.normals.clear();
  return a;
}

TEST(RigBuilder, APartNeverTakesVerticesAcrossAGap) {
  // A thick "torso" cylinder and a thin "arm" cylinder beside it, 5 cm apart: the torso's
  // surface facing the arm is nearer the arm's axis (0.1 m) than its own (0.2 m), yet the
  // segment from the arm's axis to it leaves the arm, so it stays with the torso.
  Mesh torso = MakeCylinder(0.2, 1.0, 64, 8);
  Mesh arm = MakeCylinder(0.05, 1.0, 32, 8);
  for (Vec3& p : arm.welded_positions) p.x() += 0.3;
  const Mesh mesh = Combine(torso, arm, "torso_mesh", "arm_mesh");
  RigDescription description;
  description.parts.push_back({"torso", {Vec3(0, 0.01, 0), Vec3(0, 0.99, 0)}, 6, 16, "", {}, {}});
  description.parts.push_back(
      {"arm", {Vec3(0.3, 0.99, 0), Vec3(0.3, 0.01, 0)}, 6, 16, "torso", {}, {}});
  const Result<BuiltRig> built = BuildRig(mesh, description, "procedural");
  ASSERT_TRUE(built.ok()) << built.error();
  const std::size_t torso_vertices = torso.welded_positions.size();
  for (std::size_t v = 0; v < mesh.welded_positions.size(); ++v)
    EXPECT_EQ(built.value().rig.vertex_part[v], v < torso_vertices ? 0 : 1) << "vertex " << v;
  for (const PartReport& report : built.value().report.parts) {
    EXPECT_EQ(report.profiles.misses, 0u);
    EXPECT_EQ(report.profiles.other_part_hits, 0u);
  }
}

TEST(RigBuilder, ACentralCurveOutsideTheMeshIsAClearError) {
  const Mesh mesh = MakeCylinder(0.2, 1.0, 64, 8);
  RigDescription description;
  description.parts.push_back({"body", {Vec3(2, 0, 0), Vec3(2, 1, 0)}, 6, 16, "", {}, {}});
  const Result<BuiltRig> built = BuildRig(mesh, description, "procedural");
  ASSERT_FALSE(built.ok());
  EXPECT_NE(built.error().find("part 'body'"), std::string::npos) << built.error();
  EXPECT_NE(built.error().find("is its central curve inside the mesh?"), std::string::npos);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
