// SceneFrame colours a cantilever's skin by the bending moment of its spine: under a tip load F
// the moment at distance s from the root is F (L - s), largest at the root, zero at the tip.
#include "wirerig/viewer/scene_frame.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(SceneFrame, BendingMomentColoursFollowFTimesTheLeverArm) {
  const nlohmann::json document = nlohmann::json::parse(R"({
    "format": "wirerig.scene", "version": 1, "name": "cantilever",
    "mesh": {"procedural": "cylinder", "parameters": {"radius": 0.05, "height": 1.0}},
    "rig": {"description": {"parts": [{"name": "beam", "central_curve": [[0, 0, 0], [0, 1, 0]],
                                       "profile_count": 20, "points_per_profile": 16}]}},
    "parts": {"beam": {"spine": {"material": "steel", "section": {"tube": {"r": 0.05, "h": 0.005}}}}},
    "clips": [{"name": "push", "duration": 1, "parts": [
      {"part": "beam", "point_loads": [{"at": 1, "magnitude": 50, "direction": [1, 0, 0],
                                        "axes": "world"}]}]}]
  })");
  const BuiltScene scene = BuildScene(ParseScene(document, ".").value()).value();
  Playback playback = Playback::Make(scene.model, scene.clips[0]).value();
  std::vector<Vec3> positions(scene.model.vertices.size()), normals(positions.size());
  ASSERT_TRUE(playback.Evaluate(0.5, positions, normals).ok());
  SceneFrame picture(scene);
  picture.set_coloring(SceneColoring::kBendingMoment);
  picture.Update(playback, positions, normals);
  const RenderFrame frame = picture.frame();
  ASSERT_EQ(frame.meshes.size(), 1u);
  const std::span<const float> moments = frame.meshes[0].scalars;
  ASSERT_EQ(moments.size(), positions.size());
  const PartModel& beam = scene.model.parts[0];
  const double force = 50.0, length = beam.spine_length;
  const double root_y = beam.spine_points.front().y();
  int checked = 0;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const double s = scene.mesh.welded_positions[v].y() - root_y;
    if (s < 0.2 * length || s > 0.8 * length) continue;  // away from the ends
    // The vertex reads the spine sample nearest its profile pair: within one profile spacing.
    const double spacing = length / 20.0;
    EXPECT_NEAR(moments[v], force * (length - s), force * spacing + 0.03 * force * length)
        << "s = " << s;
    ++checked;
  }
  EXPECT_GT(checked, 100);
  EXPECT_EQ(frame.legend.map, ColorMap::kViridis);
  EXPECT_GT(frame.legend.max, 0.7 * force * length);
  // Base colour again: no scalars.
  picture.set_coloring(SceneColoring::kBaseColor);
  picture.Update(playback, positions, normals);
  EXPECT_TRUE(picture.frame().meshes[0].scalars.empty());
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
