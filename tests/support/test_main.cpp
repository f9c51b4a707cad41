// gtest main for wirerig tests: traps division by zero, invalid operations and overflow,
// so a NaN or Inf produced anywhere in the code under test fails the test where it happens.
#include <fenv.h>

#include <gtest/gtest.h>

int main(int argc, char** argv) {
  feenableexcept(FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
