// Which part each welded vertex and triangle of a mesh belongs to.
//
// In order of precedence: the description's vertex_part (from skin weights); the mesh parts a
// part lists by name (mesh_parts); otherwise the nearest visible central curve. "Visible" is
// the junction rule: a vertex goes to a curve only if the straight segment from the curve to
// the vertex stays inside the mesh (so an arm never takes hip vertices across the air gap),
// and to a child part whose closest point is the child's root end only when no other curve
// sees the vertex (so an arm does not take torso vertices behind the shoulder).
#pragma once

#include <cstdint>
#include <vector>

#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/rig/rig_description.h"
#include "wirerig/rig/triangle_bvh.h"

namespace wirerig {

struct PartAssignment {
  std::vector<int> vertex_part;    // #W welded vertex -> part
  std::vector<int> triangle_part;  // #F triangle -> part (majority of its vertices)
  // part -> its ray-target triangles (all of its triangles but those of passive mesh parts)
  std::vector<std::vector<std::uint32_t>> part_triangles;
  std::size_t occluded_fallbacks = 0;  // vertices no curve could see: went to the nearest
};

// passive[f]: triangle f belongs to one of the description's passive mesh parts. Errors name
// a passive mesh part the mesh does not have.
Result<std::vector<bool>> FindPassiveTriangles(const Mesh& mesh, const RigDescription& description);

// The indices of the triangles that are not passive.
std::vector<std::uint32_t> ActiveTriangles(const std::vector<bool>& passive);

// `active_bvh` is built over mesh.welded_positions / mesh.welded_triangles restricted to the
// active triangles; `passive` comes from FindPassiveTriangles.
Result<PartAssignment> AssignParts(const Mesh& mesh, const RigDescription& description,
                                   const TriangleBvh& active_bvh, const std::vector<bool>& passive);

}  // namespace wirerig
