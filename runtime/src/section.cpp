#include "wirerig/runtime/section.h"

#include <cmath>
#include <numbers>

namespace wirerig {
namespace {
bool PositiveFinite(double x) { return std::isfinite(x) && x > 0.0; }
}  // namespace

Status ValidateStrip(double width, double thickness) {
  if (!PositiveFinite(width)) return Status::Invalid("b", "must be positive and finite (m)");
  if (!PositiveFinite(thickness)) return Status::Invalid("h", "must be positive and finite (m)");
  return Status::Ok();
}

Status ValidateTube(double mean_radius, double wall_thickness) {
  if (!PositiveFinite(mean_radius)) return Status::Invalid("r", "must be positive and finite (m)");
  if (!PositiveFinite(wall_thickness))
    return Status::Invalid("h", "must be positive and finite (m)");
  if (wall_thickness > 2.0 * mean_radius)
    return Status::Invalid("h", "must not exceed twice the mean radius r");
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
  if (!PositiveFinite(section.area))
    return Status::Invalid("A", "must be positive and finite (m^2)");
  if (!PositiveFinite(section.second_moment))
    return Status::Invalid("I", "must be positive and finite (m^4)");
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
