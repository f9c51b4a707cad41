#include "joint_region.h"

#include <algorithm>

namespace wirerig {
namespace {

constexpr double kSectionRadius = 1.6;  // limb radii

}  // namespace

JointRegion MakeJointRegion(const RigModel& model, std::size_t c, std::span<const Vec3> rest,
                            const SkinQualityReference& reference,
                            std::span<const std::uint32_t> surface_border) {
  const PartModel& part = model.parts[c];
  const JointModel& joint = part.joint;
  const Vec3 centre = part.spine_points.front(), axis = joint.axes.col(2);
  const double h = joint.blend_length > 0.0 ? joint.blend_length : 2.0 * joint.radius;
  JointRegion region;
  for (double s : {-0.5, -0.25, 0.0, 0.25, 0.5, 0.75})
    region.sections.push_back(MakeCrossSection(rest, reference, centre + s * h * axis, axis,
                                               kSectionRadius * joint.radius));
  region.limb = LimbOf(model, c, surface_border);
  return region;
}

SkinMeasures MeasureJointRegion(const SkinQualityReference& reference, std::span<const Vec3> rest,
                                std::span<const Vec3> posed, const JointRegion& region,
                                std::span<const Triangle> triangles) {
  SkinMeasures m;
  const SkinQuality q = MeasureSkin(reference, posed);
  m.folded_edges = q.folded_edges;
  m.worst_stretch = q.worst_stretch;
  m.volume_ratio = LimbVolumeRatio(region.limb, rest, posed, triangles);
  for (const CrossSection& s : region.sections) {
    const double r = CrossSectionPerimeter(s, rest);
    if (r > 0.0)
      m.smallest_perimeter = std::min(m.smallest_perimeter, CrossSectionPerimeter(s, posed) / r);
  }
  return m;
}

}  // namespace wirerig
