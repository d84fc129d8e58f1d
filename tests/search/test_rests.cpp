// Rest stretches of the reference (search/rests.h) on chain graphs whose activity is set by hand:
// 1 everywhere but for known still stretches at 0.0625.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "search/rests.h"
#include "tests/search/fixtures.h"

namespace gmg {
namespace {

constexpr float kStill = 0.0625f;  // exact in binary: window sums tie exactly

// 100 frames; still at [40, 55) and [80, 85); a break node at `extra_break` too when >= 0.
MotionGraph graph_with_rests(int extra_break = -1) {
  MotionGraph g = testing::chain_graph(100, {}, {}, {});
  if (extra_break >= 0) {
    // The same chain, with the natural edge out of the break frame kept (as chain_graph does for
    // its last frame): only the break node ends the capture run.
    GraphBuilder b(100);
    b.node(extra_break).kinds |= kBreakNode;
    b.node(99).kinds |= kBreakNode;
    for (int f = 0; f + 1 < 100; ++f) b.add_edge(f, f + 1, EdgeInfo{0.0});
    b.finish(g);
  }
  std::vector<float> activity(100, 1.0f);
  for (int f = 40; f < 55; ++f) activity[static_cast<std::size_t>(f)] = kStill;
  for (int f = 80; f < 85; ++f) activity[static_cast<std::size_t>(f)] = kStill;
  g.activity = activity;
  return g;
}

TEST(RestFinder, HoldIsTheLongestStillRun) {
  const RestFinder r(graph_with_rests());
  EXPECT_EQ(r.hold(), 15);
}

TEST(RestFinder, StillestFindsTheStillStretch) {
  const RestFinder r(graph_with_rests());
  // Six 10-frame windows lie inside [40, 55) (starts 40..45), all equally still: the earliest first.
  EXPECT_EQ(r.stillest(10, 3), (std::vector<int>{40, 41, 42}));
  EXPECT_EQ(r.stillest(10, 6), (std::vector<int>{40, 41, 42, 43, 44, 45}));
  // Then the windows with one moving frame: 39 and 46 (mean (9 * 0.0625 + 1) / 10).
  EXPECT_EQ(r.stillest(10, 8), (std::vector<int>{40, 41, 42, 43, 44, 45, 39, 46}));
  // 5-frame windows: [80, 85) is as still as those inside [40, 55).
  const std::vector<int> five = r.stillest(5, 12);
  EXPECT_EQ(five, (std::vector<int>{40, 41, 42, 43, 44, 45, 46, 47, 48, 49, 50, 80}));
  EXPECT_DOUBLE_EQ(r.stillness(40, 10), static_cast<double>(kStill));
  EXPECT_DOUBLE_EQ(r.stillness(39, 10), (9.0 * static_cast<double>(kStill) + 1.0) / 10.0);
}

TEST(RestFinder, StretchesLeavingTheCaptureRunAreNotRests) {
  // A break at frame 47 splits the still stretch into 8 and 7 frames: the longest rest is 8.
  const RestFinder r(graph_with_rests(47));
  EXPECT_EQ(r.hold(), 8);
  EXPECT_EQ(r.stillness(45, 5), std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(r.stillness(40, 8), static_cast<double>(kStill));
  // No 10-frame window fits in either part: the stillest ends at the break with two moving frames.
  EXPECT_EQ(r.stillest(10, 1), (std::vector<int>{38}));
  EXPECT_EQ(r.stillness(95, 10), std::numeric_limits<double>::infinity());  // past the end
}

TEST(RestFinder, NoActivityNoRests) {
  const MotionGraph g = testing::chain_graph(50, {}, {}, {});
  const RestFinder r(g);
  EXPECT_EQ(r.hold(), 0);
  EXPECT_TRUE(r.stillest(5, 3).empty());
  EXPECT_EQ(r.stillness(0, 5), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace gmg
