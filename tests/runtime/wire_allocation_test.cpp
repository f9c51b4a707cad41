// Proves that the large-curl and wire IK jobs never allocate in Run(): global operator new is
// replaced by one that counts (support/counting_allocator.h), so this is a binary of its own.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "wirerig/runtime/corotational_wire.h"
#include "wirerig/runtime/corotational_wire_ik.h"
#include "wirerig/runtime/wire_ik.h"

#include "support/counting_allocator.h"

using wirerig::testing::g_allocations;

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(WireNoAllocation, CountingAllocatorSeesAllocations) {
  EXPECT_GE(testing::CountedAllocationsOfAHeapVector(), 2);
}

TEST(WireNoAllocation, CorotationalWireWithEveryLoadAndBothTips) {
  const std::array<PointLoad, 2> points = {PointLoad{0.3, Vec3(1.0, 2.0, 0.0)},
                                           PointLoad{0.8, Vec3(0.0, -1.0, 0.0)}};
  const std::array<LineLoad, 1> lines = {LineLoad{0.1, 0.9, Vec3(0.0, -3.0, 0.0)}};
  const std::array<double, 4> v = {0.0, 0.3, 0.77, 1.0};
  std::array<Vec3, 4> p, t;
  CorotationalWireResult result;
  for (BoundaryCondition bc :
       {BoundaryCondition::kCantileverFree, BoundaryCondition::kCantileverGuided}) {
    CorotationalWireJob job;
    job.boundary = bc;
    job.length = 1.0;
    job.bending_stiffness = 0.5;
    job.tip_force = Vec3(-0.5, 3.0, 0.0);
    job.point_loads = points;
    job.line_loads = lines;
    job.samples = v;
    job.position = p;
    job.tangent = t;
    job.result = &result;
    const long before = g_allocations;
    ASSERT_TRUE(job.Run().ok());
    job.warm_start = true;
    job.root_moment_guess = result.root_moment;
    ASSERT_TRUE(job.Run().ok());
    job.warm_start = false;
    job.tip_force_follows = true;  // the follower force's Newton solve
    ASSERT_TRUE(job.Run().ok());
    job.tip_force_follows = false;
    job.segments = 1;  // refused: Validate fails without allocating either
    EXPECT_FALSE(job.Run().ok());
    EXPECT_EQ(g_allocations - before, 0) << ToString(bc);
  }
}

TEST(WireNoAllocation, WireIkBothBases) {
  const std::array<double, 3> at = {0.2, 0.5, 0.9};
  std::array<Vec3, 3> forces;
  WireIkResult result;
  WireIkJob ik;
  ik.boundary = BoundaryCondition::kSimplySupported;
  ik.length = 2.0;
  ik.bending_stiffness = 10.0;
  ik.basis = WireIkBasis::kPointLoads;
  ik.load_at = at;
  ik.forces = forces;
  ik.result = &result;
  ik.target_at = 0.4;
  ik.target = Vec3(0.0, 0.01, 0.02);
  const long before = g_allocations;
  ASSERT_TRUE(ik.Run().ok());
  ik.boundary = BoundaryCondition::kCantileverFree;
  ik.basis = WireIkBasis::kTipForce;
  ik.forces = std::span<Vec3>(forces.data(), 1);
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_EQ(g_allocations - before, 0);
}

TEST(WireNoAllocation, CorotationalWireIk) {
  const std::array<double, 2> v = {0.5, 1.0};
  std::array<Vec3, 2> p;
  CorotationalWireIkResult result;
  CorotationalWireIkJob ik;
  ik.wire.length = 1.0;
  ik.wire.bending_stiffness = 1.0;
  ik.wire.segments = 16;
  ik.wire.samples = v;
  ik.wire.position = p;
  ik.target = Vec3(0.6, 0.7, 0.0);
  ik.max_force = 10.0;
  ik.result = &result;
  const long before = g_allocations;
  ASSERT_TRUE(ik.Run().ok());
  EXPECT_EQ(g_allocations - before, 0);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
