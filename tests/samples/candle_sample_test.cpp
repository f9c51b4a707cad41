// samples/candle (paper Fig. 5b-f): axial tension and compression of candle spines with 101
// load nodes. The scene is played headless and every spine sample's displacement along the
// axis is checked against the closed form of PHYSICS.md section 3, written out here:
//   X(v) = (L / EA) sum_j P_j g(v, v_j),  g = min(|v - v0|, |v_j - v0|) on the same side of v0,
// and against the paper's headline numbers (12.75 F L / EA at the ends of the middle-fixed
// candle, 50.5 F L / EA at the free end of the one-sided cases, Delta sum over 100 nodes).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "sample_test_support.h"

namespace wirerig::samples {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr const char* kScene = "candle/candle.scene.json";
constexpr double kE = 2.0e6, kA = 0.005;  // the scene's wax and section

// One candle's case: where it is held, the force at node j (v_j = j / 100; 0 = no load), and
// its free end's displacement in units of F L / EA from the paper's sums.
struct Case {
  std::string part;
  double fixed_at;
  double force;                     // F, N
  std::function<double(int)> load;  // the signed load at node j, in units of F
  double end_v;                     // the end whose displacement is the headline number
  double end_units;                 // X(end_v) / (F L / EA)
};

std::vector<Case> Cases() {
  return {
      // (b) top held, every node below pulled down: X(0) = -sum_{j<100} (1 - v_j) = -50.5.
      {"candle_1", 1.0, 30.0, [](int j) { return j == 100 ? 0.0 : -1.0; }, 0.0, -50.5},
      // (c) middle held, upper nodes pulled up and lower nodes down: X(1) = +12.75.
      {"candle_2", 0.5, 60.0, [](int j) { return j == 50 ? 0.0 : (j > 50 ? 1.0 : -1.0); }, 1.0,
       12.75},
      // (d) bottom held, every node above pushed down: X(1) = -sum_{j>0} v_j = -50.5.
      {"candle_3", 0.0, 30.0, [](int j) { return j == 0 ? 0.0 : -1.0; }, 1.0, -50.5},
      // (e) middle held, both halves pushed towards it: X(1) = -12.75.
      {"candle_4", 0.5, 60.0, [](int j) { return j == 50 ? 0.0 : (j > 50 ? -1.0 : 1.0); }, 1.0,
       -12.75},
      // (f) middle held, only nodes 30..70 pulled apart: X(1) = sum_{k=1}^{20} k / 100 = 2.1.
      {"candle_5", 0.5, 150.0,
       [](int j) { return j < 30 || j > 70 || j == 50 ? 0.0 : (j > 50 ? 1.0 : -1.0); }, 1.0, 2.1},
  };
}

// The closed form, independently of the runtime's AxialJob: sum over the 101 nodes.
double ClosedForm(const Case& c, double v, double length) {
  double sum = 0.0;
  const double v0 = c.fixed_at;
  for (int j = 0; j <= 100; ++j) {
    const double vj = j / 100.0, p = c.force * c.load(j);
    if (p == 0.0 || (v - v0) * (vj - v0) <= 0.0) continue;
    sum += p * std::min(std::abs(v - v0), std::abs(vj - v0));
  }
  return sum * length / (kE * kA);
}

TEST(CandleSample, SpinesStretchAndShortenByTheClosedForm) {
  std::unique_ptr<PlayedScene> played = PlaySample(kScene);
  ASSERT_NE(played, nullptr);
  // The scene's stiffness is the one this test assumes.
  for (const PartModel& part : played->scene.model.parts)
    ASSERT_DOUBLE_EQ(part.spine_stiffness.axial, kE * kA) << part.name;
  played->Evaluate(1.0);  // the loads' full values
  const RigWorkspace& w = played->playback->workspace();
  for (const Case& c : Cases()) {
    SCOPED_TRACE(c.part);
    const std::size_t i = played->Part(c.part);
    const PartModel& part = played->scene.model.parts[i];
    const std::size_t n = part.spine_points.size();
    ASSERT_EQ(n, 100u);  // 4 x 25 profiles
    const Vec3 axis = part.spine_points.back() - part.spine_points.front();
    const double length = axis.norm();  // straight spine: its rest length
    const double unit = c.force * length / (kE * kA);
    double largest = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const double v = double(k) / double(n - 1);
      const Vec3 moved = w.spine_points[i][k] - part.spine_points[k];
      const double along = moved.dot(axis) / length;
      const double expected = ClosedForm(c, v, length);
      EXPECT_NEAR(along, expected, 1e-6 * std::abs(c.end_units) * unit) << "v = " << v;
      EXPECT_LT((moved - along * axis / length).norm(), 1e-12) << "v = " << v;  // no sideways
      largest = std::max(largest, std::abs(along));
    }
    // The paper's numbers at the free end, and it moves the most.
    const std::size_t end = c.end_v == 0.0 ? 0 : n - 1;
    const double end_moved = (w.spine_points[i][end] - part.spine_points[end]).dot(axis) / length;
    EXPECT_NEAR(end_moved / unit, c.end_units, 1e-6 * std::abs(c.end_units));
    EXPECT_DOUBLE_EQ(largest, std::abs(end_moved));
    // The held point does not move.
    if (c.fixed_at == 0.0 || c.fixed_at == 1.0) {
      const std::size_t held = c.fixed_at == 0.0 ? 0 : n - 1;
      EXPECT_LT((w.spine_points[i][held] - part.spine_points[held]).norm(), 1e-15);
    }
  }
  // The reference candle (a) stays at rest.
  const std::size_t a = played->Part("candle_0");
  for (std::size_t k = 0; k < w.spine_points[a].size(); ++k)
    EXPECT_LT((w.spine_points[a][k] - played->scene.model.parts[a].spine_points[k]).norm(), 1e-15);
}

// The internal force of PHYSICS.md section 3 (tension > 0): beyond v0 the loads further out,
// before v0 minus the loads further in; at v0 itself the side towards the wire's interior
// (above v0, or below when v0 = 1: AxialJob's documented convention).
double NormalForce(const Case& c, double v) {
  double n = 0.0;
  // The interior side's value at the support and at the ends (a load on an end face counts).
  const bool above = v > c.fixed_at || (v == c.fixed_at && c.fixed_at < 1.0);
  for (int j = 0; j <= 100; ++j) {
    const double vj = j / 100.0, p = c.force * c.load(j);
    if (above && (vj > v || (v == 1.0 && j == 100))) n += p;
    if (!above && (vj < v || (v == 0.0 && j == 0))) n -= p;
  }
  return n;
}

TEST(CandleSample, TensionThinsAndCompressionThickensTheCandle) {
  // preserve_volume: a profile scales by 1 / sqrt(1 + N / EA) in its plane, N taken at the
  // spine samples around it and interpolated linearly to the profile.
  std::unique_ptr<PlayedScene> played = PlaySample(kScene);
  ASSERT_NE(played, nullptr);
  played->Evaluate(1.0);
  const RigWorkspace& w = played->playback->workspace();
  for (const Case& c : Cases()) {
    const std::size_t i = played->Part(c.part);
    const PartModel& part = played->scene.model.parts[i];
    const double last = double(part.spine_points.size() - 1);
    double thinnest = 1.0, thickest = 1.0;
    for (std::size_t p = 0; p < part.profiles.size(); ++p) {
      const double x = part.profiles[p].spine_v * last, k = std::min(std::floor(x), last - 1.0);
      const double f = x - k;
      const double n = (1.0 - f) * NormalForce(c, k / last) + f * NormalForce(c, (k + 1.0) / last);
      const double expected = 1.0 / std::sqrt(1.0 + n / (kE * kA));
      EXPECT_NEAR(w.profile_scale[i][p], expected, 1e-12) << c.part << " profile " << p;
      thinnest = std::min(thinnest, w.profile_scale[i][p]);
      thickest = std::max(thickest, w.profile_scale[i][p]);
    }
    // Tension thins (b, c, f), compression thickens (d, e).
    const bool tension = c.part == "candle_1" || c.part == "candle_2" || c.part == "candle_5";
    EXPECT_LT(tension ? thinnest : 1.0 / thickest, 0.9) << c.part;
  }
}

TEST(CandleSample, RefusesAHeldPointOffTheWire) {
  nlohmann::json scene = ReadJson(SampleScenePath(kScene));
  scene["clips"][0]["parts"][1]["axial_fixed_at"] = 1.5;
  EXPECT_NE(SceneError(scene).find("axial_fixed_at: must lie in [0, 1]"), std::string::npos)
      << SceneError(scene);
  scene = ReadJson(SampleScenePath(kScene));
  scene["mesh"]["parameters"]["count"] = 0;
  EXPECT_NE(SceneError(scene).find("/mesh/parameters/count"), std::string::npos)
      << SceneError(scene);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::samples
