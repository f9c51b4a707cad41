// BuildRig: the whole rig-building pipeline on an imported, welded mesh. Assigns vertices to
// parts, casts each part's profile curves, interpolates its spine, attaches children to their
// parents, and gives every wire a material and section:
//   profile wire: a strip of the skin, b = the spacing of the profiles, h = skin thickness;
//   spine wire: a tube of the part's mean profile radius r and wall h = skin thickness (<= 2r).
#pragma once

#include <string>
#include <vector>

#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/rig/profile_curves.h"
#include "wirerig/rig/rig.h"
#include "wirerig/rig/rig_description.h"

namespace wirerig {

struct RigBuildOptions {
  double skin_thickness = 0.005;  // m
  // Optional: a watertight stand-in of an open mesh (AutomaticDescription::wrap); profile rays
  // escaping through the mesh's holes take its hit (ProfileRequest::wrap_bvh).
  const Mesh* wrap = nullptr;
  // A part fewer than 2 of whose profiles hit the surface is dropped (its skin and its children
  // go to its parent; a warning says so) instead of failing the rig: for automatic
  // descriptions, whose small parts (an eyelid bone, a spur) may miss the surface. A root that
  // misses gives its place, skin and other children to its child with the largest subtree.
  bool drop_parts_without_profiles = false;
};

struct PartReport {
  std::string name;
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  ProfileDiagnostics profiles;
};

struct RigBuildReport {
  std::vector<PartReport> parts;
  std::size_t occluded_fallbacks = 0;  // vertices no central curve could see
  std::vector<std::string> warnings;   // human-readable, one per problem found
  std::vector<std::string> notes;      // what the builder repaired, for the modeller; no problem
};

struct BuiltRig {
  Rig rig;
  RigBuildReport report;
};

// `mesh_path` is recorded in the rig. Errors name the part at fault.
Result<BuiltRig> BuildRig(const Mesh& mesh, const RigDescription& description,
                          const std::string& mesh_path, const RigBuildOptions& options = {});

}  // namespace wirerig
