// Midpoint subdivision: every triangle split 1-to-4 at its edge midpoints (flat: positions do
// not move, so the surface keeps its shape and a coarse mesh gains vertices where wires can
// bend it, e.g. a low-polygon car roof). Render vertices: an edge's midpoint is shared by the
// triangles on both sides of it; normals are averaged and renormalized, UVs averaged, skin
// influences taken from the edge's first vertex. Parts keep contiguous triangle ranges (a
// triangle's four children follow each other). The weld is rebuilt (WeldByPosition, exact).
#pragma once

#include "wirerig/rig/mesh.h"

namespace wirerig {

// `levels` times; each level multiplies the triangles by 4. Levels above 6 are refused by the
// callers that read them from files (4^6 = 4096 triangles per triangle).
Mesh SubdivideMidpoint(const Mesh& mesh, int levels);

}  // namespace wirerig
