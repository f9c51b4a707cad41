// A procedural octopus (paper Fig. 13): an egg-shaped mantle standing on +Y and
// `tentacle_count` tapered tentacles leaving its underside, spread evenly around it, curving
// outwards and down. Each piece is a closed, outward-facing tube (mesh parts "mantle",
// "tentacle_0", ...), and the rig description that goes with it: the mantle is the root part,
// each tentacle a child with its own central curve, restricted to its own mesh part.
#pragma once

#include "wirerig/rig/mesh.h"
#include "wirerig/rig/rig_description.h"

namespace wirerig {

struct OctopusParameters {
  double mantle_radius = 0.22;     // m, widest radius of the mantle
  double mantle_height = 0.5;      // m
  int tentacle_count = 8;          // >= 1
  double tentacle_length = 1.0;    // m, along the tentacle's centre line
  double tentacle_radius = 0.055;  // m, at the root
  double tip_radius = 0.008;       // m, at the tip (< tentacle_radius)
  double spread = 0.55;            // how far the tentacles reach outwards, in [0, 1]
  int radial_segments = 24;        // vertices around every ring
  int rings = 40;                  // rings along each piece
  int profile_count = 14;          // profile curves per tentacle (the mantle gets 12)
  int points_per_profile = 24;
};

struct ProceduralRigSource {
  Mesh mesh;
  RigDescription description;
};

// Empty when valid, else "<field>: <reason>".
std::string ValidateOctopusParameters(const OctopusParameters& parameters);

// Validates the parameters; the error names the field.
Result<ProceduralRigSource> MakeOctopus(const OctopusParameters& parameters = {});

}  // namespace wirerig
