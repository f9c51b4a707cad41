// The welded vertices of a rig model for one set of poses, through EvaluateRigJob with a fresh
// workspace: for tests that look at a pose, not at the job's API. A failed job fails the test.
#pragma once

#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "wirerig/runtime/rig_evaluation.h"

namespace wirerig::testing {

inline std::vector<Vec3> EvaluatePose(const RigModel& model, std::span<const PartPose> poses,
                                      bool preserve_volume = false) {
  RigWorkspace workspace = MakeRigWorkspace(model);
  std::vector<Vec3> positions(model.vertices.size());
  EvaluateRigJob job;
  job.model = &model;
  job.poses = poses;
  job.workspace = &workspace;
  job.positions = positions;
  job.preserve_volume = preserve_volume;
  const Status status = job.Run();
  EXPECT_TRUE(status.ok()) << ToString(status);
  return positions;
}

}  // namespace wirerig::testing
