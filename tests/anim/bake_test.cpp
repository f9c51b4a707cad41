// Baking: key times, the baked spine tip against the cantilever formula at every key, render
// vertices following their welded vertex, frames as rotations, progress and bad options.
#include "wirerig/anim/bake.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "anim_test_rigs.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

using testing::Beam;

Clip TipLoadClip(double duration) {
  RawClip raw;
  raw.name = "push";
  raw.duration = duration;
  RawPartTracks part;
  part.part = "beam";
  PointLoadChannels<RawTrack> load;
  load.at.keys = {{0.0, 1.0, Interpolation::kStep}};
  load.magnitude.keys = {{0.0, 0.0, Interpolation::kLinear},
                         {duration, 0.05, Interpolation::kLinear}};
  load.direction.keys = {{0.0, Vec3(0, 1, 0), Interpolation::kStep}};
  part.channels.point_loads.push_back(load);
  raw.parts.push_back(part);
  return BuildClip(raw, Beam().model).value();
}

TEST(Bake, KeyTimesCoverTheClipAndItsEnd) {
  EXPECT_EQ(BakeKeyTimes(1.0, 4.0), (std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0}));
  EXPECT_EQ(BakeKeyTimes(0.6, 4.0), (std::vector<double>{0.0, 0.25, 0.5, 0.6}));
  EXPECT_EQ(BakeKeyTimes(10.0, 30.0).size(), 301u);
}

TEST(Bake, SpineTipFollowsTheCantileverFormulaAtEveryKey) {
  const testing::TestRig& rig = Beam();
  const Clip clip = TipLoadClip(2.0);
  std::size_t calls = 0;
  BakeOptions options;
  options.fps = 10.0;
  options.progress = [&](std::size_t done, std::size_t total) {
    EXPECT_EQ(done, ++calls);
    EXPECT_EQ(total, 21u);
  };
  Result<BakedAnimation> baked = BakeClip(rig.mesh, rig.model, clip, PlaybackOptions{}, options);
  ASSERT_TRUE(baked.ok()) << baked.error();
  const BakedAnimation& bake = baked.value();
  EXPECT_EQ(calls, 21u);
  ASSERT_EQ(bake.KeyCount(), 21u);
  const std::size_t render = rig.mesh.positions.size();
  ASSERT_EQ(bake.vertex_count, render);
  ASSERT_EQ(bake.positions.size(), 21u * render);
  ASSERT_EQ(bake.normals.size(), bake.positions.size());
  ASSERT_EQ(bake.spines.size(), 1u);
  const PartModel& beam = rig.model.parts[0];
  const std::size_t samples = beam.spine_points.size();
  const double l = beam.spine_length, ei = beam.spine_stiffness.bending;
  const Vec3 binormal = beam.spine_frames.back().binormal;
  for (std::size_t k = 0; k < bake.KeyCount(); ++k) {
    const double force = 0.05 * bake.times[k] / 2.0;  // N, along the local y (binormal)
    const double deflection = force * l * l * l / (3.0 * ei);
    const Vec3 tip = bake.spines[0].points[k * samples + samples - 1];
    EXPECT_NEAR((tip - beam.spine_points.back()).dot(binormal), deflection,
                1e-9 + 1e-9 * deflection)
        << "key " << k;
    // The mesh's largest displacement is the tip's, give or take the top cap turning with
    // the end slope.
    double largest = 0.0;
    for (std::size_t v = 0; v < render; ++v)
      largest = std::max(
          largest,
          double((bake.positions[k * render + v] - rig.mesh.positions[v].cast<float>()).norm()));
    EXPECT_NEAR(largest, deflection, 0.25 * deflection + 1e-6) << "key " << k;
  }
  // Frames as rotations: the third column is the spine's tangent.
  for (std::size_t s = 0; s < samples; ++s)
    EXPECT_LE(
        (bake.spines[0].rest_rotations[s] * Vec3::UnitZ() - beam.spine_frames[s].tangent).norm(),
        1e-12);
}

TEST(Bake, RefusesBadFrameRatesAndForeignMeshes) {
  const testing::TestRig& rig = Beam();
  const Clip clip = TipLoadClip(1.0);
  BakeOptions options;
  options.fps = 0.0;
  EXPECT_EQ(BakeClip(rig.mesh, rig.model, clip, {}, options).error(),
            "fps: must be in [1, 1000] keys per second");
  Mesh other = MakeCylinder(0.1, 1.0, 8, 2);
  EXPECT_EQ(BakeClip(other, rig.model, clip, {}).error(),
            "mesh: is not the mesh the rig model was built on (vertex counts differ)");
}

TEST(Bake, KeyCountMatchesTheKeyTimes) {
  for (const auto& [duration, fps] : {std::pair{1.0, 4.0},
                                      {0.6, 4.0},
                                      {10.0, 30.0},
                                      {2.05, 7.0},
                                      {1.0 / 3.0, 3.0},
                                      {0.001, 1.0}}) {
    SCOPED_TRACE(::testing::Message() << duration << " s at " << fps);
    EXPECT_EQ(BakeKeyCount(duration, fps), double(BakeKeyTimes(duration, fps).size()));
  }
  EXPECT_EQ(BakeKeyCount(1e5, 1000.0), 1e8 + 1.0);
}

TEST(Bake, EstimateCountsFloatVerticesAndSpineFrames) {
  const testing::TestRig& rig = Beam();
  BakeOptions options;
  const double v = double(rig.mesh.positions.size());
  const double s = double(rig.model.parts[0].spine_points.size());
  EXPECT_EQ(EstimateBakeBytes(rig.mesh, rig.model, 10.0, options),
            10.0 * (24.0 * v + (sizeof(Vec3) + sizeof(Quat)) * s + 8.0));
  options.normals = false;
  EXPECT_EQ(EstimateBakeBytes(rig.mesh, rig.model, 10.0, options),
            10.0 * (12.0 * v + (sizeof(Vec3) + sizeof(Quat)) * s + 8.0));
}

// A clip of 1e5 s threw std::bad_alloc from BakeClip: it is refused with its numbers first.
TEST(Bake, RefusesAClipTooLargeToHoldBeforeAllocating) {
  const testing::TestRig& rig = Beam();
  const Clip clip = TipLoadClip(1e5);
  BakeOptions options;
  options.fps = 1000.0;
  Result<BakedAnimation> baked(Error{""});
  ASSERT_NO_THROW(baked = BakeClip(rig.mesh, rig.model, clip, {}, options));
  ASSERT_FALSE(baked.ok());
  const std::string& error = baked.error();
  EXPECT_EQ(error.rfind("the bake would hold 100000001 keys (100000 s at 1000 keys/s) x " +
                            std::to_string(rig.mesh.positions.size()) + " vertices = ",
                        0),
            0u)
      << error;
  EXPECT_NE(error.find("more than the 4.29 GB a bake may take"), std::string::npos) << error;
  // The limit is the option's: a 1 s clip at 10 keys/s over a 1 kB limit.
  options.fps = 10.0;
  options.max_bytes = 1000.0;
  const std::string small = BakeClip(rig.mesh, rig.model, TipLoadClip(1.0), {}, options).error();
  EXPECT_NE(small.find("11 keys (1 s at 10 keys/s)"), std::string::npos) << small;
  EXPECT_NE(small.find("more than the 1e-06 GB"), std::string::npos) << small;
  options.max_bytes = EstimateBakeBytes(rig.mesh, rig.model, 11.0, options);
  EXPECT_TRUE(BakeClip(rig.mesh, rig.model, TipLoadClip(1.0), {}, options).ok());
}

// A load far too large for the stiffness went out silently: the bake warns about the part, at
// its worst key; a mild load warns about nothing.
TEST(Bake, WarnsWhenADeflectionExceedsThePartsLength) {
  const testing::TestRig& rig = Beam();
  const PartModel& beam = rig.model.parts[0];
  const double l = beam.spine_length, ei = beam.spine_stiffness.bending;
  RawClip raw;
  raw.name = "crush";
  raw.duration = 1.0;
  RawPartTracks part;
  part.part = "beam";
  PointLoadChannels<RawTrack> load;
  load.at.keys = {{0.0, 1.0, Interpolation::kStep}};
  // Tip deflection F L^3 / 3EI grows linearly to 5 L at t = 1.
  load.magnitude.keys = {{0.0, 0.0, Interpolation::kLinear},
                         {1.0, 5.0 * l * 3.0 * ei / (l * l * l), Interpolation::kLinear}};
  load.direction.keys = {{0.0, Vec3(0, 1, 0), Interpolation::kStep}};
  part.channels.point_loads.push_back(load);
  raw.parts.push_back(part);
  BakeOptions options;
  options.fps = 4.0;
  Result<BakedAnimation> baked =
      BakeClip(rig.mesh, rig.model, BuildClip(raw, rig.model).value(), {}, options);
  ASSERT_TRUE(baked.ok()) << baked.error();
  ASSERT_EQ(baked.value().warnings.size(), 1u);
  const std::string& warning = baked.value().warnings[0];
  EXPECT_EQ(warning.rfind("part \"beam\": its deflection reached ", 0), 0u) << warning;
  EXPECT_NE(warning.find("at t = 1 s: linear beam theory no longer holds"), std::string::npos)
      << warning;
  Result<BakedAnimation> mild = BakeClip(rig.mesh, rig.model, TipLoadClip(1.0), {}, options);
  ASSERT_TRUE(mild.ok()) << mild.error();
  EXPECT_TRUE(mild.value().warnings.empty());
  // The message itself: ratio, deflection and length.
  PartWarnings w;
  w.max_deflection_ratio = 1.5;
  EXPECT_NE(DeflectionWarning(beam, w, 0.25).find("(1.5 x its length"), std::string::npos);
  w.max_deflection_ratio = 0.9;
  EXPECT_EQ(DeflectionWarning(beam, w, 0.25), "");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
