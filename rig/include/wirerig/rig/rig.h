// Rig: what rig building produces and rig files hold. Per part: its central curve, profile
// curves (with the frames of their planes) and spine (the curve through the profile
// centroids), with material and section per wire; the part hierarchy with attachment
// parameters; and which part every welded mesh vertex belongs to.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "wirerig/rig/joint_description.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/rig/profile_curves.h"
#include "wirerig/runtime/material.h"
#include "wirerig/runtime/section.h"

namespace wirerig {

struct WireProperties {
  Material material;
  Section section;
};

struct RigPart {
  std::string name;
  int parent = -1;          // index into Rig::parts (parents come first), -1 for the root
  double attachment = 0.0;  // v on the parent's spine nearest this part's first spine point
  std::vector<Vec3> central_curve;
  int profile_count = 0;
  int points_per_profile = 0;
  std::vector<ProfileCurve> profiles;         // the profiles that hit the surface, in order
  std::vector<WireProperties> profile_wires;  // one per profile
  std::vector<Vec3> spine_points;  // profile centroids; the spine interpolates them (C2 cubic)
  WireProperties spine_wire;
  JointDescription joint;  // how it turns on its parent
  // false: a skinless bone (rig_description.h): profile_count 0, no profiles, its spine the 2
  // points of its central curve, no vertices.
  bool skin = true;
};

struct Rig {
  static constexpr int kFormatVersion = 1;

  std::string mesh;               // the mesh file, as given when the rig was built
  ImportOptions import;           // up axis / unit overrides used to import it
  std::size_t mesh_vertices = 0;  // welded vertices: a rig fits only a mesh with these counts
  std::size_t mesh_triangles = 0;
  std::vector<RigPart> parts;
  std::vector<int> vertex_part;  // #W welded vertex -> part index
};

}  // namespace wirerig
