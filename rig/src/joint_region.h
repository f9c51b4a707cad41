// The skin a joint moves and how it is judged: the limb on the child's side (limb_volume.h) and
// six cross-sections across the joint (at -h/2 ... 3h/4 along the bone, h the bridge's
// half-length; the surface within 1.6 limb radii of the bone line). Shared by the joint-skin
// report and the bridge's growth fit.
#pragma once

#include <span>
#include <vector>

#include "limb_volume.h"
#include "wirerig/rig/joint_skin_report.h"
#include "wirerig/rig/skin_quality.h"

namespace wirerig {

struct JointRegion {
  Limb limb;
  std::vector<CrossSection> sections;
};

// Part `c`'s joint region. `surface_border`: SurfaceBorder(model.triangles).
JointRegion MakeJointRegion(const RigModel& model, std::size_t c, std::span<const Vec3> rest,
                            const SkinQualityReference& reference,
                            std::span<const std::uint32_t> surface_border);

// Folded edges and worst stretch over the whole mesh, the limb's volume ratio and the smallest
// cross-section perimeter ratio of `posed` against `rest`.
SkinMeasures MeasureJointRegion(const SkinQualityReference& reference, std::span<const Vec3> rest,
                                std::span<const Vec3> posed, const JointRegion& region,
                                std::span<const Triangle> triangles);

}  // namespace wirerig
