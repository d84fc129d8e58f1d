// Reuse of the reference: decayed play counts, worked out by hand.
#include <cmath>

#include <gtest/gtest.h>

#include "search/reuse.h"

namespace gmg {
namespace {

TEST(Reuse, PlaysDecayWithTheirHalfLife) {
  ReuseTracker r(10, 30.0);  // half-life 30 output frames
  EXPECT_EQ(r.frame_cost(4, 0), 0.0);
  r.play({3, 4, 4, 5}, 0);  // the held 4 is one play
  EXPECT_DOUBLE_EQ(r.plays(4, 0), 1.0);
  EXPECT_NEAR(r.plays(4, 30), 0.5, 1e-12);
  EXPECT_NEAR(r.plays(4, 60), 0.25, 1e-12);
  r.play({4}, 30);  // a second play half a life later: 0.5 + 1
  EXPECT_NEAR(r.plays(4, 30), 1.5, 1e-12);
  EXPECT_NEAR(r.frame_cost(4, 30), 2.25, 1e-12) << "a frame costs its plays squared";
  EXPECT_NEAR(r.plays(3, 30), 0.5, 1e-12);
  EXPECT_EQ(r.frame_cost(6, 30), 0.0);
}

TEST(Reuse, APathPaysItsMostPlayedFrame) {
  ReuseTracker r(10, 30.0);
  r.play({2, 3}, 0);
  EXPECT_DOUBLE_EQ(r.path_cost({3, 4, 5, 6}, 0), 1.0);
  EXPECT_DOUBLE_EQ(r.path_cost({6, 7}, 0), 0.0);
  std::vector<double> w;
  r.window_costs(3, 30, {0, 1, 4, 9}, w);  // windows 0-2, 1-3, 4-6, 9 (clamped)
  ASSERT_EQ(w.size(), 4u);
  EXPECT_NEAR(w[0], 0.25, 1e-12);
  EXPECT_NEAR(w[1], 0.25, 1e-12);
  EXPECT_EQ(w[2], 0.0);
  EXPECT_EQ(w[3], 0.0);
}

}  // namespace
}  // namespace gmg
