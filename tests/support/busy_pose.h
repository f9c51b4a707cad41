// A pose that exercises every stage of EvaluateRigJob on a many-part rig (the human): every
// part turned, bent and (with volume preservation) stretched, the root moved, and the first
// part's profiles loaded. Evaluate with preserve_volume = true.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig::testing {

struct BusyPose {
  std::vector<PartPose> poses;
  std::vector<std::array<PointLoad, 1>> bends;
  std::vector<std::array<AxialPointLoad, 1>> pulls;
  std::vector<std::array<LineLoad, 1>> pushes;
  std::vector<ProfileLoads> profile_loads;
};

inline BusyPose MakeBusyPose(const RigModel& model) {
  BusyPose b;
  const std::size_t parts = model.parts.size();
  b.poses.resize(parts);
  b.bends.resize(parts);
  b.pulls.resize(parts);
  for (std::size_t i = 0; i < parts; ++i) {
    const PartModel& part = model.parts[i];
    const double x = double(i);
    b.poses[i].rotation = Quat(Eigen::AngleAxisd(
        0.1 + 0.03 * x, Vec3(std::sin(1.7 * x + 0.3), std::cos(1.1 * x), 0.5).normalized()));
    const double force = 0.05 * part.spine_stiffness.bending / std::pow(part.spine_length, 3);
    b.bends[i] = {{{0.7, Vec3(force, -0.5 * force, 0.0)}}};
    b.pulls[i] = {{{1.0, 0.05 * part.spine_stiffness.axial}}};
    b.poses[i].loads.bending_point_loads = b.bends[i];
    b.poses[i].loads.axial_point_loads = b.pulls[i];
  }
  b.poses[0].translation = Vec3(0.1, -0.2, 0.3);
  const PartModel& first = model.parts[0];
  b.pushes.reserve(first.profiles.size());
  for (std::uint32_t p = 1; p + 1 < first.profiles.size(); p += 2) {
    const double q = 1e-3 * first.profiles[p].stiffness.bending;
    b.pushes.push_back({{{0.0, 1.0, Vec3(q, 0, 0)}}});
    b.profile_loads.push_back(
        {0, p, 0.1, 0.6, BoundaryCondition::kClamped, {}, b.pushes.back(), {}});
  }
  return b;
}

// The busy pose evaluated in float into an interleaved buffer (position and normal of a vertex
// side by side, stride 6; -7 where nothing was written), volume kept, on `parallel` (may be
// null), eight lanes where allowed and the CPU has AVX2.
inline std::vector<float> EvaluateBusyInterleaved(const RigModel& model, const BusyPose& pose,
                                                  const ParallelFor* parallel, bool allow_avx2,
                                                  NormalMode mode = NormalMode::kFromTriangles) {
  RigWorkspace workspace = MakeRigWorkspace(model);
  std::vector<float> buffer(6 * model.vertices.size(), -7.0f);
  EvaluateRigJob job;
  job.model = &model;
  job.poses = pose.poses;
  job.profile_loads = pose.profile_loads;
  job.workspace = &workspace;
  job.float_positions = buffer;
  job.float_position_stride = 6;
  job.float_normals = std::span<float>(buffer).subspan(3);
  job.float_normal_stride = 6;
  job.preserve_volume = true;
  job.parallel = parallel;
  job.allow_avx2 = allow_avx2;
  job.normal_mode = mode;
  const Status status = job.Run();
  EXPECT_TRUE(status.ok()) << ToString(status);
  return buffer;
}

}  // namespace wirerig::testing
