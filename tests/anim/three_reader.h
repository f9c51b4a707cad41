// three.js as an independent reader of wirerig's glTF exports: runs
// scripts/three_skinned_positions.mjs (three's GLTFLoader and AnimationMixer under node, as
// scripts/setup.sh installs them) and parses the world positions it prints.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "wirerig/runtime/conventions.h"

namespace wirerig::testing {

// A mesh as three.js draws it: every vertex of its POSITION accessor, in accessor order.
struct ThreeMesh {
  std::string name;
  bool skinned = false;
  std::size_t morph_targets = 0;
  std::size_t primitives = 0;     // three.js meshes sharing the accessor (one per glTF primitive)
  double primitive_spread = 0.0;  // m, largest disagreement between those primitives
  std::vector<std::vector<Vec3>> positions;  // per requested time, #V world positions, m
};

struct ThreePlayback {
  std::string error;      // empty on success; else why node or three.js could not read the file
  std::string revision;   // three.js's REVISION, e.g. "187"
  std::string animation;  // the animation played (the file's first), empty if none
  std::vector<ThreeMesh> meshes;
};

// Plays `file` with three.js at `times` (s). Node or three.js missing is an error that says to
// run scripts/setup.sh: the callers fail on it, never skip.
ThreePlayback PlayWithThree(const std::filesystem::path& file, const std::vector<double>& times);

}  // namespace wirerig::testing
