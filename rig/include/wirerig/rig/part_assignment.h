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
  // With RigDescription::clean_assignment: vertices of a child part far from its curve that went
  // to the nearest part seeing them (part_assignment.cpp), and vertices of islands that joined
  // the part around them (MergePartIslands).
  std::size_t far_vertices = 0;
  std::size_t island_vertices = 0;
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

// Islands of a part's skin (with RigDescription::clean_assignment). The nearest-curve assignment
// can leave a few of a part's vertices inside another part's skin (a patch of a camel's neck
// taken by a front leg whose curve passes just under it); such an island moves with its part
// while the skin around it follows another, and tears when the joint bends (the camel's
// shoulders stretched an edge 93x under every skinning method).
//
// Per (part, connected piece of the surface), the part's largest connected region there keeps
// its vertices; its other regions of at most kIslandFraction of that one are islands. Each joins
// the part that most edges leaving it reach, among the parts not `restricted` (they take no
// nearest-curve vertices: skinless, or claiming mesh parts by name) that are not its
// own part's descendants (`parent`: per part, -1 for the root): a parent's patches inside a
// child's skin say the child reaches too far, and giving them to the child would make it reach
// further (the man's head would take the torso's patches in its neck). Repeated until nothing
// moves. Islands with a `fixed` vertex (assigned by the user) stay. Returns how many vertices
// moved.
inline constexpr double kIslandFraction = 0.05;
std::size_t MergePartIslands(const std::vector<Triangle>& triangles, const std::vector<int>& parent,
                             const std::vector<bool>& fixed, const std::vector<bool>& restricted,
                             std::vector<int>* vertex_part);

}  // namespace wirerig
