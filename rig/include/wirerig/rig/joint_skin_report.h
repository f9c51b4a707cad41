// The joint-skin report: every joint of a rig bent alone through its sweep (joint_sweep.h), the
// skin measured (skin_quality.h) for the wire rig and for the skinning engines ship
// (reference_skinning.h) on the same bones, weights and poses.
//
// Per joint and pose: folded edges and the worst stretch over the whole mesh; the volume of the
// limb (the child's side: its vertices, its descendants' and the bridge's, closed by the cone to
// the middle of the region's border) against rest; the smallest ratio of a cross-section's
// perimeter to rest over six planes across the joint (at -h/2 ... 3h/4 along the bone, h the
// bridge's half-length; the surface within 1.6 limb radii of the bone line).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "wirerig/rig/reference_skinning.h"
#include "wirerig/rig/skin_quality.h"

namespace wirerig {

struct SkinMeasures {
  std::size_t folded_edges = 0;
  double worst_stretch = 1.0;
  double volume_ratio = 1.0;        // posed / rest
  double smallest_perimeter = 1.0;  // posed / rest
  // Merges another pose's measures into worst-case ones.
  void Worst(const SkinMeasures& other);
};

// The deformers compared: the wire rig, then ReferenceSkinning's methods in their order.
inline constexpr int kSkinMethods = 4;
const char* SkinMethodName(int method);  // "wire rig", "linear blend", ...

struct JointSkinRow {
  std::string joint;  // the child part's name
  std::string pose;   // JointSweepPose::label
  std::array<SkinMeasures, kSkinMethods> methods;
};

// `joints`: the child parts to sweep (empty: every part with a parent whose joint can turn).
// Every part is evaluated at its rest pose but the swept joint (rigid motion only).
std::vector<JointSkinRow> MeasureJointSweep(const RigModel& model, std::span<const Vec3> rest,
                                            std::span<const std::size_t> joints = {});

}  // namespace wirerig
