// Automatic rigs of meshes the curve skeleton cannot take as they are: an open tube (both caps
// removed), a capsule with a separate sphere beside it, Testwuson.X (open, 51 pieces) with its
// skeleton ignored. Their alpha wrap is one closed 2-manifold around them, and the rig's parts
// run along the known axes. A flat sheet is refused with its reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/automatic_description.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/watertight_proxy.h"

#ifndef WIRERIG_ASSET_DIR
#error "the tests need WIRERIG_ASSET_DIR (set by CMake)"
#endif

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

// A cylinder (r = 0.1 m, 1 m along +Y) without its two end caps: open at both ends.
Mesh OpenTube() {
  Mesh mesh = MakeCylinder(0.1, 1.0, 24, 20);
  std::vector<Triangle> kept;
  for (const Triangle& t : mesh.welded_triangles) {
    const Vec3 n = (mesh.welded_positions[t[1]] - mesh.welded_positions[t[0]])
                       .cross(mesh.welded_positions[t[2]] - mesh.welded_positions[t[0]]);
    if (std::abs(n.normalized().y()) < 0.5) kept.push_back(t);  // the side, not a cap
  }
  mesh.triangles = mesh.welded_triangles = kept;
  mesh.weld_map.clear();
  mesh.positions = mesh.welded_positions;
  mesh.parts = {{"tube", 0, std::uint32_t(kept.size()), -1}};
  return mesh;
}

// The angle (degrees) between the chord of a part's central curve and +Y.
double DegreesFromY(const PartDescription& part) {
  const Vec3 chord = (part.central_curve.back() - part.central_curve.front()).normalized();
  return std::acos(std::min(1.0, std::abs(chord.y()))) * 180.0 / M_PI;
}

TEST(WatertightProxy, SaysWhyAMeshNeedsAWrap) {
  EXPECT_EQ(WatertightProblem(MakeCapsule(0.1, 1.0, 24, 20, 6)), "");
  const std::string open = WatertightProblem(OpenTube());
  EXPECT_NE(open.find("not closed: 48 boundary edges"), std::string::npos) << open;
  Mesh pieces = MakeCapsule(0.1, 1.0, 24, 20, 6);
  Mesh sphere = MakeCapsule(0.15, 0.0, 16, 1, 8);
  for (Vec3& p : sphere.positions) p.x() += 0.5;
  for (Vec3& p : sphere.welded_positions) p.x() += 0.5;
  AppendMesh(pieces, sphere);
  EXPECT_EQ(WatertightProblem(pieces), "the mesh is in 2 separate pieces");
}

TEST(WatertightProxy, WrapIsClosedAndHugsTheMesh) {
  const Mesh tube = OpenTube();
  const Result<WatertightProxy> wrap = WrapWatertight(tube);
  ASSERT_TRUE(wrap.ok()) << wrap.error();
  EXPECT_EQ(WatertightProblem(wrap.value().mesh), "");
  const double diagonal = std::sqrt(0.2 * 0.2 * 2 + 1.0);
  EXPECT_NEAR(wrap.value().alpha, diagonal / kWrapRelativeAlpha, 1e-12);
  // Every wrap vertex lies within alpha + offset of the tube with its ends closed (the wrap
  // closes the holes): the cylinder of radius 0.1 about the Y axis, y in [0, 1].
  for (const Vec3& p : wrap.value().mesh.welded_positions) {
    const double radial = std::hypot(p.x(), p.z()) - 0.1;
    const double axial = std::max(-p.y(), p.y() - 1.0);  // < 0 between the ends
    const double distance = radial > 0.0 || axial > 0.0
                                ? std::hypot(std::max(radial, 0.0), std::max(axial, 0.0))
                                : -std::max(radial, axial);
    EXPECT_LT(distance, wrap.value().alpha + wrap.value().offset) << p.transpose();
  }
  EXPECT_EQ(wrap.value().holes_closed, 2u);
  WrapOptions options;
  options.alpha = -1.0;  // not set: from the mesh
  EXPECT_TRUE(WrapWatertight(tube, options).ok());
  // Far below the diagonal: refused with the least alpha allowed, before any work.
  options.alpha = diagonal / 1e4;
  const Result<WatertightProxy> tiny = WrapWatertight(tube, options);
  ASSERT_FALSE(tiny.ok());
  EXPECT_NE(tiny.error().find("below the mesh's diagonal / 200"), std::string::npos)
      << tiny.error();
  options.alpha = diagonal / 190.0;  // within the bound: wraps
  EXPECT_TRUE(WrapWatertight(tube, options).ok());
}

TEST(WatertightProxy, OpenTubeRigsAlongItsAxis) {
  const Mesh tube = OpenTube();
  const Result<AutomaticDescription> automatic = DescribeAutomatically(tube);
  ASSERT_TRUE(automatic.ok()) << automatic.error();
  EXPECT_NE(automatic.value().source.find("alpha wrap"), std::string::npos);
  EXPECT_NE(automatic.value().source.find("boundary edges"), std::string::npos);
  const RigDescription& d = automatic.value().description;
  ASSERT_GE(d.parts.size(), 1u);
  EXPECT_LT(DegreesFromY(d.parts[0]), 5.0);
  for (const Vec3& p : d.parts[0].central_curve) EXPECT_LT(std::hypot(p.x(), p.z()), 0.03);
  const Result<BuiltRig> rig = BuildRig(tube, d, "open tube");
  EXPECT_TRUE(rig.ok()) << rig.error();
}

TEST(WatertightProxy, CapsuleWithASphereBesideItRigsAlongTheCapsule) {
  Mesh mesh = MakeCapsule(0.1, 1.0, 24, 20, 6);
  Mesh sphere = MakeCapsule(0.12, 0.0, 16, 1, 8);
  for (Vec3& p : sphere.positions) p += Vec3(0.6, 0.5, 0.0);
  for (Vec3& p : sphere.welded_positions) p += Vec3(0.6, 0.5, 0.0);
  AppendMesh(mesh, sphere);
  const Result<AutomaticDescription> automatic = DescribeAutomatically(mesh);
  ASSERT_TRUE(automatic.ok()) << automatic.error();
  EXPECT_NE(automatic.value().source.find("2 separate pieces"), std::string::npos);
  const RigDescription& d = automatic.value().description;
  ASSERT_GE(d.parts.size(), 1u);
  EXPECT_LT(DegreesFromY(d.parts[0]), 5.0);
  for (const Vec3& p : d.parts[0].central_curve) EXPECT_LT(std::hypot(p.x(), p.z()), 0.03);
}

TEST(WatertightProxy, FlatSheetIsRefusedWithItsReason) {
  Mesh sheet;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j) sheet.positions.emplace_back(0.1 * i, 0.0, 0.1 * j);
  for (std::uint32_t i = 0; i < 10; ++i)
    for (std::uint32_t j = 0; j < 10; ++j) {
      const std::uint32_t a = i * 11 + j;
      sheet.triangles.push_back({a, a + 1, a + 12});
      sheet.triangles.push_back({a, a + 12, a + 11});
    }
  sheet.parts = {{"sheet", 0, std::uint32_t(sheet.triangles.size()), -1}};
  WeldByPosition(sheet);
  const Result<AutomaticDescription> automatic = DescribeAutomatically(sheet);
  ASSERT_FALSE(automatic.ok());
  EXPECT_NE(automatic.error().find("not closed"), std::string::npos) << automatic.error();
  EXPECT_NE(automatic.error().find("it is flat"), std::string::npos) << automatic.error();
}

TEST(WatertightProxy, TestwusonRigsFromItsWrapWithTheSkeletonIgnored) {
  Result<ImportedMesh> imported =
      ImportMesh(std::string(WIRERIG_ASSET_DIR) + "/assimp/X/Testwuson.X");
  ASSERT_TRUE(imported.ok()) << imported.error() << " (asset missing: run scripts/setup.sh)";
  const Mesh& mesh = imported.value().mesh;
  AutomaticOptions options;
  options.ignore_skeleton = true;
  const Result<AutomaticDescription> automatic = DescribeAutomatically(mesh, options);
  ASSERT_TRUE(automatic.ok()) << automatic.error();
  EXPECT_NE(automatic.value().source.find("alpha wrap"), std::string::npos);
  const RigDescription& d = automatic.value().description;
  std::vector<std::string> names;
  for (const PartDescription& p : d.parts) names.push_back(p.name);
  for (const char* expected :
       {"torso", "head", "tail", "leg_front_left_upper", "leg_back_right_lower"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  // Rays escaping through the model's holes take the wrap's hit: none misses.
  ASSERT_TRUE(automatic.value().wrap.has_value());
  RigBuildOptions build_options;
  build_options.wrap = &*automatic.value().wrap;
  const Result<BuiltRig> rig = BuildRig(mesh, d, "Testwuson.X", build_options);
  ASSERT_TRUE(rig.ok()) << rig.error();
  std::size_t misses = 0, through_holes = 0;
  for (const PartReport& part : rig.value().report.parts) {
    misses += part.profiles.misses;
    through_holes += part.profiles.wrap_hits;
  }
  EXPECT_EQ(misses, 0u);
  EXPECT_GT(through_holes, 0u);
  const Result<BuiltRig> unwrapped = BuildRig(mesh, d, "Testwuson.X");
  ASSERT_TRUE(unwrapped.ok()) << unwrapped.error();
  std::size_t unwrapped_misses = 0;
  for (const PartReport& part : unwrapped.value().report.parts)
    unwrapped_misses += part.profiles.misses;
  EXPECT_EQ(unwrapped_misses, through_holes);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
