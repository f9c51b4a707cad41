// The quality report of a built rig, for every rig `wirerig rig` makes: how much of the mesh is
// bound, which profiles cross or leave the surface, which parts have no profiles, and a one-line
// verdict.
#pragma once

#include <string>
#include <vector>

#include "wirerig/rig/rig_builder.h"

namespace wirerig {

struct RigQuality {
  std::size_t vertices = 0;           // welded vertices of the mesh
  std::size_t bound_vertices = 0;     // those a part follows
  std::size_t profiles = 0;           // kept profile curves over all parts
  std::size_t crossing_profiles = 0;  // that cross themselves, or pairs that cross a neighbour
  std::size_t escaped_rays = 0;       // rays that left the surface and met nothing
  std::size_t dropped_profiles = 0;   // origin outside the part, or fewer than 2 hits
  std::vector<std::string> parts_without_profiles;  // fewer than 2 profiles: no wires
  std::size_t warnings = 0;                         // the build report's warnings
  // "good" (no warning), "usable" (every vertex bound, every part with profiles, under 10% of
  // its profiles crossing), else "poor"; then the main reasons.
  std::string verdict;
};

RigQuality AssessRig(const BuiltRig& built);

}  // namespace wirerig
