// Materials, sections and stiffnesses against hand-computed values and the exact annulus.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "wirerig/runtime/material.h"
#include "wirerig/runtime/section.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(Section, StripIsBhAndBh3Over12WithPlateModulus) {
  const Section s = StripSection(0.05, 0.002);
  EXPECT_DOUBLE_EQ(s.area, 1e-4);
  EXPECT_DOUBLE_EQ(s.second_moment, 0.05 * 8e-9 / 12.0);
  const Material m{2.0e9, 0.3, 1000.0};
  const WireStiffness k = ComputeStiffness(m, s);
  EXPECT_DOUBLE_EQ(k.axial, 2.0e9 * 1e-4);
  // D b with D = E h^3 / (12 (1 - nu^2)): the plate's flexural rigidity times the width.
  EXPECT_DOUBLE_EQ(k.bending, 2.0e9 * 8e-9 / (12.0 * (1.0 - 0.09)) * 0.05);
}

TEST(Section, TubeIsTheExactAnnulus) {
  const double r = 0.05, h = 0.004;
  const Section s = TubeSection(r, h);
  const double ro = r + h / 2, ri = r - h / 2, pi = std::numbers::pi;
  EXPECT_NEAR(s.area, pi * (ro * ro - ri * ri), 1e-14 * s.area);
  EXPECT_NEAR(s.second_moment, pi / 4.0 * (std::pow(ro, 4) - std::pow(ri, 4)),
              1e-14 * s.second_moment);
  const WireStiffness k = ComputeStiffness({1e6, 0.45, 1000.0}, s);
  EXPECT_DOUBLE_EQ(k.bending, 1e6 * s.second_moment);  // plain E for spines
}

TEST(Section, CustomUsesPlainYoungsModulus) {
  const WireStiffness k = ComputeStiffness({3e9, 0.4, 1.0}, CustomSection(2e-4, 5e-9));
  EXPECT_DOUBLE_EQ(k.axial, 6e5);
  EXPECT_DOUBLE_EQ(k.bending, 15.0);
}

TEST(Section, InvalidDimensionsAreNamed) {
  EXPECT_EQ(ValidateStrip(0.0, 0.001).field, "b");
  EXPECT_EQ(ValidateStrip(0.01, -1.0).field, "h");
  EXPECT_EQ(ValidateTube(std::nan(""), 0.001).field, "r");
  EXPECT_EQ(ValidateTube(0.01, 0.0).field, "h");
  EXPECT_EQ(ValidateTube(0.01, 0.03).field, "h");  // inner radius would be negative
  EXPECT_TRUE(ValidateTube(0.01, 0.02).ok());      // a solid rod
  // Finite inputs whose section overflows (b h^3 / 12 = inf) or underflows (b h = 0) are refused:
  // a rig built with a skin thickness of 1e300 m wrote I = inf (JSON null) and could not be read.
  EXPECT_EQ(ValidateStrip(0.05, 1e300).field, "h");
  EXPECT_EQ(ValidateStrip(1e-200, 1e-200).field, "h");
  EXPECT_EQ(ValidateTube(1e200, 1e200).field, "h");
  EXPECT_TRUE(ValidateStrip(0.05, 1e-3).ok());
  EXPECT_EQ(ValidateSection(CustomSection(0.0, 1.0)).field, "A");
  EXPECT_EQ(ValidateSection(CustomSection(1.0, -1.0)).field, "I");
  // Finite but so large that E A or E I would overflow (a scene's A = 1e300 was blamed on the
  // clip's poses): refused; E A at the bounds is finite.
  EXPECT_EQ(ValidateSection(CustomSection(1e300, 1.0)).field, "A");
  EXPECT_EQ(ValidateSection(CustomSection(1.0, 1e151)).field, "I");
  EXPECT_TRUE(ValidateSection(CustomSection(1e150, 1e150)).ok());
  EXPECT_TRUE(
      std::isfinite(ComputeStiffness({1e150, 0.3, 1.0}, CustomSection(1e150, 1e150)).axial));
  EXPECT_EQ(ValidateSection({static_cast<SectionKind>(9), 1.0, 1.0}).field, "kind");
}

TEST(Material, PresetsAreValidAndFindable) {
  ASSERT_GE(MaterialPresets().size(), 5u);
  for (const MaterialPreset& preset : MaterialPresets()) {
    SCOPED_TRACE(std::string(preset.name));
    EXPECT_TRUE(ValidateMaterial(preset.material).ok());
    EXPECT_EQ(FindMaterialPreset(preset.name), &preset.material);
  }
  ASSERT_NE(FindMaterialPreset("steel"), nullptr);
  EXPECT_DOUBLE_EQ(FindMaterialPreset("steel")->youngs_modulus, 200e9);
  EXPECT_EQ(FindMaterialPreset("unobtainium"), nullptr);
}

TEST(Material, InvalidFieldsAreNamed) {
  EXPECT_EQ(ValidateMaterial({0.0, 0.3, 1.0}).field, "E");
  EXPECT_EQ(ValidateMaterial({std::numeric_limits<double>::infinity(), 0.3, 1.0}).field, "E");
  EXPECT_EQ(ValidateMaterial({1e300, 0.3, 1.0}).field, "E");
  EXPECT_EQ(ValidateMaterial({1e9, 0.5, 1.0}).field, "nu");
  EXPECT_EQ(ValidateMaterial({1e9, -1.0, 1.0}).field, "nu");
  EXPECT_EQ(ValidateMaterial({1e9, 0.3, -1.0}).field, "density");
  EXPECT_EQ(ValidateMaterial({1e9, 0.3, 1.0, -0.01}).field, "damping_ratio");
  EXPECT_EQ(ValidateMaterial({1e9, 0.3, 1.0, std::nan("")}).field, "damping_ratio");
  EXPECT_EQ(ValidateMaterial({1e9, 0.3, 1.0, 101.0}).field, "damping_ratio");
}

TEST(Material, DampingRatiosAreLightForMetalsAndHeavierForTissues) {
  EXPECT_DOUBLE_EQ((Material{1e9, 0.3, 1.0}.damping_ratio), 0.05);  // the default
  for (const MaterialPreset& preset : MaterialPresets()) {
    SCOPED_TRACE(std::string(preset.name));
    EXPECT_GT(preset.material.damping_ratio, 0.0);
    EXPECT_LT(preset.material.damping_ratio, 1.0);  // every preset is under-damped
  }
  EXPECT_LT(FindMaterialPreset("steel")->damping_ratio, FindMaterialPreset("wood")->damping_ratio);
  EXPECT_LT(FindMaterialPreset("wood")->damping_ratio,
            FindMaterialPreset("soft_tissue")->damping_ratio);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
