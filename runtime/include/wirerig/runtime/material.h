// Material of a wire: isotropic, linear elastic (paper section 4).
#pragma once

#include <span>
#include <string_view>

#include "wirerig/runtime/status.h"

namespace wirerig {

struct Material {
  double youngs_modulus = 0.0;  // E > 0, Pa
  double poisson_ratio = 0.0;   // nu in (-1, 0.5)
  double density = 0.0;         // rho >= 0, kg/m^3
  // Modal damping ratio zeta of the material's wires (modal_wire.h), dimensionless, in
  // [0, 100]: the fraction of critical damping of every bending mode. 0.05 (a lightly damped
  // solid) unless a preset says otherwise.
  double damping_ratio = 0.05;
};

// E positive and finite, nu in (-1, 0.5), density finite and not negative, damping_ratio in
// [0, 100] (field "damping_ratio").
Status ValidateMaterial(const Material& material);

struct MaterialPreset {
  std::string_view name;
  Material material;
};

// Typical room-temperature values, SI: rubber, soft_tissue, skin, cartilage, wood (pine,
// along the grain), aluminium, steel. Damping ratios: order-of-magnitude structural values
// (loss factor / 2): metals ~0.002, wood 0.02, rubber and cartilage 0.05, tissues 0.1.
std::span<const MaterialPreset> MaterialPresets();
// Nullptr if no preset has that name.
const Material* FindMaterialPreset(std::string_view name);

}  // namespace wirerig
