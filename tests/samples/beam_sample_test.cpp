// samples/beam (paper Fig. 6): one beam bent by a midspan force, simply supported with F/2
// (t = 1 s) and clamped with F (t = 2 s). The played spine is checked against the textbook
// midspan-load deflection curves, written out here (x from the left support, P the force):
//   simply supported  y(x) = P x (3 L^2 - 4 x^2) / (48 EI),  x <= L/2 (symmetric); y(L/2) =
//                     P L^3 / 48 EI; end slopes P L^2 / 16 EI (the tangent turns at a support)
//   clamped           y(x) = P x^2 (3 L - 4 x) / (48 EI),    x <= L/2 (symmetric); y(L/2) =
//                     P L^3 / 192 EI; end slopes 0 (the tangent is continuous)
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sample_test_support.h"

namespace wirerig::samples {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr const char* kScene = "beam/beam.scene.json";
constexpr double kEI = 2.0e9 * 2.0e-5;  // the scene's E and I
constexpr double kF = 80000.0;          // N, the clamped case; the simply supported gets F/2

double SimplySupported(double x, double length, double p) {
  x = std::min(x, length - x);
  return p * x * (3.0 * length * length - 4.0 * x * x) / (48.0 * kEI);
}
double Clamped(double x, double length, double p) {
  x = std::min(x, length - x);
  return p * x * x * (3.0 * length - 4.0 * x) / (48.0 * kEI);
}

struct Measured {
  double max_error = 0.0;                     // largest |measured - formula| over the samples, m
  double largest = 0.0;                       // largest deflection, m
  double start_slope = 0.0, end_slope = 0.0;  // downward turn of the end tangents (tan)
};

// Deflections (downwards, -Y) of the played spine against `formula` at every sample.
template <typename Formula>
Measured Measure(PlayedScene& played, double t, Formula formula) {
  played.Evaluate(t);
  const RigWorkspace& w = played.playback->workspace();
  const PartModel& beam = played.scene.model.parts[0];
  const double length = (beam.spine_points.back() - beam.spine_points.front()).norm();
  Measured m;
  for (std::size_t k = 0; k < beam.spine_points.size(); ++k) {
    const Vec3 moved = w.spine_points[0][k] - beam.spine_points[k];
    const double x = (beam.spine_points[k] - beam.spine_points.front()).x();
    m.max_error = std::max(m.max_error, std::abs(-moved.y() - formula(x, length)));
    m.max_error = std::max(m.max_error, std::abs(moved.x()) + std::abs(moved.z()));
    m.largest = std::max(m.largest, -moved.y());
  }
  const Vec3 t0 = w.spine_frames[0].front().tangent, t1 = w.spine_frames[0].back().tangent;
  m.start_slope = -t0.y() / t0.x();  // going down from the left support
  m.end_slope = t1.y() / t1.x();     // coming up to the right support
  return m;
}

TEST(BeamSample, SimplySupportedWithHalfTheForceBendsTwiceAsFar) {
  std::unique_ptr<PlayedScene> played = PlaySample(kScene);
  ASSERT_NE(played, nullptr);
  const PartModel& beam = played->scene.model.parts[0];
  ASSERT_DOUBLE_EQ(beam.spine_stiffness.bending, kEI);
  ASSERT_EQ(beam.spine_points.size(), 64u);  // 4 x 16 profiles
  const double length = (beam.spine_points.back() - beam.spine_points.front()).norm();
  const double midspan_ss = 0.5 * kF * std::pow(length, 3) / (48.0 * kEI);
  const double midspan_cc = kF * std::pow(length, 3) / (192.0 * kEI);

  const Measured ss =
      Measure(*played, 1.0, [](double x, double l) { return SimplySupported(x, l, 0.5 * kF); });
  EXPECT_LT(ss.max_error, 1e-6 * midspan_ss);
  // Midspan is between the two middle samples: the largest sample is just short of it.
  EXPECT_LT(ss.largest, midspan_ss);
  EXPECT_GT(ss.largest, 0.999 * midspan_ss);
  const double ss_slope = 0.5 * kF * length * length / (16.0 * kEI);
  EXPECT_NEAR(ss.start_slope, ss_slope, 1e-6 * ss_slope);
  EXPECT_NEAR(ss.end_slope, ss_slope, 1e-6 * ss_slope);

  const Measured cc = Measure(*played, 2.0, [](double x, double l) { return Clamped(x, l, kF); });
  EXPECT_LT(cc.max_error, 1e-6 * midspan_cc);
  EXPECT_GT(cc.largest, 0.999 * midspan_cc);
  EXPECT_LT(std::abs(cc.start_slope), 1e-12);  // tangent continuity at the clamps
  EXPECT_LT(std::abs(cc.end_slope), 1e-12);

  // The paper's point: half the force, twice the midspan deflection.
  EXPECT_NEAR(midspan_ss / midspan_cc, 2.0, 1e-12);
  // Small deflection: within 10% of the span and 0.3 rad (no warning).
  EXPECT_LT(midspan_ss, 0.1 * length);
  EXPECT_LT(std::atan(ss_slope), 0.3);
  played->Evaluate(1.0);
  EXPECT_FALSE(played->warnings[0].beyond_small_deflection);
}

TEST(BeamSample, RefusesAnUnknownSupport) {
  nlohmann::json scene = ReadJson(SampleScenePath(kScene));
  scene["clips"][0]["parts"][0]["boundary"][1]["boundary"] = "pinned";
  const std::string error = SceneError(scene);
  EXPECT_NE(error.find("/clips/0/parts/0/boundary/1/boundary"), std::string::npos) << error;
  scene = ReadJson(SampleScenePath(kScene));
  scene["mesh"]["parameters"]["radius"] = 1.0;
  EXPECT_NE(SceneError(scene).find("/mesh/parameters/radius"), std::string::npos)
      << SceneError(scene);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::samples
