// Beats on onsets (engine/assemble/timeline.h BeatAlignment): one stretch of capture played at its
// own speed (source frame = output frame), onsets and kinematic beats placed by hand.
#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "engine/assemble/timeline.h"

namespace gmg {
namespace {

PathPiece piece(int first, int count) {
  PathPiece p;
  p.path.resize(static_cast<std::size_t>(count));
  std::iota(p.path.begin(), p.path.end(), first);
  p.length = count;
  return p;
}

const CaptureRuns kRuns(200, {199});

std::vector<SourceClock> aligned(const std::vector<PathPiece>& pieces, std::vector<int> onsets,
                                 std::vector<int> beats) {
  BeatAlignment a;
  a.onsets = std::move(onsets);
  a.beats = std::move(beats);
  return source_timeline(pieces, kRuns, &a);
}

void expect_untouched(const std::vector<SourceClock>& clock) {
  for (std::size_t o = 0; o < clock.size(); ++o) {
    EXPECT_DOUBLE_EQ(clock[o].time, static_cast<double>(o)) << o;
    EXPECT_DOUBLE_EQ(clock[o].rate, 1.0) << o;
  }
}

// The clock's speed stays within [1 / max_rate, max_rate] and time only moves forward.
void expect_rates_within(const std::vector<SourceClock>& clock, double max_rate) {
  for (std::size_t o = 0; o < clock.size(); ++o) {
    EXPECT_GE(clock[o].rate, 1.0 / max_rate) << o;
    EXPECT_LE(clock[o].rate, max_rate) << o;
    if (o > 0) {
      EXPECT_GT(clock[o].time, clock[o - 1].time) << o;
    }
  }
}

TEST(BeatAlignment, WithoutBeatsTheClockRunsStraight) {
  expect_untouched(source_timeline({piece(0, 60)}, kRuns));
  expect_untouched(aligned({piece(0, 60)}, {30}, {}));
  expect_untouched(aligned({piece(0, 60)}, {}, {27}));
}

TEST(BeatAlignment, AnOnsetThreeFramesAfterABeatMovesOntoIt) {
  const std::vector<SourceClock> clock = aligned({piece(0, 60)}, {30}, {27});
  ASSERT_EQ(clock.size(), 60u);
  EXPECT_DOUBLE_EQ(clock[30].time, 27.0);
  // The stretch's ends stay where the plan put them.
  EXPECT_DOUBLE_EQ(clock[0].time, 0.0);
  EXPECT_DOUBLE_EQ(clock[59].time, 59.0);
  expect_rates_within(clock, 1.33);
}

TEST(BeatAlignment, ABeatAfterTheOnsetToo) {
  const std::vector<SourceClock> clock = aligned({piece(0, 60)}, {30}, {10, 34, 50});
  EXPECT_DOUBLE_EQ(clock[30].time, 34.0);
  expect_rates_within(clock, 1.33);
}

TEST(BeatAlignment, BeyondMaxShiftNothingMoves) {
  expect_untouched(aligned({piece(0, 60)}, {30}, {25}));
  expect_untouched(aligned({piece(0, 60)}, {30}, {35}));
  // Within a larger max_shift it does.
  BeatAlignment a;
  a.onsets = {30};
  a.beats = {25};
  a.max_shift = 5;
  EXPECT_DOUBLE_EQ(source_timeline({piece(0, 60)}, kRuns, &a)[30].time, 25.0);
}

TEST(BeatAlignment, TooFastNothingMoves) {
  // Onset at output 10 onto beat 14: 14 source frames in 10 output frames, 1.4 > 1.33.
  expect_untouched(aligned({piece(0, 60)}, {10}, {14}));
}

TEST(BeatAlignment, AnOnsetNextToAKnotIsLeft) {
  // Output frame 57 is 2 frames before the stretch's last frame, a key frame already.
  expect_untouched(aligned({piece(0, 60)}, {57}, {55}));
}

TEST(BeatAlignment, AnOnsetOnAPiecesFirstFrameMovesThatKnot) {
  // Two pieces, one continuous run: the second piece's first frame (output 30) is a knot.
  const std::vector<SourceClock> clock = aligned({piece(0, 30), piece(30, 30)}, {30}, {33});
  EXPECT_DOUBLE_EQ(clock[30].time, 33.0);
  EXPECT_DOUBLE_EQ(clock[59].time, 59.0);
  EXPECT_EQ(clock[0].run, clock[59].run);
  expect_rates_within(clock, 1.33);
}

TEST(BeatAlignment, ABendNearTheRateLimitIsMade) {
  // Onset 13 onto beat 16: secants 16/13 = 1.23 and 43/46 = 0.93, and the curve through them stays
  // within 1.33 at every frame.
  const std::vector<SourceClock> bent = aligned({piece(0, 60)}, {13}, {16});
  EXPECT_DOUBLE_EQ(bent[13].time, 16.0);
  expect_rates_within(bent, 1.33);
  // Onset 12 onto beat 16: 16/12 = 1.33333 > 1.33, left.
  expect_untouched(aligned({piece(0, 60)}, {12}, {16}));
}

// The bend's secants may lie within max_rate while the C1 curve drawn through the knots overshoots
// them: onset 13 onto beat 17 in a 60-frame stretch has secants 17/13 = 1.31 and 42/46 = 0.91, and
// the curve through them played output frames 1-7 at up to 1.372 source frames a frame. The speed
// must stay within max_rate at every frame.
TEST(BeatAlignment, RateStaysWithinMaxRateNearTheLimit) {
  expect_rates_within(aligned({piece(0, 60)}, {13}, {17}), 1.33);
}

}  // namespace
}  // namespace gmg
