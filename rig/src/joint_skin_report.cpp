#include "wirerig/rig/joint_skin_report.h"

#include <algorithm>
#include <cmath>

#include "joint_region.h"
#include "wirerig/rig/joint_sweep.h"
#include "wirerig/rig/skin_quality.h"

namespace wirerig {

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
    const JointRegion region = MakeJointRegion(model, c, rest, reference, surface_border);
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
      row.methods[0] = MeasureJointRegion(reference, rest, posed, region, model.triangles);
      BoneMatricesFromWorkspace(model, workspace, bones);
      std::vector<Vec3> other(n);
      for (int m = 1; m < kSkinMethods; ++m) {
        ReferenceSkinningJob skinning{ReferenceSkinning(m - 1), &skin, bones, x, y, z, nx, ny, nz};
        skinning.Run();
        for (std::size_t v = 0; v < n; ++v) other[v] = Vec3(x[v], y[v], z[v]);
        row.methods[std::size_t(m)] =
            MeasureJointRegion(reference, rest, other, region, model.triangles);
      }
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

}  // namespace wirerig
