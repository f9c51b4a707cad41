// A rig description from an asset's own skeleton (Mesh::joints and skin weights): one part per
// bone, so a skinned arm keeps its shoulder, elbow and wrist.
//
// Bones. Joint j's bone runs from j to the child that continues its chain: its only child, or
// of several the one whose direction is most aligned with the bone coming into j (a neck
// rather than a clavicle), or at a root the one leading the largest subtree (most joints, then
// most skinned vertices). Its other children are side branches whose parts hang from j's part.
// A leaf bone (fingertip, tail tip, head) runs from j along the bone coming into it to the
// farthest vertex skinned to it, so it gets the length its skin has. A leaf without a parent
// runs along its bind orientation's bone axis: the local axis (+-X, +-Y or +-Z) along which the
// file's other bones point from their parents, or when no bone shows it, the bind axis nearest
// the direction from the joint to its vertices.
//
// Parts. Every bone with a length (at least 1e-3 of the mesh's diagonal) and skinned vertices
// (vertices whose largest weight is its joint) is a part named after its joint (made unique;
// "bone_<index>" when empty), its central curve the bone. Other bones (no vertices: helper and
// end joints; no length: coincident pivots) merge into their parent's part: their vertices go
// to it, and when such a bone continues the parent's chain, the parent's curve runs on along it.
// A bone without a parent that merges is dropped (its vertices are left to the nearest curve).
// When several trees remain, the one with the most vertices is the root and every other tree
// hangs from the part nearest its root joint among the trees placed before it.
//
// Joints. Each part's joint is a ball with no limits (Mesh::Joint has none); its axis is the
// bone's bind X axis, or its bind Z axis when X runs along the bone (within 45 degrees; files
// whose bones point along X), or unset (the bone's rest normal) when both do.
//
// vertex_part: every welded vertex goes to the part of its joint of largest weight, through the
// merges; -1 (the nearest visible curve, part_assignment.h) when no kept part takes it.
#pragma once

#include "wirerig/io/result.h"
#include "wirerig/rig/mesh.h"
#include "wirerig/rig/rig_description.h"

namespace wirerig {

// Errors: "the mesh has no skeleton", "the mesh's skeleton has no skin weights", "joint N
// ('name'): its parent must come before it", "joint N ('name'): its bind transform is not
// finite", "the skeleton has no bone with both a length and skinned vertices".
Result<RigDescription> DescribeFromSkeleton(const Mesh& mesh);

}  // namespace wirerig
