// Proves that the modal wire jobs never allocate: global operator new is replaced by one that
// counts (the technique of no_allocation_test.cpp), so this is a binary of its own.
#include <gtest/gtest.h>

#include <vector>

#include "wirerig/runtime/modal_wire.h"

#include "support/counting_allocator.h"

using wirerig::testing::g_allocations;

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(ModalWireNoAllocation, CountingAllocatorSeesAllocations) {
  EXPECT_GE(testing::CountedAllocationsOfAHeapVector(), 2);
}

TEST(ModalWireNoAllocation, BuildStepAndEvaluateWithEveryOption) {
  std::vector<PointLoad> point = {{0.2, Vec3(0, -1, 0)}, {0.7, Vec3(1, 0, 0)}};
  std::vector<LineLoad> line = {{0.1, 0.5, Vec3(0, 0, 2)}};
  std::vector<LinearLineLoad> linear = {{0.2, 0.9, Vec3(1, 0, 0), Vec3(0, -2, 1)}};
  std::vector<double> v(33);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = double(i) / double(v.size() - 1);
  std::vector<double> values(v.size() * 32), slopes(v.size() * 32);
  std::vector<Vec3> x(v.size()), slope(v.size());
  for (BoundaryCondition bc :
       {BoundaryCondition::kSimplySupported, BoundaryCondition::kClamped,
        BoundaryCondition::kCantileverFree, BoundaryCondition::kCantileverGuided}) {
    for (double zeta : {0.0, 0.1, 1.0, 3.0}) {
      SCOPED_TRACE(::testing::Message() << ToString(bc) << " zeta " << zeta);
      long before = g_allocations;
      ModalWireModel model;
      ASSERT_TRUE(BuildModalBasis(bc, 32, &model.basis).ok());
      model.length = 0.8;
      model.bending_stiffness = 0.3;
      model.mass_per_length = 0.2;
      model.damping_ratio = zeta;
      ModalWireLoads loads;
      loads.point_loads = point;
      loads.line_loads = line;
      loads.start_displacement = Vec3(0.0, 0.01, 0.0);
      if (IsCantilever(bc)) loads.tip_force = Vec3(0.0, 0.5, 0.0);
      loads.linear_line_loads = linear;
      loads.support_acceleration = Vec3(2.0, -9.81, 0.0);
      loads.support_angular_velocity = Vec3(0.5, -1.0, 2.0);
      loads.support_angular_acceleration = Vec3(3.0, 0.0, -1.0);
      ModalWireState state;
      ModalStepTable table;
      ASSERT_TRUE(InitializeModalWireAtRest(model, &state).ok());
      ASSERT_TRUE(InitializeModalWireAtStatic(model, loads, &state).ok());
      ASSERT_TRUE(PrecomputeModalStep(model, 1.0 / 60.0, &table).ok());
      ASSERT_TRUE(TabulateModes(model.basis, v, values, slopes).ok());
      EXPECT_EQ(g_allocations, before) << "setup";

      ModalWireStepJob step;
      step.model = &model;
      step.loads = loads;
      step.dt = 1.0 / 60.0;
      step.state = &state;
      ModalWireEvaluateJob eval;
      eval.model = &model;
      eval.state = &state;
      eval.loads = loads;
      eval.samples = v;
      eval.displacement = x;
      eval.slope = slope;
      before = g_allocations;
      for (ModalHold hold : {ModalHold::kZeroOrder, ModalHold::kFirstOrder}) {
        step.hold = hold;
        step.step_table = nullptr;
        ASSERT_TRUE(step.Run().ok());
        step.step_table = &table;
        ASSERT_TRUE(step.Run().ok());
      }
      ASSERT_TRUE(eval.Run().ok());
      eval.mode_values = values;
      eval.mode_slopes = slopes;
      ASSERT_TRUE(eval.Run().ok());
      eval.slope = {};
      ASSERT_TRUE(eval.Run().ok());
      // Refusals do not allocate either.
      step.dt = -1.0;
      EXPECT_FALSE(step.Run().ok());
      EXPECT_EQ(g_allocations, before) << "per frame";
    }
  }
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
