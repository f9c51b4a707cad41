// The procedural octopus: closed pieces, a rig that builds with no misses, tentacle profiles
// that are circles of the tapered radius around the centre line, and named parameter errors.
#include "wirerig/procedural/octopus.h"

#include <gtest/gtest.h>

#include "wirerig/procedural/shapes.h"
#include "wirerig/rig/mesh_statistics.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_model_builder.h"
#include "wirerig/runtime/rigid_body.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(ProceduralOctopus, PiecesAreClosedAndOutwardFacing) {
  const ProceduralRigSource octopus = MakeOctopus().value();
  const MeshStatistics stats = ComputeMeshStatistics(octopus.mesh);
  EXPECT_TRUE(stats.closed());
  EXPECT_EQ(stats.connected_components, 9u);
  EXPECT_EQ(stats.degenerate_triangles, 0u);
  ASSERT_EQ(octopus.mesh.parts.size(), 9u);
  // Each piece encloses a positive volume (outward faces): signed-tetrahedra mass properties
  // refuse inward or open surfaces.
  for (const MeshPart& part : octopus.mesh.parts) {
    const std::vector<Triangle> triangles(
        octopus.mesh.triangles.begin() + part.first_triangle,
        octopus.mesh.triangles.begin() + part.first_triangle + part.triangle_count);
    MassProperties mass;
    EXPECT_TRUE(ComputeSolidMassProperties(octopus.mesh.positions, triangles, 1000.0, &mass).ok())
        << part.name;
  }
}

TEST(ProceduralOctopus, SweptTubeOfConstantRadiusHasTheCylindersVolume) {
  // A straight swept tube without poles is open; with poles at both ends it is a cylinder with
  // cone caps: volume pi r^2 (h - 2d) + 2 (pi r^2 d / 3) for pole distance d.
  std::vector<Vec3> centres;
  std::vector<double> radii;
  const int rings = 20;
  for (int k = 0; k <= rings; ++k) {
    centres.emplace_back(0.0, 0.1 * k, 0.0);
    radii.push_back(k == 0 || k == rings ? 0.0 : 0.3);
  }
  const Mesh tube = MakeSweptTube(centres, radii, 256, "tube");
  MassProperties mass;
  ASSERT_TRUE(ComputeSolidMassProperties(tube.positions, tube.triangles, 1.0, &mass).ok());
  const double r = 0.3, h = 2.0, d = 0.1, pi = std::numbers::pi;
  // The 256-gon's area is (256 / 2pi) sin(2pi / 256) of the circle's.
  const double polygon = 256.0 / (2.0 * pi) * std::sin(2.0 * pi / 256.0);
  const double expected = polygon * (pi * r * r * (h - 2 * d) + 2.0 * pi * r * r * d / 3.0);
  EXPECT_NEAR(mass.volume, expected, 1e-9 * expected);
}

TEST(ProceduralOctopus, RigBuildsWithCircularTentacleProfiles) {
  const OctopusParameters parameters;
  const ProceduralRigSource octopus = MakeOctopus(parameters).value();
  Result<BuiltRig> built = BuildRig(octopus.mesh, octopus.description, "procedural:octopus");
  ASSERT_TRUE(built.ok()) << built.error();
  const Rig& rig = built.value().rig;
  ASSERT_EQ(rig.parts.size(), 9u);
  for (const PartReport& report : built.value().report.parts) {
    EXPECT_EQ(report.profiles.misses, 0u) << report.name;
    EXPECT_EQ(report.profiles.open_profiles, 0u) << report.name;
  }
  for (std::size_t p = 1; p < rig.parts.size(); ++p) {
    const RigPart& tentacle = rig.parts[p];
    EXPECT_EQ(tentacle.parent, 0);
    EXPECT_LT(tentacle.attachment, 0.5);  // from the mantle's underside
    ASSERT_GE(tentacle.profiles.size(), 10u);
    for (const ProfileCurve& profile : tentacle.profiles) {
      double lo = 1e9, hi = 0.0;
      for (const Vec3& q : profile.points) {
        const double r = (q - profile.origin).norm();
        lo = std::min(lo, r);
        hi = std::max(hi, r);
      }
      // A circle of one radius around the re-centred origin: the 24-gon's rings are cut by a
      // plane close to, not exactly at, a ring, so allow a few percent.
      EXPECT_LT(hi - lo, 0.06 * hi) << tentacle.name << " v " << profile.v;
      EXPECT_LE(hi, parameters.tentacle_radius * 1.02);
      EXPECT_GE(lo, parameters.tip_radius * 0.9);
    }
  }
  EXPECT_TRUE(BuildRigModel(octopus.mesh, rig).ok());
}

TEST(ProceduralOctopus, RefusesBadParametersByName) {
  OctopusParameters p;
  p.tentacle_count = 0;
  EXPECT_EQ(MakeOctopus(p).error(), "tentacle_count: must be in [1, 64]");
  p = {};
  p.tip_radius = 0.1;
  EXPECT_EQ(MakeOctopus(p).error(), "tip_radius: must be positive and below tentacle_radius");
  p = {};
  p.mantle_radius = std::nan("");
  EXPECT_EQ(MakeOctopus(p).error(), "mantle_radius: must be in (0, 1e6) m");
  p.mantle_radius = 1e300;  // said "must be positive" of a positive number: the bound is stated
  EXPECT_EQ(MakeOctopus(p).error(), "mantle_radius: must be in (0, 1e6) m");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
