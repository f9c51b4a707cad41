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
};

// E positive and finite, nu in (-1, 0.5), density finite and not negative.
Status ValidateMaterial(const Material& material);

struct MaterialPreset {
  std::string_view name;
  Material material;
};

// Typical room-temperature values, SI: rubber, soft_tissue, skin, cartilage, wood (pine,
// along the grain), aluminium, steel.
std::span<const MaterialPreset> MaterialPresets();
// Nullptr if no preset has that name.
const Material* FindMaterialPreset(std::string_view name);

}  // namespace wirerig
