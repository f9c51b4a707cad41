// Procedural meshes for analytic tests and samples. Closed, outward-oriented, welded, one
// part each, metres; their axis is +Y from the origin unless stated.
#pragma once

#include <string>
#include <vector>

#include "wirerig/rig/mesh.h"

namespace wirerig {

// Cylinder of `radius` from y = 0 to y = height, capped with fans at both ends.
Mesh MakeCylinder(double radius, double height, int radial_segments, int height_segments);
// Cone frustum with radius r0 at y = 0 and r1 at y = height (r1 may be 0: a pointed cone).
Mesh MakeCone(double r0, double r1, double height, int radial_segments, int height_segments);
// Torus around the Y axis in the XZ plane: core radius R, tube radius r.
Mesh MakeTorus(double major_radius, double minor_radius, int ring_segments, int tube_segments);
// Capsule: a cylinder of `radius` and `height` (y = 0 .. height) with hemispherical ends.
Mesh MakeCapsule(double radius, double height, int radial_segments, int height_segments,
                 int cap_rings);

// A closed tube swept along a curve: ring k of `radial_segments` vertices sits at `centres[k]`
// in the plane normal to the curve (rotation-minimizing frames), with radius `radii[k]`; a
// radius of 0 at the first or last centre closes that end with a pole. Rings in between must
// have positive radii. One part named `name`. Needs at least 2 centres (3 with poles),
// consecutive centres distinct; returns an empty mesh otherwise.
Mesh MakeSweptTube(const std::vector<Vec3>& centres, const std::vector<double>& radii,
                   int radial_segments, const std::string& name);

// Appends `piece` to `mesh` as new parts (indices shifted; render and welded sets both),
// keeping the weld of each piece; pieces do not weld to each other.
void AppendMesh(Mesh& mesh, const Mesh& piece);

}  // namespace wirerig
