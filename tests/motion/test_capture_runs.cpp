// Capture runs: continuity, run bounds and reading inside a run, from a source's break frames.
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/motion/capture_runs.h"

namespace gmg {
namespace {

// 10 frames, breaks at 3 and 9: runs [0, 3] and [4, 9].
TEST(CaptureRuns, RunsBetweenBreaks) {
  const CaptureRuns runs(10, {3, 9});
  EXPECT_EQ(runs.frame_count(), 10);
  EXPECT_TRUE(runs.continues(2));
  EXPECT_FALSE(runs.continues(3));
  EXPECT_TRUE(runs.continues(4));
  EXPECT_FALSE(runs.continues(9));
  EXPECT_EQ(runs.first(0), 0);
  EXPECT_EQ(runs.first(3), 0);
  EXPECT_EQ(runs.first(4), 4);
  EXPECT_EQ(runs.first(9), 4);
  EXPECT_EQ(runs.last(0), 3);
  EXPECT_EQ(runs.last(3), 3);
  EXPECT_EQ(runs.last(4), 9);
  // Without a break at the end the last run ends at the last frame.
  const CaptureRuns open(10, {3});
  EXPECT_EQ(open.last(5), 9);
  EXPECT_TRUE(open.continues(9));
}

TEST(CaptureRuns, ReadsAndDifferencesInsideARun) {
  const CaptureRuns runs(10, {3, 9});
  EXPECT_TRUE(runs.readable(2.5, 1));
  EXPECT_TRUE(runs.readable(3.0, 1));   // the run's last frame itself
  EXPECT_FALSE(runs.readable(3.5, 1));  // 3 does not continue into 4
  EXPECT_FALSE(runs.readable(4.0, 1));  // another run
  EXPECT_FALSE(runs.readable(-0.5, 0));
  EXPECT_FALSE(runs.readable(10.0, 9));
  EXPECT_EQ(runs.next_frame(2, 0.5), 3);
  EXPECT_EQ(runs.next_frame(3, 0.5), 3);
  EXPECT_EQ(runs.next_frame(2, 0.0), 2);
  double t = 0.0, sign = 0.0;
  ASSERT_TRUE(runs.velocity_partner(5.5, 1.0, t, sign));  // backward inside the run
  EXPECT_EQ(t, 4.5);
  EXPECT_EQ(sign, 1.0);
  ASSERT_TRUE(runs.velocity_partner(4.0, 1.0, t, sign));  // forward at the run's start
  EXPECT_EQ(t, 5.0);
  EXPECT_EQ(sign, -1.0);
  EXPECT_FALSE(runs.velocity_partner(4.0, 0.0, t, sign));  // a held frame
}

TEST(CaptureRuns, FromContinuesFlagsAndRefusingBadBreaks) {
  const CaptureRuns runs(std::vector<char>{1, 1, 1, 0, 1, 1, 0});
  EXPECT_EQ(runs.breaks(), (std::vector<int>{3, 6}));
  EXPECT_EQ(runs.frame_count(), 7);
  EXPECT_THROW(CaptureRuns(5, {3, 2}), Error);
  EXPECT_THROW(CaptureRuns(5, {5}), Error);
  EXPECT_THROW(CaptureRuns(5, {-1}), Error);
}

}  // namespace
}  // namespace gmg
