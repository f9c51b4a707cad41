#include "wirerig/runtime/material.h"

#include <array>
#include <cmath>

#include "validation.h"

namespace wirerig {

Status ValidateMaterial(const Material& m) {
  if (!std::isfinite(m.youngs_modulus) || m.youngs_modulus <= 0.0 ||
      m.youngs_modulus > detail::kMaxStiffnessFactor)
    return Status::Invalid("E", "must be positive and finite, within 1e150 (Pa)");
  if (!std::isfinite(m.poisson_ratio) || m.poisson_ratio <= -1.0 || m.poisson_ratio >= 0.5)
    return Status::Invalid("nu", "must lie in (-1, 0.5)");
  if (!std::isfinite(m.density) || m.density < 0.0)
    return Status::Invalid("density", "must be finite and not negative (kg/m^3)");
  if (!std::isfinite(m.damping_ratio) || m.damping_ratio < 0.0 || m.damping_ratio > 100.0)
    return Status::Invalid("damping_ratio", "must lie in [0, 100]");
  return Status::Ok();
}

namespace {
// Sources: standard engineering handbook values (order of magnitude for tissues and for
// every damping ratio).
constexpr std::array kPresets = {
    MaterialPreset{"rubber", {0.05e9, 0.49, 1100.0, 0.05}},
    MaterialPreset{"soft_tissue", {0.1e6, 0.45, 1060.0, 0.1}},
    MaterialPreset{"skin", {1.0e6, 0.48, 1100.0, 0.1}},
    MaterialPreset{"cartilage", {10.0e6, 0.40, 1100.0, 0.05}},
    MaterialPreset{"wood", {10.0e9, 0.35, 500.0, 0.02}},
    MaterialPreset{"aluminium", {69.0e9, 0.33, 2700.0, 0.002}},
    MaterialPreset{"steel", {200.0e9, 0.30, 7850.0, 0.002}},
};
}  // namespace

std::span<const MaterialPreset> MaterialPresets() { return kPresets; }

const Material* FindMaterialPreset(std::string_view name) {
  for (const MaterialPreset& preset : kPresets)
    if (preset.name == name) return &preset.material;
  return nullptr;
}

}  // namespace wirerig
