// samples/chair (paper Fig. 10): a chair reshaped by spine and profile wires together. At t = 1
// the four legs splay (cantilevers with a tip force outwards), the back reclines (a cantilever
// under a uniform line load backwards) and a lumbar bulge pushes three of the back's profile
// wires forwards (clamped stretches, uniform load); the seat, the root, carries nothing. Checked
// against textbook curves written out here (x from the clamped root):
//   tip force P:      y = P x^2 (3 L - x) / (6 EI),                tip P L^3 / 3 EI
//   uniform load q:   y = q x^2 (6 L^2 - 4 L x + x^2) / (24 EI),   tip q L^4 / 8 EI
//   clamped stretch:  y = q L^4 v^2 (1 - v)^2 / (24 EI),           peak q L^4 / 384 EI
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sample_test_support.h"

namespace wirerig::samples {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr const char* kScene = "chair/chair.scene.json";
constexpr double kLegEI = 10.0e9 * 1.1e-7;   // wood, the scene's leg section
constexpr double kLegForce = 2500.0;         // N, outwards at each leg's foot
constexpr double kBackEI = 0.05e9 * 4.8e-6;  // rubber, the scene's back section
constexpr double kBackLoad = 2500.0;         // N/m, backwards (-Z) along the back
constexpr double kLumbarLoad = 35.0;         // N/m, forwards (+Z) on back profiles 2, 3, 4

// Largest |measured - formula| over a part's spine samples, the displacement taken along `dir`
// (and nothing across it), with x the rest distance from the spine's root.
template <typename Formula>
double SpineError(const PlayedScene& played, std::size_t part, const Vec3& dir, Formula formula) {
  const RigWorkspace& w = played.playback->workspace();
  const PartModel& model = played.scene.model.parts[part];
  double worst = 0.0;
  for (std::size_t k = 0; k < model.spine_points.size(); ++k) {
    const Vec3 moved = w.spine_points[part][k] - model.spine_points[k];
    const double x = (model.spine_points[k] - model.spine_points.front()).norm();
    worst = std::max(worst, std::abs(moved.dot(dir) - formula(x)));
    worst = std::max(worst, (moved - moved.dot(dir) * dir).norm());
  }
  return worst;
}

double SpineLength(const PartModel& part) {
  return (part.spine_points.back() - part.spine_points.front()).norm();
}

TEST(ChairSample, LegsSplayAndTheBackReclinesByTheCantileverFormulas) {
  std::unique_ptr<PlayedScene> played = PlaySample(kScene);
  ASSERT_NE(played, nullptr);
  played->Evaluate(1.0);
  const RigWorkspace& w = played->playback->workspace();
  const double sx[4] = {1, -1, -1, 1}, sz[4] = {1, 1, -1, -1};
  for (int i = 0; i < 4; ++i) {
    const std::size_t leg = played->Part("leg_" + std::to_string(i));
    const PartModel& model = played->scene.model.parts[leg];
    ASSERT_DOUBLE_EQ(model.spine_stiffness.bending, kLegEI);
    const double length = SpineLength(model);
    const Vec3 out = Vec3(sx[i], 0.0, sz[i]).normalized();
    const double tip = kLegForce * std::pow(length, 3) / (3.0 * kLegEI);
    EXPECT_LT(SpineError(*played, leg, out,
                         [&](double x) {
                           return kLegForce * x * x * (3.0 * length - x) / (6.0 * kLegEI);
                         }),
              1e-6 * tip)
        << model.name;
    const Vec3 foot = w.spine_points[leg].back() - model.spine_points.back();
    EXPECT_NEAR(foot.dot(out), tip, 1e-6 * tip) << model.name;
    EXPECT_FALSE(played->warnings[leg].beyond_small_deflection) << model.name;
  }
  const std::size_t back = played->Part("back");
  const PartModel& model = played->scene.model.parts[back];
  ASSERT_DOUBLE_EQ(model.spine_stiffness.bending, kBackEI);
  const double length = SpineLength(model);
  const double tip = kBackLoad * std::pow(length, 4) / (8.0 * kBackEI);
  EXPECT_LT(SpineError(*played, back, -Vec3::UnitZ(),
                       [&](double x) {
                         return kBackLoad * x * x * (6 * length * length - 4 * length * x + x * x) /
                                (24.0 * kBackEI);
                       }),
            1e-6 * tip);
  EXPECT_NEAR(-(w.spine_points[back].back() - model.spine_points.back()).z(), tip, 1e-6 * tip);
  EXPECT_FALSE(played->warnings[back].beyond_small_deflection);
}

TEST(ChairSample, LumbarBulgeIsAClampedStretchAndTheSeatStaysPut) {
  nlohmann::json document = ReadJson(SampleScenePath(kScene));
  std::unique_ptr<PlayedScene> played = PlayDocument(document);
  document["clips"][0].erase("profiles");  // the same chair without the bulge
  std::unique_ptr<PlayedScene> plain = PlayDocument(document);
  ASSERT_NE(played, nullptr);
  ASSERT_NE(plain, nullptr);
  played->Evaluate(0.0);
  const std::vector<Vec3> rest = played->positions;
  played->Evaluate(1.0);
  plain->Evaluate(1.0);
  const std::size_t back = played->Part("back");
  const PartModel& model = played->scene.model.parts[back];
  // The back's profile wires: rubber strips b = 0.04 m, h = 0.01 m, modulus E / (1 - nu^2).
  const double ei = 0.05e9 / (1.0 - 0.49 * 0.49) * 0.04 * 1e-6 / 12.0;
  for (std::uint32_t p = 0; p < model.profiles.size(); ++p) {
    const ProfileModel& profile = model.profiles[p];
    ASSERT_NEAR(profile.stiffness.bending, ei, 1e-9 * ei);
    const std::size_t m = profile.local_points.size();
    // The stretch [0.5, 1] of the loop (u = q / m), its rest arc length.
    double length = 0.0;
    for (std::size_t q = m / 2; q < m; ++q)
      length += (profile.local_points[(q + 1) % m] - profile.local_points[q]).norm();
    const double peak = kLumbarLoad * std::pow(length, 4) / (384.0 * ei);
    const bool loaded = p >= 2 && p <= 4;
    for (std::size_t q = 0; q < m; ++q) {
      // The profile wire's own bending: the bulging chair minus the plain one (same spines).
      const double moved = (played->playback->workspace().profile_points[back][p][q] -
                            plain->playback->workspace().profile_points[back][p][q])
                               .norm();
      const double v = (double(q) / double(m) - 0.5) / 0.5;
      const double expected = loaded && q >= m / 2 ? kLumbarLoad * std::pow(length, 4) * v * v *
                                                         (1 - v) * (1 - v) / (24.0 * ei)
                                                   : 0.0;
      EXPECT_NEAR(moved, expected, 1e-6 * peak) << "profile " << p << " point " << q;
      if (loaded && q == 3 * m / 4) {
        EXPECT_NEAR(moved, peak, 1e-6 * peak);  // v = 1/2
      }
    }
  }
  // The seat, the root, carries no load: its vertices do not move.
  const std::size_t seat = played->Part("seat");
  std::size_t seat_vertices = 0;
  for (std::size_t v = 0; v < rest.size(); ++v) {
    if (played->scene.model.vertices[v].part != seat) continue;
    ++seat_vertices;
    EXPECT_LT((played->positions[v] - rest[v]).norm(), 1e-12) << "vertex " << v;
  }
  EXPECT_GT(seat_vertices, 100u);
}

TEST(ChairSample, RefusesAPartTheChairDoesNotHave) {
  nlohmann::json scene = ReadJson(SampleScenePath(kScene));
  scene["clips"][0]["parts"][0]["part"] = "leg_9";
  EXPECT_NE(SceneError(scene).find("leg_9"), std::string::npos) << SceneError(scene);
  scene = ReadJson(SampleScenePath(kScene));
  scene["mesh"]["parameters"]["leg_radius"] = 0.5;
  EXPECT_NE(SceneError(scene).find("/mesh/parameters/leg_radius"), std::string::npos)
      << SceneError(scene);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::samples
