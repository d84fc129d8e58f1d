// Assembly by source time: where each output frame reads the source.
#include <cmath>

#include <gtest/gtest.h>

#include "engine/assemble/timeline.h"

namespace gmg {
namespace {

// Frames 0..99 in one capture run.
std::vector<char> one_run() {
  std::vector<char> c(100, 1);
  c.back() = 0;
  return c;
}

std::vector<int> frames(int first, int count) {
  std::vector<int> p;
  for (int i = 0; i < count; ++i) p.push_back(first + i);
  return p;
}

TEST(Timeline, OnePieceIsALinearWarp) {
  // 11 source frames stretched over 21 output frames: rate 0.5, frame i reads 10 + i / 2.
  const std::vector<SourceClock> c = source_timeline({{frames(10, 11), 21}}, one_run());
  ASSERT_EQ(c.size(), 21u);
  for (int i = 0; i < 21; ++i) {
    EXPECT_NEAR(c[static_cast<std::size_t>(i)].time, 10 + 0.5 * i, 1e-12) << i;
    EXPECT_NEAR(c[static_cast<std::size_t>(i)].rate, 0.5, 1e-12) << i;
    EXPECT_EQ(c[static_cast<std::size_t>(i)].run, 0);
  }
}

TEST(Timeline, ContinuingPiecesChangeSpeedGraduallyAndKeepTheirKeyFrames) {
  // Three pieces continuing one another: slow (0.7), fast (1.4), slow again. Each starts on its
  // key frame (the previous piece's stop node) and the speed between them changes without a jump.
  const std::vector<PathPiece> pieces = {{frames(0, 15), 21}, {frames(15, 29), 21}, {frames(44, 15), 21}};
  const std::vector<SourceClock> c = source_timeline(pieces, one_run());
  ASSERT_EQ(c.size(), 63u);
  EXPECT_DOUBLE_EQ(c[0].time, 0.0);
  EXPECT_DOUBLE_EQ(c[21].time, 15.0);
  EXPECT_DOUBLE_EQ(c[42].time, 44.0);
  EXPECT_DOUBLE_EQ(c[62].time, 58.0);
  double largest_change = 0.0;
  for (std::size_t i = 1; i < c.size(); ++i) {
    EXPECT_GT(c[i].time, c[i - 1].time) << "monotone at " << i;
    EXPECT_EQ(c[i].run, 0) << "one run: no transition";
    if (i >= 2)
      largest_change =
          std::max(largest_change, std::abs((c[i].time - c[i - 1].time) - (c[i - 1].time - c[i - 2].time)));
  }
  // Piecewise-linear playback would change the step by 0.7 at once (0.7 -> 1.4); the curve spreads
  // it over the pieces.
  EXPECT_LT(largest_change, 0.15);
}

TEST(Timeline, ATransitionStartsANewRunAndIsNotSmoothedAcross) {
  const std::vector<PathPiece> pieces = {{frames(0, 11), 11}, {frames(50, 11), 21}};
  const std::vector<SourceClock> c = source_timeline(pieces, one_run());
  EXPECT_EQ(c[10].run, 0);
  EXPECT_EQ(c[11].run, 1);
  EXPECT_DOUBLE_EQ(c[10].time, 10.0);
  for (int i = 0; i < 21; ++i) EXPECT_NEAR(c[static_cast<std::size_t>(11 + i)].time, 50 + 0.5 * i, 1e-12) << i;
}

}  // namespace
}  // namespace gmg

namespace gmg {
namespace {

// Frames 0-2 are one capture run, a break after 2, frames 3-4 another (continues = 1 1 0 1 0).
TEST(CaptureRuns, ReadAndDifferenceOnlyInsideARun) {
  const std::vector<char> continues = {1, 1, 0, 1, 0};
  const CaptureRuns runs(continues);
  EXPECT_TRUE(runs.readable(1.5, 0));
  EXPECT_TRUE(runs.readable(2.0, 0)) << "a whole frame at the run's end";
  EXPECT_FALSE(runs.readable(2.5, 2)) << "between 2 and 3 lies the break";
  EXPECT_FALSE(runs.readable(3.0, 2)) << "another run";
  EXPECT_FALSE(runs.readable(-0.5, 0));
  EXPECT_FALSE(runs.readable(5.0, 4)) << "past the last frame";
  EXPECT_EQ(runs.next_frame(1, 0.5), 2);
  EXPECT_EQ(runs.next_frame(2, 0.5), 2) << "no frame to interpolate towards across the break";
  EXPECT_EQ(runs.next_frame(1, 0.0), 1);
  double partner = 0.0, sign = 0.0;
  ASSERT_TRUE(runs.velocity_partner(1.5, 1.0, partner, sign));
  EXPECT_EQ(partner, 0.5);
  EXPECT_EQ(sign, 1.0);
  ASSERT_TRUE(runs.velocity_partner(3.0, 1.0, partner, sign)) << "a run's first frame looks forward";
  EXPECT_EQ(partner, 4.0);
  EXPECT_EQ(sign, -1.0);
  EXPECT_FALSE(runs.velocity_partner(1.0, 0.0, partner, sign)) << "a held frame has no velocity";
  EXPECT_FALSE(runs.velocity_partner(0.0, 3.0, partner, sign)) << "a run too short for the rate";
}

}  // namespace
}  // namespace gmg
