#include "wirerig/viewer/timeline.h"

#include <gtest/gtest.h>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(Timeline, PausedTimeDoesNotMove) {
  Timeline t;
  t.duration = 2.0;
  t.Advance(0.5);
  EXPECT_EQ(t.time, 0.0);
}

TEST(Timeline, PlayingAdvancesBySpeedAndLoops) {
  Timeline t;
  t.duration = 2.0;
  t.playing = true;
  t.speed = 2.0;
  t.Advance(0.5);
  EXPECT_DOUBLE_EQ(t.time, 1.0);
  t.Advance(0.75);
  EXPECT_DOUBLE_EQ(t.time, 0.5);
  EXPECT_TRUE(t.playing);
}

TEST(Timeline, BackwardsLoopWrapsToTheEnd) {
  Timeline t;
  t.duration = 2.0;
  t.playing = true;
  t.speed = -1.0;
  t.Advance(0.5);
  EXPECT_DOUBLE_EQ(t.time, 1.5);
}

TEST(Timeline, WithoutLoopStopsAtTheEnd) {
  Timeline t;
  t.duration = 1.0;
  t.playing = true;
  t.loop = false;
  t.Advance(3.0);
  EXPECT_DOUBLE_EQ(t.time, 1.0);
  EXPECT_FALSE(t.playing);
}

TEST(Timeline, SeekClamps) {
  Timeline t;
  t.duration = 1.0;
  t.Seek(5.0);
  EXPECT_DOUBLE_EQ(t.time, 1.0);
  t.Seek(-1.0);
  EXPECT_DOUBLE_EQ(t.time, 0.0);
}

TEST(Timeline, ZeroDurationNeverMoves) {
  Timeline t;
  t.playing = true;
  t.Advance(1.0);
  EXPECT_EQ(t.time, 0.0);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
