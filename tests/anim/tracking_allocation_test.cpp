// Proves that keyed poses played through the articulated dynamics (ArticulatedTracking::Apply:
// the clip sampled, forces, torques and gravity, fixed steps, scrubbing back to a cached state)
// never allocate once the tracking is made: global operator new is replaced by one that counts,
// so this is a binary of its own.
#include <gtest/gtest.h>

#include <vector>

#include <nlohmann/json.hpp>

#include "wirerig/anim/articulated_tracking.h"
#include "wirerig/anim/scene.h"

#include "support/counting_allocator.h"

using wirerig::testing::g_allocations;

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(TrackingNoAllocation, CountingAllocatorSeesAllocations) {
  EXPECT_GE(testing::CountedAllocationsOfAHeapVector(), 2);
}

TEST(TrackingNoAllocation, StepsAndScrubsWithKeysForcesTorquesAndGravity) {
  // A capsule as three parts: a ball-jointed middle (limited), a hinged end; keyed angles on
  // both, a keyed force and torque on the end, gravity.
  const nlohmann::json document = nlohmann::json::parse(R"({
    "format": "wirerig.scene", "version": 1, "name": "arm",
    "mesh": {"procedural": "capsule", "parameters": {"radius": 0.05, "height": 1.5}},
    "rig": {"description": {"parts": [
      {"name": "top", "central_curve": [[0, 1.52, 0], [0, 1.0, 0]], "profile_count": 6},
      {"name": "middle", "parent": "top", "central_curve": [[0, 1.0, 0], [0, 0.5, 0]],
       "profile_count": 6, "joint": {"type": "ball", "limits": {"x": [-40, 40]}}},
      {"name": "end", "parent": "middle", "central_curve": [[0, 0.5, 0], [0, -0.02, 0]],
       "profile_count": 6, "joint": {"type": "hinge", "axis": [1, 0, 0]}}]}},
    "default_kind": "rigid",
    "playback": {"tracking": {"frequency": 3, "damping_ratio": 0.5, "gravity": [0, -9.81, 0]}},
    "clips": [{"name": "swing", "duration": 2, "parts": [
      {"part": "middle", "joint_angles": {"keys": [[0, [0, 0, 0]], [1, [30, 10, 0]],
                                                   [2, [-20, 0, 5]]]}},
      {"part": "end", "joint_angles": {"keys": [[0, [0, 0, 0]], [1.5, [60, 0, 0]]]},
       "rigid_forces": [{"at": [0, 0, 0], "force": {"keys": [[0, [0, 0, 2]], [2, [1, 0, 0]]]}}],
       "rigid_torque": {"keys": [[0, [0.5, 0, 0]], [2, [0, 0, 0]]]}}]}]
  })");
  Result<SceneDescription> description = ParseScene(document, ".");
  ASSERT_TRUE(description.ok()) << description.error();
  Result<BuiltScene> built = BuildScene(description.value());
  ASSERT_TRUE(built.ok()) << built.error();
  const BuiltScene& scene = built.value();
  Result<ArticulatedTracking> made =
      ArticulatedTracking::Make(scene.model, scene.clips[0], scene.description.playback.tracking);
  ASSERT_TRUE(made.ok()) << made.error();
  ArticulatedTracking tracking = std::move(made).value();
  std::vector<PartPose> poses(scene.model.parts.size());
  const long before = g_allocations;
  for (double t : {0.3, 1.1, 1.9, 0.2, 1.7, 0.0, 2.0}) {  // forward, then back to checkpoints
    ASSERT_TRUE(tracking.Apply(t, poses).ok());
  }
  EXPECT_EQ(g_allocations - before, 0);
  EXPECT_GT(tracking.JointAngles(2).x(), 20.0);  // the end did swing toward its keys
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
