#include "wirerig/rig/joint_skin_report.h"

#include <algorithm>
#include <cmath>

#include "wirerig/rig/joint_sweep.h"

namespace wirerig {
namespace {

constexpr double kSectionRadius = 1.6;

// Flags the vertices of part `c`'s side of its joint: its subtree's and its bridge's.
std::vector<std::uint8_t> LimbSide(const RigModel& model, std::size_t c) {
  std::vector<std::uint8_t> in_subtree(model.parts.size(), 0);
  in_subtree[c] = 1;
  for (std::size_t i = c + 1; i < model.parts.size(); ++i)
    if (model.parts[i].parent >= 0 && in_subtree[std::size_t(model.parts[i].parent)])
      in_subtree[i] = 1;
  std::vector<std::uint8_t> out(model.vertices.size(), 0);
  for (std::size_t v = 0; v < model.vertices.size(); ++v) {
    const VertexAttachment& a = model.vertices[v];
    out[v] = in_subtree[a.part] || a.OnJoint(int(c));
  }
  return out;
}

// The region's border: its vertices on a triangle that leaves it.
std::vector<std::uint32_t> Border(const std::vector<std::uint8_t>& region,
                                  const std::vector<Triangle>& triangles) {
  std::vector<std::uint8_t> border(region.size(), 0);
  for (const Triangle& t : triangles) {
    const int inside = region[t[0]] + region[t[1]] + region[t[2]];
    if (inside == 0 || inside == 3) continue;
    for (std::uint32_t v : t) border[v] |= region[v];
  }
  std::vector<std::uint32_t> out;
  for (std::size_t v = 0; v < border.size(); ++v)
    if (border[v]) out.push_back(std::uint32_t(v));
  return out;
}

Vec3 MeanOf(std::span<const Vec3> positions, const std::vector<std::uint32_t>& vertices) {
  Vec3 sum = Vec3::Zero();
  for (std::uint32_t v : vertices) sum += positions[v];
  return vertices.empty() ? sum : Vec3(sum / double(vertices.size()));
}

// The region's volume is closed by the cone to the middle of its border (a nearly flat cap
// across the limb where it meets the body), in each configuration.
SkinMeasures Measure(const SkinQualityReference& reference, std::span<const Vec3> rest,
                     std::span<const Vec3> posed, const std::vector<CrossSection>& sections,
                     const std::vector<std::uint8_t>& limb,
                     const std::vector<std::uint32_t>& border,
                     const std::vector<Triangle>& triangles) {
  const Vec3 rest_apex = MeanOf(rest, border), apex = MeanOf(posed, border);
  SkinMeasures m;
  const SkinQuality q = MeasureSkin(reference, posed);
  m.folded_edges = q.folded_edges;
  m.worst_stretch = q.worst_stretch;
  const double rest_volume = RegionVolume(rest, triangles, limb, rest_apex);
  m.volume_ratio =
      rest_volume != 0.0 ? RegionVolume(posed, triangles, limb, apex) / rest_volume : 1.0;
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
    const std::vector<std::uint8_t> limb = LimbSide(model, c);
    const std::vector<std::uint32_t> border = Border(limb, model.triangles);
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
      row.methods[0] = Measure(reference, rest, posed, sections, limb, border, model.triangles);
      BoneMatricesFromWorkspace(model, workspace, bones);
      std::vector<Vec3> other(n);
      for (int m = 1; m < kSkinMethods; ++m) {
        ReferenceSkinningJob skinning{ReferenceSkinning(m - 1), &skin, bones, x, y, z, nx, ny, nz};
        skinning.Run();
        for (std::size_t v = 0; v < n; ++v) other[v] = Vec3(x[v], y[v], z[v]);
        row.methods[std::size_t(m)] =
            Measure(reference, rest, other, sections, limb, border, model.triangles);
      }
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

}  // namespace wirerig
