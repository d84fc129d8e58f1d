// engine/core/math: the shared constants and angle unwrapping.
#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace gmg
