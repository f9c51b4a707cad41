// Skin quality: what a viewer sees of a deformed mesh against its rest shape (issue targets for
// skin at joints), for any deformer (wire rig, linear blend, dual quaternions, ...):
//   folded edges: interior edges whose two triangles' normals were within 60 degrees at rest
//     and are more than 120 degrees apart after deformation (a flap or a tear);
//   stretch: the largest edge length over its rest length;
//   volume of a region: the signed volume of a set of triangles closed by the cone to a point;
//   change of volume of a surface: exact (divergence theorem) while its border stays put;
//   perimeter of a cross-section: the loop where a rest plane cuts the surface, followed as
//     material points (edge, fraction) into the deformed mesh.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "wirerig/runtime/conventions.h"

namespace wirerig {

// Edge adjacency and rest measures of a mesh, made once.
struct SkinQualityReference {
  struct Edge {
    std::uint32_t a = 0, b = 0;         // vertices
    std::uint32_t left = 0, right = 0;  // triangles; right == left for a border edge
    double rest_length = 0.0;
    bool smooth = false;  // interior, with the two rest normals within 60 degrees
  };
  std::vector<Edge> edges;
  std::span<const Triangle> triangles;
};
SkinQualityReference MakeSkinQualityReference(std::span<const Vec3> rest,
                                              std::span<const Triangle> triangles);

struct SkinQuality {
  std::size_t folded_edges = 0;
  double worst_stretch = 1.0;
};
// `only`: when not empty, one flag per vertex; edges with a vertex not flagged are skipped.
SkinQuality MeasureSkin(const SkinQualityReference& reference, std::span<const Vec3> positions,
                        std::span<const std::uint8_t> only = {});

// Signed volume of the triangles whose three vertices are flagged, closed by the cone to
// `apex` (positive for outward triangles around the apex), m^3.
double RegionVolume(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                    std::span<const std::uint8_t> flagged, const Vec3& apex);

// The vertices of the edges not on exactly two triangles (a surface's holes and seams), sorted.
std::vector<std::uint32_t> SurfaceBorder(std::span<const Triangle> triangles);

// The change of the volume the surface encloses from `rest` to `posed`, m^3: exact for a closed
// surface, or one whose `border` (SurfaceBorder) stays within 1e-9 of the rest surface's
// bounding diagonal of its rest place; nullopt when the border moved (the change would depend
// on how the holes are capped).
std::optional<double> SurfaceVolumeChange(std::span<const Vec3> rest, std::span<const Vec3> posed,
                                          std::span<const Triangle> triangles,
                                          std::span<const std::uint32_t> border);

// A cross-section of the rest surface: where the plane through `point` with unit `normal` cuts
// the edges with both ends within `radius` of `point`, ordered by angle about the normal.
struct CrossSection {
  struct Cut {
    std::uint32_t a = 0, b = 0;
    double t = 0.0;  // the point (1 - t) a + t b
  };
  std::vector<Cut> cuts;
};
CrossSection MakeCrossSection(std::span<const Vec3> rest, const SkinQualityReference& reference,
                              const Vec3& point, const Vec3& normal, double radius);
// The closed loop's length through the cuts' material points in `positions`, m.
double CrossSectionPerimeter(const CrossSection& section, std::span<const Vec3> positions);

}  // namespace wirerig
