// The paper's procedural props (candles, trunk, lamp post, chair): closed, outward-facing
// pieces, rigs that build with no ray misses and the documented parts and parents, straight
// spines where the physics samples need them, and parameter errors that name the field.
#include "wirerig/procedural/props.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "wirerig/rig/mesh_statistics.h"
#include "wirerig/rig/rig_builder.h"
#include "wirerig/rig/rig_model_builder.h"
#include "wirerig/runtime/rigid_body.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

struct Expected {
  std::string part;
  std::string parent;
};

// Closed pieces enclosing positive volumes, a rig with every expected part and parent, no
// misses and no open profiles, and a runtime model.
void CheckProp(const ProceduralRigSource& prop, const std::vector<Expected>& expected,
               const std::string& label) {
  SCOPED_TRACE(label);
  const MeshStatistics stats = ComputeMeshStatistics(prop.mesh);
  EXPECT_TRUE(stats.closed());
  EXPECT_EQ(stats.degenerate_triangles, 0u);
  ASSERT_EQ(prop.mesh.parts.size(), expected.size());
  for (const MeshPart& part : prop.mesh.parts) {
    const std::vector<Triangle> triangles(
        prop.mesh.triangles.begin() + part.first_triangle,
        prop.mesh.triangles.begin() + part.first_triangle + part.triangle_count);
    MassProperties mass;
    EXPECT_TRUE(ComputeSolidMassProperties(prop.mesh.positions, triangles, 1000.0, &mass).ok())
        << part.name;
  }
  Result<BuiltRig> built = BuildRig(prop.mesh, prop.description, label);
  ASSERT_TRUE(built.ok()) << built.error();
  const Rig& rig = built.value().rig;
  ASSERT_EQ(rig.parts.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(rig.parts[i].name, expected[i].part);
    const std::string parent = rig.parts[i].parent < 0 ? "" : rig.parts[rig.parts[i].parent].name;
    EXPECT_EQ(parent, expected[i].parent) << expected[i].part;
    EXPECT_EQ(rig.parts[i].profiles.size(), std::size_t(prop.description.parts[i].profile_count))
        << expected[i].part;
  }
  for (const PartReport& report : built.value().report.parts) {
    EXPECT_EQ(report.profiles.misses, 0u) << report.name;
    EXPECT_EQ(report.profiles.open_profiles, 0u) << report.name;
    EXPECT_EQ(report.profiles.self_intersecting, 0u) << report.name;
  }
  Result<BuiltRigModel> model = BuildRigModel(prop.mesh, rig);
  ASSERT_TRUE(model.ok()) << model.error();
  EXPECT_EQ(model.value().report.fallback_vertices, 0u);
}

// Largest distance of a part's rest spine samples from the line through its ends.
double SpineStraightness(const PartModel& part) {
  const Vec3 a = part.spine_points.front(), axis = (part.spine_points.back() - a).normalized();
  double worst = 0.0;
  for (const Vec3& p : part.spine_points)
    worst = std::max(worst, ((p - a) - (p - a).dot(axis) * axis).norm());
  return worst;
}

RigModel ModelOf(const ProceduralRigSource& prop) {
  const Rig rig = BuildRig(prop.mesh, prop.description, "prop").value().rig;
  return BuildRigModel(prop.mesh, rig).value().model;
}

TEST(ProceduralProps, CandleRowIsUprightCandlesUnderTheFirst) {
  const ProceduralRigSource candles = MakeCandleRow().value();
  std::vector<Expected> expected;
  for (int i = 0; i < 6; ++i)
    expected.push_back({"candle_" + std::to_string(i), i == 0 ? "" : "candle_0"});
  CheckProp(candles, expected, "candles");
  const RigModel model = ModelOf(candles);
  for (const PartModel& part : model.parts) {
    EXPECT_EQ(part.spine_points.size(), 100u);  // 4 x 25 profiles
    EXPECT_LT(SpineStraightness(part), 1e-9);
    // The spine runs up the axis between the first and last profile, k / 26 of the height.
    EXPECT_NEAR(part.spine_length, 0.5 * 24.0 / 26.0, 1e-9);
    EXPECT_NEAR(part.spine_frames.front().tangent.y(), 1.0, 1e-12);
  }
}

TEST(ProceduralProps, BeamLiesAlongX) {
  const ProceduralRigSource beam = MakeBeam().value();
  CheckProp(beam, {{"beam", ""}}, "beam");
  const RigModel model = ModelOf(beam);
  EXPECT_LT(SpineStraightness(model.parts[0]), 1e-9);
  EXPECT_NEAR(model.parts[0].spine_frames.front().tangent.x(), 1.0, 1e-12);
  EXPECT_NEAR(model.parts[0].spine_length, 2.0 * 15.0 / 17.0, 1e-9);  // profiles k / 17
}

TEST(ProceduralProps, TrunkIsOneStraightTaperedPart) {
  const TrunkParameters parameters;
  const ProceduralRigSource trunk = MakeTrunk(parameters).value();
  CheckProp(trunk, {{"trunk", ""}}, "trunk");
  const RigModel model = ModelOf(trunk);
  EXPECT_LT(SpineStraightness(model.parts[0]), 1e-9);
  // Tapered: the lowest profile is wider than the highest.
  const auto radius = [](const ProfileModel& profile) {
    double sum = 0.0;
    for (const Vec3& q : profile.local_points) sum += q.head<2>().norm();
    return sum / double(profile.local_points.size());
  };
  EXPECT_GT(radius(model.parts[0].profiles.front()), radius(model.parts[0].profiles.back()));
  EXPECT_LT(radius(model.parts[0].profiles.back()), parameters.base_radius);
}

TEST(ProceduralProps, LampPostHasAPostAndALantern) {
  const ProceduralRigSource lamp = MakeLampPost().value();
  CheckProp(lamp, {{"post", ""}, {"lantern", "post"}}, "lamp_post");
  const RigModel model = ModelOf(lamp);
  EXPECT_LT(SpineStraightness(model.parts[0]), 1e-9);
  EXPECT_GT(model.parts[1].attachment, 0.95);  // the lantern sits on the post's top
}

TEST(ProceduralProps, ChairHasSeatBackAndFourLegs) {
  const ChairParameters parameters;
  const ProceduralRigSource chair = MakeChair(parameters).value();
  CheckProp(chair,
            {{"seat", ""},
             {"back", "seat"},
             {"leg_0", "seat"},
             {"leg_1", "seat"},
             {"leg_2", "seat"},
             {"leg_3", "seat"}},
            "chair");
  const RigModel model = ModelOf(chair);
  for (const PartModel& part : model.parts) EXPECT_LT(SpineStraightness(part), 1e-6) << part.name;
  // The seat's spine runs along +X, the back's up, each leg's down from under the seat.
  EXPECT_NEAR(model.parts[0].spine_frames.front().tangent.x(), 1.0, 1e-9);
  EXPECT_NEAR(model.parts[1].spine_frames.front().tangent.y(), 1.0, 1e-9);
  for (std::size_t leg = 2; leg < 6; ++leg) {
    EXPECT_NEAR(model.parts[leg].spine_frames.front().tangent.y(), -1.0, 1e-9);
    EXPECT_LT(model.parts[leg].spine_points.front().y(), parameters.seat_height - 0.07);
  }
}

TEST(ProceduralProps, RefuseBadParametersByName) {
  BeamParameters beam;
  beam.radius = 1.0;
  EXPECT_EQ(MakeBeam(beam).error(), "radius: must be positive and below a quarter of the length");
  CandleRowParameters candles;
  candles.spacing = 0.05;
  EXPECT_EQ(MakeCandleRow(candles).error(), "spacing: must exceed twice the radius (m)");
  candles = {};
  candles.height_segments = 0;
  EXPECT_EQ(MakeCandleRow(candles).error(), "height_segments: must be in [1, 4096]");
  TrunkParameters trunk;
  trunk.top_radius = 0.2;
  EXPECT_EQ(MakeTrunk(trunk).error(), "top_radius: must be positive and below base_radius");
  trunk = {};
  trunk.flare = std::nan("");
  EXPECT_EQ(MakeTrunk(trunk).error(), "flare: must be in [0, 2]");
  LampPostParameters lamp;
  lamp.base_radius = 0.01;
  EXPECT_EQ(MakeLampPost(lamp).error(), "base_radius: must exceed pole_radius");
  lamp = {};
  lamp.rings = 10;
  EXPECT_EQ(MakeLampPost(lamp).error(), "rings: must be in [24, 4096]");
  ChairParameters chair;
  chair.leg_radius = 0.2;
  EXPECT_EQ(MakeChair(chair).error(), "leg_radius: must be positive and below a tenth of the seat");
  chair = {};
  chair.points_per_profile = 2;
  EXPECT_EQ(MakeChair(chair).error(), "points_per_profile: must be in [3, 1024]");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
