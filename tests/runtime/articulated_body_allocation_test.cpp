// Proves that ArticulatedStepJob::Run() never allocates, with both integrators and every force:
// global operator new is replaced by one that counts (the technique of no_allocation_test.cpp),
// so this is a binary of its own.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include "wirerig/runtime/articulated_body.h"

#include "support/counting_allocator.h"

using wirerig::testing::g_allocations;

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(ArticulatedNoAllocation, CountingAllocatorSeesAllocations) {
  EXPECT_GE(testing::CountedAllocationsOfAHeapVector(), 2);
}

TEST(ArticulatedNoAllocation, StepsWithBothIntegratorsAndEveryForce) {
  // A floating torso with a ball-jointed arm (limited, tracked), a hinged forearm (limited,
  // damped), a welded hand; gravity and an external wrench.
  std::vector<ArticulatedBodyDesc> bodies(4);
  bodies[0].joint = ArticulatedJointType::kFloating;
  bodies[0].mass = 5.0;
  bodies[0].inertia = Vec3(0.1, 0.08, 0.12).asDiagonal();
  bodies[1].parent = 0;
  bodies[1].joint = ArticulatedJointType::kBall;
  bodies[1].joint_position = Vec3(0.2, 0.3, 0.0);
  bodies[1].center_of_mass = Vec3(0.0, -0.15, 0.0);
  bodies[1].inertia = Vec3(0.01, 0.002, 0.01).asDiagonal();
  bodies[1].min_degrees = Vec3(-10.0, -10.0, -10.0);
  bodies[1].max_degrees = Vec3(10.0, 10.0, 10.0);
  bodies[1].damping = 0.1;
  bodies[2].parent = 1;
  bodies[2].joint = ArticulatedJointType::kHinge;
  bodies[2].joint_position = Vec3(0.0, -0.3, 0.0);
  bodies[2].center_of_mass = Vec3(0.0, -0.12, 0.0);
  bodies[2].inertia = Vec3(0.008, 0.001, 0.008).asDiagonal();
  bodies[2].min_degrees.x() = 0.0;
  bodies[2].max_degrees.x() = 5.0;
  bodies[2].damping = 0.05;
  bodies[3].parent = 2;
  bodies[3].joint = ArticulatedJointType::kFixed;
  bodies[3].joint_position = Vec3(0.0, -0.25, 0.0);
  bodies[3].mass = 0.3;
  bodies[3].inertia = Vec3(0.001, 0.001, 0.001).asDiagonal();
  ArticulatedModel model;
  ASSERT_TRUE(ArticulatedModel::Build(bodies, &model).ok());
  std::vector<JointTarget> targets(4);
  targets[1].rotation = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitX()));
  targets[1].stiffness = 30.0;
  targets[1].damping = 1.0;
  targets[2].angle = 0.3;
  targets[2].stiffness = 10.0;
  targets[2].damping = 0.5;
  const std::vector<ExternalWrench> wrenches = {
      {2, Vec3(1.0, 0.0, 0.0), Vec3(0.1, 0.2, 0.0), Vec3(0.0, 0.1, 0.0)}};
  for (ArticulatedIntegrator integrator :
       {ArticulatedIntegrator::kSemiImplicitEuler, ArticulatedIntegrator::kRk4}) {
    ArticulatedState state = MakeArticulatedState(model);
    state.joints[0].angular_velocity = Vec3(0.5, 1.0, -0.3);
    state.joints[1].angular_velocity = Vec3(3.0, -2.0, 1.0);
    ArticulatedWorkspace workspace = MakeArticulatedWorkspace(model);
    ArticulatedMeasures measures;
    ArticulatedStepJob job;
    job.model = &model;
    job.integrator = integrator;
    job.dt = 1e-3;
    job.wrenches = wrenches;
    job.targets = targets;
    job.workspace = &workspace;
    job.state = &state;
    const long before = g_allocations;
    for (int i = 0; i < 500; ++i) {
      ASSERT_TRUE(job.Run().ok());
      ASSERT_TRUE(MeasureArticulated(model, state, job.gravity, &measures).ok());
      ASSERT_TRUE(EvaluateArticulatedBodies(model, &state).ok());
      SetJointAnglesDegrees(ArticulatedJointType::kHinge,
                            JointAnglesDegrees(ArticulatedJointType::kHinge, state.joints[2]),
                            &state.joints[2]);
    }
    const long after = g_allocations;
    EXPECT_EQ(after, before) << static_cast<int>(integrator);
    EXPECT_TRUE(std::isfinite(measures.kinetic_energy));
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
