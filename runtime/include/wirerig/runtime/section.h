// Cross-section of a wire and the stiffnesses it gives with a material (paper section 4,
// corrected in PHYSICS.md section 4).
//   strip (b, h), a profile wire covering a surface band of width b and thickness h:
//       A = b h, I = b h^3 / 12, bending modulus E / (1 - nu^2) (cylindrical bending of a
//       wide strip), axial modulus E (free edges; PHYSICS.md errata 16).
//   tube (r, h), a spine wire inside a shell of mean radius r and wall thickness h:
//       A = 2 pi r h, I = pi r h (r^2 + h^2/4) (exact annulus), moduli E.
//   custom (A, I): moduli E.
#pragma once

#include "wirerig/runtime/material.h"
#include "wirerig/runtime/status.h"

namespace wirerig {

enum class SectionKind : int { kCustom = 0, kStrip = 1, kTube = 2 };

struct Section {
  SectionKind kind = SectionKind::kCustom;
  double area = 0.0;           // A > 0, m^2
  double second_moment = 0.0;  // I > 0, m^4
};

// Width b > 0 and thickness h > 0, metres, whose A and I are positive and finite.
Status ValidateStrip(double width, double thickness);
// Mean radius r > 0 and wall thickness 0 < h <= 2r (the inner radius r - h/2 is not negative),
// whose A and I are positive and finite.
Status ValidateTube(double mean_radius, double wall_thickness);

// Call only with arguments that pass the matching Validate*; the result then passes
// ValidateSection.
Section StripSection(double width, double thickness);
Section TubeSection(double mean_radius, double wall_thickness);
Section CustomSection(double area, double second_moment);

// A and I positive and finite, kind known.
Status ValidateSection(const Section& section);

struct WireStiffness {
  double axial = 0.0;    // EA, N
  double bending = 0.0;  // E_b I, N*m^2 with E_b = E/(1-nu^2) for strips, E otherwise
};

// Both arguments must be valid.
WireStiffness ComputeStiffness(const Material& material, const Section& section);

}  // namespace wirerig
