// Resampling an accepted path to its target length.
#include <gtest/gtest.h>

#include "engine/assemble/resample.h"
#include "engine/core/error.h"
#include "tests/assemble/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(Resample, StretchesEvenlyWithSlerp) {
  // Arm angles 0, 0.4, 0.8 (path of 3 frames) resampled to 5 frames: positions 0, .5, 1, 1.5, 2
  // along the path, so angles 0, 0.2, 0.4, 0.6, 0.8 (SLERP about one axis is linear in angle).
  const Motion m = arm_motion({0.0, 0.4, 0.8});
  const Motion r = resample_path(m, {0, 1, 2}, 5);
  ASSERT_EQ(r.frame_count, 5);
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(glm::angle(r.rotation(i, 1)), 0.2 * i, 1e-12) << i;
}

TEST(Resample, SqueezesAndFollowsThePathOrder) {
  // A path that jumps back (2, 1, 0) read at 2 frames takes its two ends.
  const Motion m = arm_motion({0.0, 0.4, 0.8});
  const Motion r = resample_path(m, {2, 1, 0}, 2);
  EXPECT_NEAR(glm::angle(r.rotation(0, 1)), 0.8, 1e-12);
  EXPECT_NEAR(glm::angle(r.rotation(1, 1)), 0.0, 1e-12);
  // One frame: the path's first.
  EXPECT_NEAR(glm::angle(resample_path(m, {1, 2}, 1).rotation(0, 1)), 0.4, 1e-12);
  EXPECT_THROW(resample_path(m, {}, 3), Error);
  EXPECT_THROW(resample_path(m, {0}, 0), Error);
}

}  // namespace
}  // namespace gmg
