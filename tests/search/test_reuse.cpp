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

TEST(Reuse, AFrameAtItsCapWithinTheWindowCostsTheCap) {
  ReuseTracker r(10, 1e12, 3, 90);  // no decay to speak of: 3 plays within 90 output frames
  r.play({4}, 0);
  r.play({4}, 10);
  EXPECT_FALSE(r.capped(4, 20)) << "two plays are under the cap";
  r.play({4}, 20);
  EXPECT_TRUE(r.capped(4, 20));
  EXPECT_TRUE(r.capped(4, 89)) << "the play at 0 is within the 90 frames before 89";
  EXPECT_FALSE(r.capped(4, 90)) << "90 frames after it, it no longer counts";
  EXPECT_NEAR(r.frame_cost(4, 50), 9.0 + ReuseTracker::kCapCost, 1e-6);
  EXPECT_NEAR(r.frame_cost(4, 90), 9.0, 1e-6);
  EXPECT_FALSE(r.capped(5, 50)) << "other frames are not";
  r.play({4}, 95);  // the last three plays: 10, 20, 95
  EXPECT_TRUE(r.capped(4, 99));
  EXPECT_FALSE(r.capped(4, 100));
  ReuseTracker none(10, 30.0);  // no cap
  none.play({4, 5}, 0);
  none.play({4}, 1);
  none.play({4}, 2);
  EXPECT_FALSE(none.capped(4, 3));
}

// Play counts are kept per block of frames made on the first play in it: frames on either side of
// a block's edge, and far into a long reference, count alike.
TEST(Reuse, FramesOfEveryBlockCountAlike) {
  ReuseTracker r(3000000, 30.0, 2, 50);
  for (int f : {4095, 4096, 2999999}) {
    EXPECT_EQ(r.plays(f, 0), 0.0);
    EXPECT_FALSE(r.capped(f, 0));
  }
  r.play({4095, 4096}, 0);
  r.play({2999999}, 0);
  r.play({4096, 2999999}, 10);
  EXPECT_DOUBLE_EQ(r.plays(4095, 0), 1.0);
  EXPECT_NEAR(r.plays(4096, 10), 1.0 + std::exp(-std::log(2.0) / 3.0), 1e-12);
  EXPECT_FALSE(r.capped(4095, 10));
  EXPECT_TRUE(r.capped(4096, 10));
  EXPECT_TRUE(r.capped(2999999, 49));
  EXPECT_FALSE(r.capped(2999999, 50));
  EXPECT_EQ(r.plays(4097, 10), 0.0);
  std::vector<double> w;
  r.window_costs(3, 10, {4094, 2999998}, w);  // 4094-4096; 2999998-2999999 (clamped)
  EXPECT_NEAR(w[0], r.frame_cost(4096, 10), 1e-12);
  EXPECT_NEAR(w[1], r.frame_cost(2999999, 10), 1e-12);
}
// A path that loops back to a frame it already played (5 6 7 through a transition to 5 6 again)
// shows the same stroke twice within a second: it costs the cap, though the tracker has seen no
// play of those frames yet. A held frame (5 5 6) is one play and costs nothing more.
TEST(Reuse, APathThatComesBackToAFrameCostsTheCap) {
  ReuseTracker r(20, 1e12, 3, 90, 300);
  EXPECT_GE(r.path_cost({5, 6, 7, 5, 6}, 0), ReuseTracker::kCapCost);
  EXPECT_EQ(r.path_cost({5, 5, 6, 7}, 0), 0.0);
  ReuseTracker no_rules(20, 1e12);  // neither a cap nor a return window: loops are not priced
  EXPECT_EQ(no_rules.path_cost({5, 6, 7, 5, 6}, 0), 0.0);
}
}  // namespace
}  // namespace gmg
