#include "wirerig/runtime/section.h"

#include <cmath>
#include <initializer_list>
#include <numbers>

#include "validation.h"

namespace wirerig {
namespace {

using detail::kMaxStiffnessFactor;
using detail::PositiveFinite;

// Whether the product of positive `factors` is at most kMaxStiffnessFactor, found in logarithms
// so that nothing overflows (callers may trap floating-point overflow).
bool ProductWithinBound(std::initializer_list<double> factors) {
  double log_product = 0.0;
  for (double f : factors) log_product += std::log(f);
  return log_product <= std::log(kMaxStiffnessFactor);
}

}  // namespace

Status ValidateStrip(double width, double thickness) {
  if (!PositiveFinite(width)) return Status::Invalid("b", "must be positive and finite (m)");
  if (!PositiveFinite(thickness)) return Status::Invalid("h", "must be positive and finite (m)");
  if (!ProductWithinBound({width, thickness}) ||
      !ProductWithinBound({width, thickness, thickness, thickness, 1.0 / 12.0}) ||
      !ValidateSection(StripSection(width, thickness)))  // b h or b h^3 / 12 underflows
    return Status::Invalid("h", "gives with b a section whose A or I is out of range");
  return Status::Ok();
}

Status ValidateTube(double mean_radius, double wall_thickness) {
  if (!PositiveFinite(mean_radius)) return Status::Invalid("r", "must be positive and finite (m)");
  if (!PositiveFinite(wall_thickness))
    return Status::Invalid("h", "must be positive and finite (m)");
  if (wall_thickness / 2.0 > mean_radius)
    return Status::Invalid("h", "must not exceed twice the mean radius r");
  const double r = mean_radius, h = wall_thickness, two_pi = 2.0 * std::numbers::pi;
  // I = pi r h (r^2 + h^2 / 4) is at most 2 pi r^3 h, h being at most 2 r.
  if (!ProductWithinBound({two_pi, r, h}) || !ProductWithinBound({two_pi, r, r, r, h}) ||
      !ValidateSection(TubeSection(r, h)))
    return Status::Invalid("h", "gives with r a section whose A or I is out of range");
  return Status::Ok();
}

Section StripSection(double width, double thickness) {
  return {SectionKind::kStrip, width * thickness, width * thickness * thickness * thickness / 12.0};
}

Section TubeSection(double r, double h) {
  const double pi = std::numbers::pi;
  return {SectionKind::kTube, 2.0 * pi * r * h, pi * r * h * (r * r + h * h / 4.0)};
}

Section CustomSection(double area, double second_moment) {
  return {SectionKind::kCustom, area, second_moment};
}

Status ValidateSection(const Section& section) {
  if (section.kind != SectionKind::kCustom && section.kind != SectionKind::kStrip &&
      section.kind != SectionKind::kTube)
    return Status::Invalid("kind", "unknown section kind");
  if (!PositiveFinite(section.area) || section.area > kMaxStiffnessFactor)
    return Status::Invalid("A", "must be positive and finite, within 1e150 (m^2)");
  if (!PositiveFinite(section.second_moment) || section.second_moment > kMaxStiffnessFactor)
    return Status::Invalid("I", "must be positive and finite, within 1e150 (m^4)");
  return Status::Ok();
}

WireStiffness ComputeStiffness(const Material& material, const Section& section) {
  const double e = material.youngs_modulus;
  const double bending_modulus = section.kind == SectionKind::kStrip
                                     ? e / (1.0 - material.poisson_ratio * material.poisson_ratio)
                                     : e;
  return {e * section.area, bending_modulus * section.second_moment};
}

}  // namespace wirerig
