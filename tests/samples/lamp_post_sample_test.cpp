// samples/lamp_post (paper Fig. 8): the four groups of profile-wire deformation, one per second:
// the whole length of all profile wires (t = 1), a part of all (t = 2), the whole length of some
// (t = 3) and a part of some (t = 4). Each loaded stretch is a clamped-clamped wire under a
// uniform line load q, so its points move by the textbook curve, written out here,
//   X(v) = q L^4 v^2 (1 - v)^2 / (24 EI),  peak q L^4 / (384 EI) at v = 1/2,
// with L the stretch's arc length (measured here on the rest profile) and EI the profile wire's
// stiffness; everything away from the loaded profiles stays where it was.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "sample_test_support.h"

namespace wirerig::samples {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr const char* kScene = "lamp_post/lamp_post.scene.json";
// The scene's loads (world -X, N/m) and the profiles of the "some" groups.
constexpr double kWholeLoad = 3000.0, kPartLoad = 24000.0;
const std::set<std::uint32_t> kSome = {9, 10, 11};

struct Group {
  double time;
  bool all;
  double from, to, q;
};

const Group kGroups[] = {{1.0, true, 0.0, 1.0, kWholeLoad},
                         {2.0, true, 0.25, 0.75, kPartLoad},
                         {3.0, false, 0.0, 1.0, kWholeLoad},
                         {4.0, false, 0.25, 0.75, kPartLoad}};

TEST(LampPostSample, LoadedStretchesBendAsClampedWires) {
  std::unique_ptr<PlayedScene> played = PlaySample(kScene);
  ASSERT_NE(played, nullptr);
  const std::size_t post = played->Part("post");
  const PartModel& model = played->scene.model.parts[post];
  ASSERT_EQ(model.profiles.size(), 20u);
  // The profile wires' stiffness: an aluminium strip, b = 0.1 m, h = 0.004 m, bending modulus
  // E / (1 - nu^2).
  const double ei = 69.0e9 / (1.0 - 0.33 * 0.33) * 0.1 * std::pow(0.004, 3) / 12.0;
  played->Evaluate(0.0);  // no load: the rest profiles
  const std::vector<std::vector<Vec3>> rest = played->playback->workspace().profile_points[post];
  for (const Group& g : kGroups) {
    SCOPED_TRACE("t = " + std::to_string(g.time));
    played->Evaluate(g.time);
    const auto& points = played->playback->workspace().profile_points[post];
    int peaks = 0;
    for (std::uint32_t p = 0; p < model.profiles.size(); ++p) {
      const ProfileModel& profile = model.profiles[p];
      ASSERT_NEAR(profile.stiffness.bending, ei, 1e-9 * ei);
      const bool loaded = g.all || kSome.count(p) > 0;
      const double length = StretchLength(profile, g.from, g.to);
      const double peak = g.q * std::pow(length, 4) / (384.0 * ei);
      const std::size_t m = profile.local_points.size();
      for (std::size_t q = 0; q < m; ++q) {
        const Vec3 moved = points[p][q] - rest[p][q];
        const double u = double(q) / double(m);
        double expected = 0.0;
        if (loaded && u >= g.from && u <= g.to) {
          const double v = (u - g.from) / (g.to - g.from);
          expected = g.q * std::pow(length, 4) * v * v * (1 - v) * (1 - v) / (24.0 * ei);
        }
        // The load is along world -X; the rest spine frame carries it there.
        EXPECT_NEAR(-moved.x(), expected, 1e-6 * peak) << "profile " << p << " point " << q;
        EXPECT_LT(std::abs(moved.y()) + std::abs(moved.z()), 1e-6 * peak);
        if (loaded && std::abs(u - 0.5 * (g.from + g.to)) < 1e-12) {
          EXPECT_NEAR(-moved.x(), peak, 1e-6 * peak);  // the midpoint: q L^4 / 384 EI
          ++peaks;
        }
      }
    }
    EXPECT_EQ(peaks, g.all ? 20 : 3);
    EXPECT_FALSE(played->warnings[post].any());
  }
}

TEST(LampPostSample, VerticesAwayFromTheLoadedProfilesStayPut) {
  std::unique_ptr<PlayedScene> played = PlaySample(kScene);
  ASSERT_NE(played, nullptr);
  const std::size_t post = played->Part("post");
  played->Evaluate(0.0);
  const std::vector<Vec3> rest = played->positions;
  for (const double t : {3.0, 4.0}) {  // the "some" groups: profiles 9, 10 and 11
    played->Evaluate(t);
    std::size_t near = 0, far = 0, moved_near = 0;
    for (std::size_t v = 0; v < rest.size(); ++v) {
      const VertexAttachment& a = played->scene.model.vertices[v];
      const bool touches = a.part == post && (kSome.count(a.profile) > 0 ||
                                              (!a.cap && kSome.count(a.profile + 1) > 0));
      const double moved = (played->positions[v] - rest[v]).norm();
      if (touches) {
        ++near;
        moved_near += moved > 1e-6 ? 1 : 0;
      } else {
        ++far;
        EXPECT_LT(moved, 1e-12) << "vertex " << v << " at t = " << t;
      }
    }
    EXPECT_GT(far, near);
    EXPECT_GT(moved_near, 0u);
  }
}

TEST(LampPostSample, RefusesAProfileThePostDoesNotHave) {
  nlohmann::json scene = ReadJson(SampleScenePath(kScene));
  scene["clips"][0]["profiles"][2]["profiles"] = {9, 10, 99};
  const std::string error = SceneError(scene);
  EXPECT_NE(error.find("/clips/0"), std::string::npos) << error;
  EXPECT_NE(error.find("profile"), std::string::npos) << error;
  scene = ReadJson(SampleScenePath(kScene));
  scene["clips"][0]["profiles"][1]["from"] = 0.8;  // from > to
  EXPECT_NE(SceneError(scene).find("profiles[1].from: the stretch must satisfy"), std::string::npos)
      << SceneError(scene);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::samples
