// Kinematic beats and the end cost of stopping at a frame, worked out by hand.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "graph/beats.h"

namespace gmg {
namespace {

// The cost 1 - exp(-d^2 / (2 (0.1 s x 30 fps)^2)) = 1 - exp(-d^2 / 18), in float as stored.
float cost_at(double d) { return static_cast<float>(1.0 - std::exp(-d * d / 18.0)); }

// One run of 12 frames, activity 1 but for a dip to 0.5 at frame 4: lower than the 4 frames either
// side (0..3, 5..8, all inside the run) and above 0.3, so frame 4 is the one beat.
TEST(Beats, EndCostIsTheDistanceToTheNearestBeat) {
  std::vector<float> a(12, 1.0f);
  a[4] = 0.5f;
  const std::vector<float> c = beat_end_costs(Samples<float>(a), CaptureRuns(12, {11}), 30.0);
  ASSERT_EQ(c.size(), 12u);
  EXPECT_EQ(c[4], 0.0f);
  EXPECT_EQ(c[7], cost_at(3.0));  // 1 - exp(-1/2): 0.1 s away
  EXPECT_EQ(c[0], cost_at(4.0));
  EXPECT_EQ(c[11], cost_at(7.0));
}

// A dip too close to a break (frame 8 lies in the next run), or too low (0.2 < 0.3), is no beat:
// every frame then costs 1.
TEST(Beats, NoBeatAcrossABreakOrAtRest) {
  std::vector<float> a(12, 1.0f);
  a[4] = 0.5f;
  for (float c : beat_end_costs(Samples<float>(a), CaptureRuns(12, {5, 11}), 30.0)) EXPECT_EQ(c, 1.0f);
  a[4] = 0.2f;
  for (float c : beat_end_costs(Samples<float>(a), CaptureRuns(12, {11}), 30.0)) EXPECT_EQ(c, 1.0f);
}

// Two runs, [0, 11] and [12, 23], with beats at 7 and 18. Frame 12 is 5 frames from the beat at 7,
// but that one lies in the other run: its cost is that of the beat at 18, 6 frames on.
TEST(Beats, OnlyBeatsOfTheFramesOwnRunCount) {
  std::vector<float> a(24, 1.0f);
  a[7] = 0.5f;
  a[18] = 0.5f;
  const std::vector<float> c = beat_end_costs(Samples<float>(a), CaptureRuns(24, {11, 23}), 30.0);
  EXPECT_EQ(c[7], 0.0f);
  EXPECT_EQ(c[18], 0.0f);
  EXPECT_EQ(c[11], cost_at(4.0));
  EXPECT_EQ(c[12], cost_at(6.0));
  EXPECT_THROW(beat_end_costs(Samples<float>(a), CaptureRuns(12, {11}), 30.0), Error);
}

}  // namespace
}  // namespace gmg
