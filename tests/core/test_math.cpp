// engine/core/math: the shared constants, angle unwrapping and the moving average.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/core/math.h"

namespace gmg {
namespace {

TEST(Math, Constants) {
  EXPECT_EQ(kPi, std::acos(-1.0));  // the double nearest pi either way
  EXPECT_EQ(kTwoPi, 2.0 * std::acos(-1.0));
  EXPECT_EQ(90.0 * kDegToRad, std::acos(-1.0) / 2.0);
  EXPECT_EQ(180.0 * kDegToRad, kPi);
}

TEST(Math, WrapNearMovesByWholeTurns) {
  EXPECT_NEAR(wrap_near(0.1 + kTwoPi, 0.0), 0.1, 1e-15);
  EXPECT_NEAR(wrap_near(0.1 - 3 * kTwoPi, 0.0), 0.1, 1e-14);
  // Across the +-pi seam: -3.0 is 0.28 rad past +pi from 3.0, so it becomes -3.0 + 2 pi.
  EXPECT_NEAR(wrap_near(-3.0, 3.0), -3.0 + kTwoPi, 1e-15);
  EXPECT_NEAR(wrap_near(3.0, -3.0), 3.0 - kTwoPi, 1e-15);
  // Near a reference far from 0: the result lies within pi of it.
  EXPECT_NEAR(wrap_near(0.5, 20.0), 0.5 + 3 * kTwoPi, 1e-14);  // 20 / 2 pi = 3.18 turns
  EXPECT_EQ(wrap_near(1.0, 1.0), 1.0);
  // Unwrapping a sawtooth that jumps by -2 pi every half turn gives the straight line back.
  double previous = 0.0;
  for (int i = 1; i <= 40; ++i) {
    const double line = 0.4 * i;
    const double wrapped = std::remainder(line, kTwoPi);  // in [-pi, pi]
    previous = wrap_near(wrapped, previous);
    EXPECT_NEAR(previous, line, 1e-12) << i;
  }
}

// Each value is the mean of its window's samples that exist: the whole window inside, fewer at the
// ends; half 0 leaves the values as they are.
TEST(Math, MovingAverageShrinksItsWindowAtTheEnds) {
  const std::vector<double> x = {1.0, 2.0, 4.0, 8.0, 16.0};
  EXPECT_EQ(moving_average(x, 1), (std::vector<double>{1.5, 7.0 / 3.0, 14.0 / 3.0, 28.0 / 3.0, 12.0}));
  EXPECT_EQ(moving_average(x, 2), (std::vector<double>{7.0 / 3.0, 15.0 / 4.0, 31.0 / 5.0, 30.0 / 4.0, 28.0 / 3.0}));
  EXPECT_EQ(moving_average(x, 0), x);
  EXPECT_EQ(moving_average(x, 10), std::vector<double>(5, 31.0 / 5.0));
  EXPECT_TRUE(moving_average({}, 3).empty());
}

}  // namespace
}  // namespace gmg
