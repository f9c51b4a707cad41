// Tests of the chest sample (issue 7, paper Fig. 3): the clamped-plate finite-difference
// reference against Timoshenko's plate constants (PHYSICS.md section 5), and the 7-wire model
// against the textbook clamped-beam formula and the xi and error values of PHYSICS.md.
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "plate_reference.h"
#include "wire_patch.h"

namespace wirerig::chest {
namespace {
namespace WIRERIG_TEST_FILE {

constexpr int kWires = 7;

// Plates on the unit square (D = q = 1) at n = 48 and 96, solved once for the suite.
class ChestPlate : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    PlateProblem problem;
    problem.intervals = 48;
    ASSERT_TRUE(SolveClampedPlate(problem, &coarse_));
    problem.intervals = 96;
    ASSERT_TRUE(SolveClampedPlate(problem, &fine_));
  }
  static PlateSolution coarse_;
  static PlateSolution fine_;
};
PlateSolution ChestPlate::coarse_;
PlateSolution ChestPlate::fine_;

TEST_F(ChestPlate, SquareCentreMatchesReferenceWithinOnePercent) {
  EXPECT_NEAR(fine_.Centre() / kClampedSquareCentre, 1.0, 0.01);
  // The centre is a grid node for even n, and it is the peak.
  EXPECT_DOUBLE_EQ(fine_.Centre(), fine_.At(48, 48));
  EXPECT_DOUBLE_EQ(fine_.Peak(), fine_.Centre());
}

TEST_F(ChestPlate, ConvergesAsHSquaredAndRichardsonLandsWithinPointOnePercent) {
  const double error_coarse = coarse_.Centre() - kClampedSquareCentre;
  const double error_fine = fine_.Centre() - kClampedSquareCentre;
  ASSERT_GT(std::abs(error_fine), 0.0);
  // O(h^2): halving h divides the error by 4.
  EXPECT_NEAR(error_coarse / error_fine, 4.0, 0.4);
  const double extrapolated = RichardsonH2(coarse_.Centre(), fine_.Centre());
  EXPECT_NEAR(extrapolated / kClampedSquareCentre, 1.0, 0.001);
}

TEST_F(ChestPlate, SolutionIsSymmetricAndZeroOnTheEdges) {
  const int n = fine_.intervals();
  double largest_asymmetry = 0.0;
  for (int i = 0; i <= n; ++i) {
    EXPECT_EQ(fine_.At(i, 0), 0.0);
    EXPECT_EQ(fine_.At(0, i), 0.0);
    EXPECT_EQ(fine_.At(i, n), 0.0);
    EXPECT_EQ(fine_.At(n, i), 0.0);
    for (int j = 0; j <= n; ++j) {
      largest_asymmetry = std::max(largest_asymmetry, std::abs(fine_.At(i, j) - fine_.At(j, i)));
      largest_asymmetry =
          std::max(largest_asymmetry, std::abs(fine_.At(i, j) - fine_.At(n - i, j)));
    }
  }
  EXPECT_LT(largest_asymmetry, 1e-10 * fine_.Peak());  // rounding of the sparse solve
}

// Clamped rectangle, b/a = 2 (a the shorter side): w_max = 0.00254 q a^4/D (Timoshenko &
// Woinowsky-Krieger, Theory of Plates and Shells, Table 35; 3 digits). Checks the a != b
// scaling of the stencil, in both orientations.
TEST(ChestPlateRectangle, CentreMatchesTimoshenkoForAspectTwo) {
  for (bool long_along_y : {true, false}) {
    PlateProblem problem;
    problem.width = long_along_y ? 1.0 : 2.0;
    problem.length = long_along_y ? 2.0 : 1.0;
    PlateSolution coarse, fine;
    problem.intervals = 48;
    ASSERT_TRUE(SolveClampedPlate(problem, &coarse));
    problem.intervals = 96;
    ASSERT_TRUE(SolveClampedPlate(problem, &fine));
    const double extrapolated = RichardsonH2(coarse.Centre(), fine.Centre());
    EXPECT_NEAR(extrapolated / 0.00254, 1.0, 0.004) << "long_along_y " << long_along_y;
  }
}

// w = c q a^4 / D: a = 2, D = 3, q = 5 scales the unit square's solution by 16 * 5 / 3.
TEST_F(ChestPlate, ScalesAsQAToTheFourthOverD) {
  PlateProblem problem;
  problem.width = 2.0;
  problem.length = 2.0;
  problem.flexural_rigidity = 3.0;
  problem.pressure = 5.0;
  problem.intervals = 48;
  PlateSolution scaled;
  ASSERT_TRUE(SolveClampedPlate(problem, &scaled));
  EXPECT_NEAR(scaled.Centre() / (coarse_.Centre() * 16.0 * 5.0 / 3.0), 1.0, 1e-10);
}

TEST(ChestPlateInput, RefusesBadInputNamingTheField) {
  PlateSolution out;
  auto refused_field = [&](PlateProblem problem) {
    Status status = SolveClampedPlate(problem, &out);
    EXPECT_FALSE(status.ok());
    return std::string(status.field);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  PlateProblem p;
  p.width = 0.0;
  EXPECT_EQ(refused_field(p), "width");
  p = {};
  p.length = nan;
  EXPECT_EQ(refused_field(p), "length");
  p = {};
  p.flexural_rigidity = -1.0;
  EXPECT_EQ(refused_field(p), "flexural_rigidity");
  p = {};
  p.pressure = inf;
  EXPECT_EQ(refused_field(p), "pressure");
  p = {};
  p.intervals = 3;
  EXPECT_EQ(refused_field(p), "intervals");
  p.intervals = PlateProblem::kMaxIntervals + 1;
  EXPECT_EQ(refused_field(p), "intervals");
  EXPECT_TRUE(out.deflection.empty());  // untouched on failure
  EXPECT_FALSE(SolveClampedPlate(PlateProblem{}, nullptr).ok());
}

// The bare wires (xi = 1) are clamped-clamped beams under their strip's load: every interior
// wire deflects X(v) = q b^4 v^2 (1 - v)^2 / (24 D) (textbook; the strip width cancels).
TEST(ChestWires, BareWiresAreTextbookClampedBeams) {
  PlateProblem problem;
  problem.width = 0.6;
  problem.length = 1.5;
  problem.flexural_rigidity = 2.0;
  problem.pressure = 3.0;
  problem.intervals = 24;
  PlateSolution plate;
  ASSERT_TRUE(SolveClampedPlate(problem, &plate));
  WirePatch patch;
  ASSERT_TRUE(FitWirePatch(plate, kWires, XiFit::kNone, &patch));
  ASSERT_EQ(patch.wire_count(), kWires);
  EXPECT_DOUBLE_EQ(patch.strip_width[1], 0.1);
  EXPECT_EQ(patch.strip_width[0], 0.0);

  std::vector<double> samples{0.0, 0.1, 0.25, 0.5, 0.8, 1.0};
  std::vector<Vec3> scratch(samples.size());
  std::vector<double> deflection(kWires * samples.size());
  WirePatchJob job;
  job.patch = &patch;
  job.pressure = 7.0;
  job.samples = samples;
  job.scratch = scratch;
  job.deflection = deflection;
  ASSERT_TRUE(job.Run());
  const double b4 = std::pow(problem.length, 4);
  for (int j = 0; j < kWires; ++j) {
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const double v = samples[k];
      const double expected =
          (j == 0 || j == kWires - 1) ? 0.0 : 7.0 * b4 * v * v * (1 - v) * (1 - v) / (24.0 * 2.0);
      EXPECT_NEAR(deflection[j * samples.size() + k], expected, 1e-12 * 7.0 * b4 / 384.0)
          << "wire " << j << " v " << v;
    }
  }
}

// PHYSICS.md section 5: xi per wire 0.1729, 0.4053, 0.4974, 0.4053, 0.1729.
TEST_F(ChestPlate, XiPerWireMatchesPhysicsWithinTwoPercent) {
  WirePatch patch;
  ASSERT_TRUE(FitWirePatch(fine_, kWires, XiFit::kPerWire, &patch));
  const double expected[kWires] = {0.0, 0.1729, 0.4053, 0.4974, 0.4053, 0.1729, 0.0};
  EXPECT_EQ(patch.xi[0], 0.0);
  EXPECT_EQ(patch.xi[kWires - 1], 0.0);
  for (int j = 1; j < kWires - 1; ++j)
    EXPECT_NEAR(patch.xi[j] / expected[j], 1.0, 0.02) << "wire " << j;
  EXPECT_NEAR(patch.xi[1], patch.xi[5], 1e-10);
  EXPECT_NEAR(patch.xi[2], patch.xi[4], 1e-10);
}

TEST_F(ChestPlate, XiPerWireLeavesUnderThreePointFivePercentOnTheWires) {
  WirePatch patch;
  ASSERT_TRUE(FitWirePatch(fine_, kWires, XiFit::kPerWire, &patch));
  WirePatchErrors errors;
  ASSERT_TRUE(CompareWithPlate(patch, fine_, &errors));
  EXPECT_EQ(errors.plate_peak, fine_.Peak());
  EXPECT_LT(errors.max_on_wires, 0.035);
  // PHYSICS.md (384-interval grid): 2.93% max, 1.47% RMS on the wires; 6.84% max on the surface.
  EXPECT_NEAR(errors.max_on_wires, 0.0293, 0.002);
  EXPECT_NEAR(errors.rms_on_wires, 0.0147, 0.002);
  EXPECT_NEAR(errors.max_surface, 0.0684, 0.004);
  EXPECT_NEAR(errors.max_per_wire[1], 0.0138, 0.002);
  EXPECT_NEAR(errors.max_per_wire[3], 0.0293, 0.002);
}

// The paper's single xi leaves 34% error; without xi the wires are 2.06 times too deep.
TEST_F(ChestPlate, SingleXiAndNoXiLeaveLargeErrors) {
  WirePatch single, none;
  ASSERT_TRUE(FitWirePatch(fine_, kWires, XiFit::kSingle, &single));
  ASSERT_TRUE(FitWirePatch(fine_, kWires, XiFit::kNone, &none));
  EXPECT_NEAR(single.xi[1], 0.3308, 0.007);
  EXPECT_EQ(single.xi[1], single.xi[3]);
  WirePatchErrors single_errors, none_errors;
  ASSERT_TRUE(CompareWithPlate(single, fine_, &single_errors));
  ASSERT_TRUE(CompareWithPlate(none, fine_, &none_errors));
  EXPECT_NEAR(single_errors.max_on_wires, 0.336, 0.02);
  EXPECT_NEAR(none_errors.max_on_wires, 1.713, 0.03);
  // Bare wire peak q/(384 D) against the plate centre: 2.06 times.
  EXPECT_NEAR((1.0 / 384.0) / fine_.Peak(), 2.06, 0.01);
}

// xi depends on the geometry only, not on q or D.
TEST_F(ChestPlate, XiDoesNotDependOnLoadOrRigidity) {
  PlateProblem problem = coarse_.problem;
  problem.pressure = -40.0;
  problem.flexural_rigidity = 0.25;
  PlateSolution other;
  ASSERT_TRUE(SolveClampedPlate(problem, &other));
  WirePatch a, b;
  ASSERT_TRUE(FitWirePatch(coarse_, kWires, XiFit::kPerWire, &a));
  ASSERT_TRUE(FitWirePatch(other, kWires, XiFit::kPerWire, &b));
  for (int j = 1; j < kWires - 1; ++j) EXPECT_NEAR(a.xi[j], b.xi[j], 1e-10 * a.xi[j]);
}

TEST_F(ChestPlate, FitAndEvaluationRefuseBadInput) {
  WirePatch patch;
  EXPECT_EQ(std::string(FitWirePatch(coarse_, 2, XiFit::kPerWire, &patch).field), "wire_count");
  EXPECT_EQ(std::string(FitWirePatch(coarse_, 6, XiFit::kPerWire, &patch).field),
            "wire_count");  // 5 does not divide 48
  EXPECT_FALSE(FitWirePatch(coarse_, kWires, XiFit::kPerWire, nullptr).ok());
  PlateProblem unloaded = coarse_.problem;
  unloaded.pressure = 0.0;
  PlateSolution flat;
  ASSERT_TRUE(SolveClampedPlate(unloaded, &flat));
  EXPECT_EQ(std::string(FitWirePatch(flat, kWires, XiFit::kPerWire, &patch).field), "plate");
  WirePatchErrors errors;
  EXPECT_FALSE(CompareWithPlate(patch, flat, &errors).ok());

  ASSERT_TRUE(FitWirePatch(coarse_, kWires, XiFit::kPerWire, &patch));
  std::vector<double> samples{0.0, 0.5, 1.0};
  std::vector<Vec3> scratch(samples.size());
  std::vector<double> deflection(kWires * samples.size());
  WirePatchJob job;
  job.patch = &patch;
  job.samples = samples;
  job.scratch = scratch;
  job.deflection = deflection;
  ASSERT_TRUE(job.Run());
  WirePatchJob bad = job;
  bad.patch = nullptr;
  EXPECT_EQ(std::string(bad.Run().field), "patch");
  bad = job;
  bad.pressure = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(std::string(bad.Run().field), "pressure");
  bad = job;
  bad.scratch = std::span<Vec3>(scratch).first(2);
  EXPECT_EQ(std::string(bad.Run().field), "scratch");
  bad = job;
  bad.deflection = std::span<double>(deflection).first(3);
  EXPECT_EQ(std::string(bad.Run().field), "deflection");
  std::vector<double> outside{0.5, 1.5};
  std::vector<Vec3> scratch2(2);
  std::vector<double> deflection2(kWires * 2);
  bad = job;
  bad.samples = outside;
  bad.scratch = scratch2;
  bad.deflection = deflection2;
  EXPECT_EQ(std::string(bad.Run().field), "samples");  // BendingJob's own check
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig::chest
