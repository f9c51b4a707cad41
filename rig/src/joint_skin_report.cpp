#include "wirerig/rig/joint_skin_report.h"

#include <algorithm>
#include <cmath>

#include "limb_volume.h"
#include "wirerig/rig/joint_sweep.h"
#include "wirerig/rig/skin_quality.h"

namespace wirerig {
namespace {

constexpr double kSectionRadius = 1.6;

SkinMeasures Measure(const SkinQualityReference& reference, std::span<const Vec3> rest,
                     std::span<const Vec3> posed, const std::vector<CrossSection>& sections,
                     const Limb& limb, const std::vector<Triangle>& triangles) {
  SkinMeasures m;
  const SkinQuality q = MeasureSkin(reference, posed);
  m.folded_edges = q.folded_edges;
  m.worst_stretch = q.worst_stretch;
  m.volume_ratio = LimbVolumeRatio(limb, rest, posed, triangles);
  for (const CrossSection& s : sections) {
    const double r = CrossSectionPerimeter(s, rest);
    if (r > 0.0)
      m.smallest_perimeter = std::min(m.smallest_perimeter, CrossSectionPerimeter(s, posed) / r);
  }
  return m;
}

}  // namespace

void SkinMeasures::Worst(const SkinMeasures& other) {
  folded_edges = std::max(folded_edges, other.folded_edges);
  worst_stretch = std::max(worst_stretch, other.worst_stretch);
  if (std::abs(other.volume_ratio - 1.0) > std::abs(volume_ratio - 1.0))
    volume_ratio = other.volume_ratio;
  smallest_perimeter = std::min(smallest_perimeter, other.smallest_perimeter);
}

const char* SkinMethodName(int method) {
  return method == 0 ? "wire rig" : ToString(ReferenceSkinning(method - 1));
}

std::vector<JointSkinRow> MeasureJointSweep(const RigModel& model, std::span<const Vec3> rest,
                                            std::span<const std::size_t> joints) {
  std::vector<std::size_t> chosen(joints.begin(), joints.end());
  if (chosen.empty())
    for (std::size_t c = 1; c < model.parts.size(); ++c) chosen.push_back(c);
  const SkinQualityReference reference = MakeSkinQualityReference(rest, model.triangles);
  const ReferenceSkin skin = MakeReferenceSkin(model, rest);
  RigWorkspace workspace = MakeRigWorkspace(model);
  const std::size_t n = rest.size();
  std::vector<Vec3> posed(n);
  std::vector<float> x(n), y(n), z(n), nx(n), ny(n), nz(n);
  std::vector<BoneMatrix> bones(model.parts.size());
  const std::vector<std::uint32_t> surface_border = SurfaceBorder(model.triangles);
  std::vector<JointSkinRow> rows;
  for (std::size_t c : chosen) {
    const PartModel& part = model.parts[c];
    const JointModel& joint = part.joint;
    const Vec3 centre = part.spine_points.front(), axis = joint.axes.col(2);
    const double h = joint.blend_length > 0.0 ? joint.blend_length : 2.0 * joint.radius;
    std::vector<CrossSection> sections;
    for (double s : {-0.5, -0.25, 0.0, 0.25, 0.5, 0.75})
      sections.push_back(MakeCrossSection(rest, reference, centre + s * h * axis, axis,
                                          kSectionRadius * joint.radius));
    const Limb limb = LimbOf(model, c, surface_border);
    for (const JointSweepPose& pose : JointSweep(joint)) {
      std::vector<PartPose> poses(model.parts.size());
      poses[c].rotation = JointRotation(joint, pose.degrees);
      EvaluateRigJob job;
      job.model = &model;
      job.poses = poses;
      job.workspace = &workspace;
      job.positions = posed;
      if (!job.Run()) continue;
      JointSkinRow row{part.name, pose.label, {}};
      row.methods[0] = Measure(reference, rest, posed, sections, limb, model.triangles);
      BoneMatricesFromWorkspace(model, workspace, bones);
      std::vector<Vec3> other(n);
      for (int m = 1; m < kSkinMethods; ++m) {
        ReferenceSkinningJob skinning{ReferenceSkinning(m - 1), &skin, bones, x, y, z, nx, ny, nz};
        skinning.Run();
        for (std::size_t v = 0; v < n; ++v) other[v] = Vec3(x[v], y[v], z[v]);
        row.methods[std::size_t(m)] =
            Measure(reference, rest, other, sections, limb, model.triangles);
      }
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

}  // namespace wirerig
