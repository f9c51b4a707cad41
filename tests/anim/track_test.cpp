// Keyframed tracks against functions they must reproduce exactly: constants and straight lines
// under every interpolation, quadratics on the interior of uniform cubic tracks; plus the
// validity rules of the raw form.
#include "wirerig/anim/track.h"

#include <gtest/gtest.h>

#include <cmath>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

RawScalarTrack Sampled(double (*f)(double), std::initializer_list<double> times,
                       Interpolation interpolation) {
  RawScalarTrack raw;
  for (double t : times) raw.keys.push_back({t, f(t), interpolation});
  return raw;
}

double Line(double t) { return 3.0 - 2.0 * t; }
double Parabola(double t) { return 0.5 * t * t - t + 2.0; }

TEST(Track, LinearReproducesAStraightLineBetweenUnevenKeys) {
  const ScalarTrack track =
      BuildTrack(Sampled(Line, {0.0, 0.3, 1.1, 2.0}, Interpolation::kLinear)).value();
  for (double t = 0.0; t <= 2.0; t += 0.01) EXPECT_NEAR(track.Sample(t), Line(t), 1e-12) << t;
}

TEST(Track, CubicReproducesAStraightLineBetweenUnevenKeys) {
  const ScalarTrack track =
      BuildTrack(Sampled(Line, {0.0, 0.3, 1.1, 2.0}, Interpolation::kCubic)).value();
  for (double t = 0.0; t <= 2.0; t += 0.01) EXPECT_NEAR(track.Sample(t), Line(t), 1e-12) << t;
}

TEST(Track, CubicIsExactForAParabolaOnInteriorUniformSegments) {
  // Catmull-Rom tangents on uniform keys are the parabola's exact slopes at interior keys, so
  // the Hermite segment between two interior keys is the parabola itself.
  const ScalarTrack track =
      BuildTrack(Sampled(Parabola, {0.0, 0.5, 1.0, 1.5, 2.0}, Interpolation::kCubic)).value();
  for (double t = 0.5; t <= 1.5; t += 0.01) EXPECT_NEAR(track.Sample(t), Parabola(t), 1e-12) << t;
}

TEST(Track, CubicIsContinuousInSlopeAcrossKeys) {
  RawScalarTrack raw;
  raw.keys = {{0.0, 0.0, Interpolation::kCubic},
              {0.4, 1.0, Interpolation::kCubic},
              {1.0, -0.5, Interpolation::kCubic},
              {1.7, 2.0, Interpolation::kCubic}};
  const ScalarTrack track = BuildTrack(raw).value();
  const double h = 1e-6;
  for (double key : {0.4, 1.0}) {
    const double left = (track.Sample(key) - track.Sample(key - h)) / h;
    const double right = (track.Sample(key + h) - track.Sample(key)) / h;
    EXPECT_NEAR(left, right, 1e-4) << key;
    EXPECT_DOUBLE_EQ(track.Sample(key), raw.keys[key == 0.4 ? 1 : 2].value);
  }
}

TEST(Track, StepHoldsEachKeyUntilTheNext) {
  const ScalarTrack track =
      BuildTrack(Sampled(Line, {0.0, 1.0, 2.0}, Interpolation::kStep)).value();
  EXPECT_EQ(track.Sample(0.0), Line(0.0));
  EXPECT_EQ(track.Sample(0.999), Line(0.0));
  EXPECT_EQ(track.Sample(1.0), Line(1.0));
  EXPECT_EQ(track.Sample(1.5), Line(1.0));
}

TEST(Track, HoldsTheEndValuesOutsideItsKeys) {
  const ScalarTrack track = BuildTrack(Sampled(Line, {0.5, 1.0}, Interpolation::kLinear)).value();
  EXPECT_EQ(track.Sample(-3.0), Line(0.5));
  EXPECT_EQ(track.Sample(0.0), Line(0.5));
  EXPECT_EQ(track.Sample(7.0), Line(1.0));
  EXPECT_EQ(track.StartTime(), 0.5);
  EXPECT_EQ(track.EndTime(), 1.0);
}

TEST(Track, MixedInterpolationFollowsEachKeysOwnSegment) {
  RawScalarTrack raw;
  raw.keys = {{0.0, 0.0, Interpolation::kStep},
              {1.0, 1.0, Interpolation::kLinear},
              {2.0, 3.0, Interpolation::kLinear}};
  const ScalarTrack track = BuildTrack(raw).value();
  EXPECT_EQ(track.Sample(0.5), 0.0);
  EXPECT_DOUBLE_EQ(track.Sample(1.5), 2.0);
}

TEST(Track, VectorTracksInterpolateEachComponent) {
  RawVectorTrack raw;
  raw.keys = {{0.0, Vec3(1, 0, 0), Interpolation::kLinear},
              {2.0, Vec3(0, 2, -4), Interpolation::kLinear}};
  const VectorTrack track = BuildTrack(raw).value();
  EXPECT_TRUE(track.Sample(0.5).isApprox(Vec3(0.75, 0.5, -1.0), 1e-15));
}

TEST(Track, EmptyAndConstantTracks) {
  EXPECT_TRUE(VectorTrack{}.IsEmpty());
  EXPECT_EQ(VectorTrack{}.Sample(1.0), Vec3::Zero());
  EXPECT_EQ(ScalarTrack{}.Sample(1.0), 0.0);
  EXPECT_EQ(ConstantTrack(2.5).Sample(-1.0), 2.5);
  EXPECT_EQ(ConstantTrack(2.5).Sample(100.0), 2.5);
}

TEST(Track, RawRulesNameTheBrokenKey) {
  RawScalarTrack raw;
  EXPECT_EQ(ValidateRawTrack(raw), "keys: a track needs at least one key");
  EXPECT_EQ(BuildTrack(raw).error(), "keys: a track needs at least one key");
  raw.keys = {{0.0, 1.0}, {1.0, 2.0}, {1.0, 3.0}};
  EXPECT_EQ(ValidateRawTrack(raw), "keys[2].time: key times must be strictly increasing");
  raw.keys = {{0.0, 1.0}, {1.0, std::nan("")}};
  EXPECT_EQ(ValidateRawTrack(raw), "keys[1].value: must be finite");
  raw.keys = {{std::numeric_limits<double>::infinity(), 1.0}};
  EXPECT_EQ(ValidateRawTrack(raw), "keys[0].time: must be finite");
  raw.keys = {{0.0, 1.0, static_cast<Interpolation>(7)}};
  EXPECT_EQ(ValidateRawTrack(raw), "keys[0].interpolation: unknown");
}

TEST(Track, InterpolationNamesRoundTrip) {
  for (Interpolation i : {Interpolation::kStep, Interpolation::kLinear, Interpolation::kCubic}) {
    Interpolation parsed = Interpolation::kStep;
    ASSERT_TRUE(ParseInterpolation(ToString(i), &parsed));
    EXPECT_EQ(parsed, i);
  }
  Interpolation parsed;
  EXPECT_FALSE(ParseInterpolation("bezier", &parsed));
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
