// The runtime clip asset (.wclip) made from offline playback: replayed with the runtime alone it
// gives the playback's frames; between frames it interpolates; bad bytes are refused.
#include "wirerig/anim/clip_asset_export.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <limits>
#include <map>
#include <random>

#include "wirerig/anim/scene.h"
#include "wirerig/runtime/rig_asset.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

const BuiltScene& SceneNamed(const std::string& relative) {
  static std::map<std::string, BuiltScene> scenes;
  auto it = scenes.find(relative);
  if (it == scenes.end()) {
    Result<BuiltScene> built = LoadAndBuildScene(std::string(WIRERIG_SAMPLES_DIR) + "/" + relative);
    EXPECT_TRUE(built.ok()) << built.error();
    it = scenes.emplace(relative, std::move(built).value()).first;
  }
  return it->second;
}

// Positions through the runtime only: SampleClipJob, then EvaluateRigJob.
std::vector<Vec3> Replay(const RigModel& model, const SampledClip& clip, double t) {
  ClipPlaybackBuffers buffers = MakeClipPlaybackBuffers(clip);
  SampleClipJob sample{&clip, t, &buffers};
  const Status sampled = sample.Run();
  EXPECT_TRUE(sampled.ok()) << ToString(sampled);
  RigWorkspace workspace = MakeRigWorkspace(model);
  std::vector<Vec3> positions(model.vertices.size());
  EvaluateRigJob job;
  job.model = &model;
  job.poses = buffers.poses;
  job.profile_loads = buffers.used_profile_loads();
  job.workspace = &workspace;
  job.positions = positions;
  const Status run = job.Run();
  EXPECT_TRUE(run.ok()) << ToString(run);
  return positions;
}

double LargestGap(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double gap = 0.0;
  for (std::size_t v = 0; v < a.size(); ++v) gap = std::max(gap, (a[v] - b[v]).norm());
  return gap;
}

class ClipAssetReplay : public ::testing::TestWithParam<const char*> {};

// Keyed forces with boundary switches (octopus), profile loads (human_sex), keyed poses through
// articulated dynamics (walk): at the frame times the runtime replay matches the offline
// playback to round-off; halfway between frames it stays within the motion of one frame.
TEST_P(ClipAssetReplay, MatchesOfflinePlayback) {
  const BuiltScene& scene = SceneNamed(GetParam());
  const Clip& clip = scene.clips.front();
  constexpr double kFps = 30.0;
  Result<SampledClip> sampled =
      SampleClipForRuntime(scene.model, clip, scene.description.playback, kFps);
  ASSERT_TRUE(sampled.ok()) << sampled.error();
  const SampledClip& asset = sampled.value();
  EXPECT_EQ(asset.frame_count(), std::size_t(std::ceil(clip.duration * kFps - 1e-9)) + 1);

  // The playback as the scene sets it up, wire dynamics included (the octopus's arms).
  Result<Playback> playback = Playback::Make(scene.model, clip, scene.description.playback);
  ASSERT_TRUE(playback.ok()) << playback.error();
  std::vector<Vec3> offline(scene.model.vertices.size());
  const std::size_t last = asset.frame_count() - 1;
  double worst_on_frames = 0.0, worst_between = 0.0, worst_frame_motion = 0.0;
  for (std::size_t k : {std::size_t(1), last / 3, last / 2, last - 1}) {
    const double t = double(k) / kFps;
    ASSERT_TRUE(playback.value().Evaluate(t, offline, {}).ok());
    worst_on_frames = std::max(worst_on_frames, LargestGap(Replay(scene.model, asset, t), offline));
    // Halfway to the next frame, against the playback there and the motion of that frame.
    const std::vector<Vec3> next = Replay(scene.model, asset, t + 1.0 / kFps);
    ASSERT_TRUE(playback.value().Evaluate(t + 0.5 / kFps, offline, {}).ok());
    worst_between =
        std::max(worst_between, LargestGap(Replay(scene.model, asset, t + 0.5 / kFps), offline));
    worst_frame_motion =
        std::max(worst_frame_motion, LargestGap(Replay(scene.model, asset, t), next));
  }
  RecordProperty("worst_between_frames_m", std::to_string(worst_between));
  EXPECT_GT(worst_frame_motion, 1e-4) << "the sampled frames should move";
  EXPECT_LT(worst_on_frames, 1e-9);
  EXPECT_LE(worst_between, std::max(0.5 * worst_frame_motion, 1e-9));

  // Through the file format: the same clip back, bit for bit.
  const std::vector<std::uint8_t> bytes = SerializeClipAsset(asset);
  SampledClip loaded;
  const Status parsed = ParseClipAsset(bytes, &loaded);
  ASSERT_TRUE(parsed.ok()) << ToString(parsed);
  EXPECT_EQ(SerializeClipAsset(loaded), bytes);
  EXPECT_TRUE(ValidateSampledClip(loaded, &scene.model).ok());
}

// The octopus's arms swing with inertia (playback.wires): the asset records each arm's motion
// beyond its static shape, and without that record the replay would miss the offline frames by
// centimetres.
TEST(ClipAsset, CarriesTheWiresMotion) {
  const BuiltScene& scene = SceneNamed("octopus/octopus.scene.json");
  ASSERT_GT(scene.description.playback.wires.modes, 0);
  const Clip& clip = scene.clips.front();
  Result<SampledClip> sampled =
      SampleClipForRuntime(scene.model, clip, scene.description.playback, 30.0);
  ASSERT_TRUE(sampled.ok()) << sampled.error();
  const SampledClip& asset = sampled.value();
  std::size_t deformable = 0;
  for (const PartModel& part : scene.model.parts)
    deformable += part.kind == SpineKind::kDeformable ? 1 : 0;
  ASSERT_EQ(asset.wires.size(), deformable);
  for (const ClipWire& wire : asset.wires) {
    EXPECT_EQ(wire.modes, std::uint32_t(scene.description.playback.wires.modes));
    EXPECT_EQ(wire.samples, scene.model.parts[wire.part].spine_points.size());
  }
  EXPECT_EQ(asset.wire_motion.size(), asset.frame_count() * asset.wire_motion_stride());

  SampledClip static_wires = asset;
  static_wires.wires.clear();
  static_wires.wire_motion.clear();
  Result<Playback> playback = Playback::Make(scene.model, clip, scene.description.playback);
  ASSERT_TRUE(playback.ok()) << playback.error();
  std::vector<Vec3> offline(scene.model.vertices.size());
  double with = 0.0, without = 0.0;
  for (const double t : {2.0, 4.5, 7.0}) {
    ASSERT_TRUE(playback.value().Evaluate(t, offline, {}).ok());
    with = std::max(with, LargestGap(Replay(scene.model, asset, t), offline));
    without = std::max(without, LargestGap(Replay(scene.model, static_wires, t), offline));
  }
  std::printf(
      "[measure] .wclip replay of the octopus against offline playback: %.1e m with the "
      "wires' motion, %.3f m without\n",
      with, without);
  EXPECT_LT(with, 1e-9);
  EXPECT_GT(without, 0.01);
}

// The walk's flesh jiggles (playback.profile_wires): the asset records every loop's motion
// beyond rest, and the runtime replays it to round-off; without that record the replay would
// miss the offline frames by the flesh's motion.
TEST(ClipAsset, CarriesTheProfileWiresMotion) {
  const BuiltScene& scene = SceneNamed("walk/walk.scene.json");
  const ProfileWireOptions& options = scene.description.playback.profile_wires;
  ASSERT_GT(options.modes, 0);
  const Clip& clip = scene.clips.front();
  Result<SampledClip> sampled =
      SampleClipForRuntime(scene.model, clip, scene.description.playback, 30.0);
  ASSERT_TRUE(sampled.ok()) << sampled.error();
  const SampledClip& asset = sampled.value();
  std::size_t loops = 0;
  for (const std::string& name : options.parts)
    for (const PartModel& part : scene.model.parts)
      if (part.name == name) loops += part.profiles.size();
  ASSERT_EQ(asset.profile_wires.size(), loops);
  for (const ClipProfileWire& wire : asset.profile_wires) {
    EXPECT_EQ(wire.modes, std::uint32_t(options.modes));
    EXPECT_EQ(wire.weights.size(),
              scene.model.parts[wire.part].profiles[wire.profile].local_points.size());
  }
  EXPECT_EQ(asset.profile_wire_motion.size(),
            asset.frame_count() * asset.profile_wire_motion_stride());

  SampledClip static_skin = asset;
  static_skin.profile_wires.clear();
  static_skin.profile_wire_motion.clear();
  Result<Playback> playback = Playback::Make(scene.model, clip, scene.description.playback);
  ASSERT_TRUE(playback.ok()) << playback.error();
  std::vector<Vec3> offline(scene.model.vertices.size());
  double with = 0.0, without = 0.0;
  for (const double t : {1.0, 1.5, 4.0, 7.5}) {
    ASSERT_TRUE(playback.value().Evaluate(t, offline, {}).ok());
    with = std::max(with, LargestGap(Replay(scene.model, asset, t), offline));
    without = std::max(without, LargestGap(Replay(scene.model, static_skin, t), offline));
  }
  std::printf(
      "[measure] .wclip replay of the walk against offline playback: %.1e m with the profile "
      "wires' motion, %.4f m without\n",
      with, without);
  EXPECT_LT(with, 1e-9);
  EXPECT_GT(without, 0.002);
}

INSTANTIATE_TEST_SUITE_P(Samples, ClipAssetReplay,
                         ::testing::Values("octopus/octopus.scene.json",
                                           "human/human_sex.scene.json", "walk/walk.scene.json"));

SampledClip OctopusClip() {
  const BuiltScene& scene = SceneNamed("octopus/octopus.scene.json");
  Result<SampledClip> sampled =
      SampleClipForRuntime(scene.model, scene.clips.front(), scene.description.playback, 10.0);
  EXPECT_TRUE(sampled.ok()) << sampled.error();
  return std::move(sampled).value();
}

std::string Refusal(const std::vector<std::uint8_t>& bytes) {
  SampledClip out;
  const Status status = ParseClipAsset(bytes, &out);
  EXPECT_FALSE(status.ok());
  EXPECT_TRUE(out.parts.empty());
  return ToString(status);
}

// A 1e5 s clip at 30 frames/s (3,000,001 frames, each a full evaluation) ran for minutes
// toward a 0.7 GB asset: refused at once, with the numbers.
TEST(ClipAsset, RefusesMoreFramesThanAnAssetMayHoldBeforeAnyWork) {
  const BuiltScene& scene = SceneNamed("octopus/octopus.scene.json");
  Clip clip = scene.clips.front();
  clip.duration = 1e5;
  const auto start = std::chrono::steady_clock::now();
  const Result<SampledClip> sampled =
      SampleClipForRuntime(scene.model, clip, scene.description.playback, 30.0);
  ASSERT_FALSE(sampled.ok());
  EXPECT_EQ(sampled.error(), "clip \"" + clip.name +
                                 "\": 3000001 frames (100000 s at 30 frames/s), more than a clip "
                                 "asset may hold (1000000); sample fewer frames per second or a "
                                 "shorter clip");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(ClipAsset, RefusesBadClipsNamingTheField) {
  const SampledClip good = OctopusClip();
  std::vector<std::uint8_t> bytes = SerializeClipAsset(good);
  bytes[1] = 'X';
  EXPECT_NE(Refusal(bytes).find("clip asset"), std::string::npos);
  SampledClip bad = good;
  bad.parts[7].rotation = Quat(2.0, 0.0, 0.0, 0.0);
  EXPECT_EQ(Refusal(SerializeClipAsset(bad)), "parts[7].rotation: must be a unit quaternion");
  bad = good;
  bad.parts[3].line_loads = {std::uint32_t(good.line_loads.size()), 1};
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("parts[3].loads"), std::string::npos);
  bad = good;
  bad.parts[2].boundary = static_cast<BoundaryCondition>(4);  // no such family
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("parts[2]"), std::string::npos);
  bad = good;
  bad.parts.pop_back();
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("one key per part per frame"), std::string::npos);
  ASSERT_FALSE(good.wires.empty());
  bad = good;
  bad.wires[0].modes = 0;
  EXPECT_EQ(Refusal(SerializeClipAsset(bad)), "wires[0].modes: must lie in [1, 32]");
  bad = good;
  bad.wires[1].part = bad.wires[0].part;
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("wires[1].part"), std::string::npos);
  bad = good;
  bad.wires[0].length = -1.0;
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("wires[0]"), std::string::npos);
  bad = good;
  bad.wire_motion.pop_back();
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("wire_motion"), std::string::npos);
  bad = good;
  bad.wire_motion[5].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("wire_motion[5]"), std::string::npos);
  ASSERT_FALSE(good.profile_wires.empty());  // the mantle's flesh
  bad = good;
  bad.profile_wires[0].weights[3] = 1.5;
  EXPECT_EQ(Refusal(SerializeClipAsset(bad)), "profile_wires[0].weights: must lie in [0, 1]");
  bad = good;
  bad.profile_wires[1].profile = bad.profile_wires[0].profile;
  bad.profile_wires[1].part = bad.profile_wires[0].part;
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("profile_wires[1].profile"), std::string::npos);
  bad = good;
  bad.profile_wires[0].reach = 0.0;
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("profile_wires[0]"), std::string::npos);
  bad = good;
  bad.profile_wire_motion.pop_back();
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("profile_wire_motion"), std::string::npos);
  bad = good;
  bad.profile_wire_motion[2].x() = std::numeric_limits<double>::infinity();
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("profile_wire_motion[2]"), std::string::npos);
  bad = good;
  bad.profile_wires[0].weights.push_back(0.5);  // one point more than the profile has
  EXPECT_NE(ToString(ValidateSampledClip(bad, &SceneNamed("octopus/octopus.scene.json").model))
                .find("profile_wires[0].profile"),
            std::string::npos);
  // Against the rig: a wire's samples must be its part's.
  bad = good;
  bad.wires[0].samples += 1;
  bad.wire_motion = good.wire_motion;
  EXPECT_NE(ToString(ValidateSampledClip(bad, &SceneNamed("octopus/octopus.scene.json").model))
                .find("wires[0].part"),
            std::string::npos);
  bad = good;
  bad.duration = 0.0;
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("duration"), std::string::npos);
  bad = good;
  ASSERT_FALSE(bad.line_loads.empty());  // the octopus's arms are driven by line loads
  bad.line_loads.front().from = 1.5;
  EXPECT_NE(Refusal(SerializeClipAsset(bad)).find("line_loads"), std::string::npos);
  // A clip for another rig.
  const BuiltScene& human = SceneNamed("human/human_sex.scene.json");
  EXPECT_FALSE(ValidateSampledClip(good, &human.model).ok());
}

// Counts that multiply: 65,536 parts and one part key carrying 65,536 axial loads would need
// 2^32 playback slots (a 32-bit product wrapped to 0 before, and the buffers were written past
// their end), and a profile wire named twice among many is found. Refused at load, naming
// the field, before any buffer is made.
TEST(ClipAsset, RefusesPlaybackBuffersThatCountsMultiplyPastTheLimit) {
  SampledClip clip;
  clip.duration = 1.0;
  clip.frame_rate = 1.0;
  clip.part_count = 65536;
  clip.profile_keys_of_frame = {LoadRange{}};
  clip.parts.resize(clip.part_count);
  clip.axial_point_loads.assign(65536, AxialPointLoad{0.5, 1.0});
  clip.parts[0].axial_point_loads = {0, 65536};
  const Status refused = ValidateSampledClip(clip);
  EXPECT_EQ(std::string(refused.field), "axial_point_loads") << ToString(refused);
  // One load fewer per part and 64 parts: within the limit, and the buffers hold every load.
  clip.part_count = 64;
  clip.parts.resize(64);
  ASSERT_TRUE(ValidateSampledClip(clip).ok()) << ToString(ValidateSampledClip(clip));
  EXPECT_EQ(MakeClipPlaybackBuffers(clip).axial_point_loads.size(), 64u * 65536u);

  clip.profile_wire_motion.clear();
  for (std::uint32_t i = 0; i < 2000; ++i) {
    ClipProfileWire wire;
    wire.part = 0;
    wire.profile = i == 1999 ? 7 : i;  // the last names profile 7 again
    wire.modes = 1;
    wire.weights = {0.5, 0.5};
    wire.length = 1.0;
    wire.bending_stiffness = 1.0;
    wire.reach = 1.0;
    clip.profile_wires.push_back(wire);
  }
  clip.profile_wire_motion.assign(clip.profile_wire_motion_stride(), Vec3::Zero());
  const Status twice = ValidateSampledClip(clip);
  EXPECT_EQ(ToString(twice),
            "profile_wires[1999].profile: must name a profile no other profile wire does");
}

TEST(ClipAsset, SampleJobRefusesBuffersOfAnotherClip) {
  const SampledClip clip = OctopusClip();
  SampledClip other = clip;
  other.part_count = 1;
  ClipPlaybackBuffers wrong = MakeClipPlaybackBuffers(other);
  EXPECT_FALSE((SampleClipJob{&clip, 1.0, &wrong}.Run().ok()));
  SampledClip without_wires = clip;
  without_wires.wires.clear();
  without_wires.wire_motion.clear();
  ClipPlaybackBuffers no_wires = MakeClipPlaybackBuffers(without_wires);
  EXPECT_EQ(ToString(SampleClipJob{&clip, 1.0, &no_wires}.Run()),
            "buffers: were made for another clip");
  SampledClip without_profile_wires = clip;
  without_profile_wires.profile_wires.clear();
  without_profile_wires.profile_wire_motion.clear();
  ClipPlaybackBuffers no_profile_wires = MakeClipPlaybackBuffers(without_profile_wires);
  EXPECT_EQ(ToString(SampleClipJob{&clip, 1.0, &no_profile_wires}.Run()),
            "buffers: were made for another clip");
  ClipPlaybackBuffers right = MakeClipPlaybackBuffers(clip);
  EXPECT_FALSE((SampleClipJob{&clip, std::nan(""), &right}.Run().ok()));
  EXPECT_TRUE((SampleClipJob{&clip, -3.0, &right}.Run().ok()));  // before the start: frame 0
}

// Corruptions that keep a valid checksum: refused or played without a crash.
TEST(ClipAsset, CorruptPayloadsNeverCrash) {
  const SampledClip clip = OctopusClip();
  const std::vector<std::uint8_t> good = SerializeClipAsset(clip);
  std::mt19937 random(7);
  std::uniform_int_distribution<std::size_t> where(20, good.size() - 1);
  std::uniform_int_distribution<int> value(0, 255);
  for (int trial = 0; trial < 1000; ++trial) {
    std::vector<std::uint8_t> bytes = good;
    for (int k = 0; k < 4; ++k) bytes[where(random)] = std::uint8_t(value(random));
    const std::uint32_t crc = Crc32(std::span(bytes).subspan(20));
    for (int i = 0; i < 4; ++i) bytes[16 + std::size_t(i)] = std::uint8_t(crc >> (8 * i));
    SampledClip parsed;
    if (!ParseClipAsset(bytes, &parsed).ok()) continue;
    ClipPlaybackBuffers buffers = MakeClipPlaybackBuffers(parsed);
    for (double t : {0.0, 0.37, 2.5, 1e3}) (void)SampleClipJob{&parsed, t, &buffers}.Run();
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
