// The lower body's path (search/lower_body.h) over stances made by hand: which frames are stance
// frames, which are still and where the capture runs end are all set here, so where the plan may
// change stretch is known.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "engine/core/error.h"
#include "search/lower_body.h"

namespace gmg {
namespace {

constexpr double kFps = 30.0;

// `frames` frames, one stance pose everywhere (every gap 0); stance frames every 10th frame; legs
// moving (speed 1) but for the still frames [still_from, still_to) (speed 0); still_speed 0.5.
Stance made_stance(int frames, int still_from, int still_to) {
  Stance s;
  s.known = true;
  s.leg_length = 90.0;
  s.pose = std::vector<float>(static_cast<std::size_t>(frames) * kStanceDims, 0.0f);
  s.place = std::vector<float>(2 * static_cast<std::size_t>(frames), 0.0f);
  std::vector<float> speed(static_cast<std::size_t>(frames), 1.0f);
  std::vector<std::uint8_t> planted(static_cast<std::size_t>(frames), 0);
  for (int f = 0; f < frames; ++f) {
    if (f >= still_from && f < still_to) speed[static_cast<std::size_t>(f)] = 0.0f;
    planted[static_cast<std::size_t>(f)] = f % 10 == 0;
  }
  s.speed = speed;
  s.planted = planted;
  s.still_speed = 0.5f;
  return s;
}

LowerBodyParams no_variety() {
  LowerBodyParams p;
  p.variety = 0.0;
  return p;
}

void expect_covering(const LowerPlan& plan, const CaptureRuns& runs, int total) {
  ASSERT_FALSE(plan.segments.empty());
  int at = 0;
  for (const LowerSegment& s : plan.segments) {
    EXPECT_EQ(s.start, at);
    EXPECT_GE(s.length, 1);
    // A stretch plays on inside one capture run.
    EXPECT_GE(runs.last(s.source), s.source + s.length - 1) << "segment at " << s.start;
    at = s.start + s.length;
  }
  EXPECT_EQ(at, total);
  EXPECT_EQ(plan.segments.front().change, LowerChange::Start);
}

// The graph frame the plan plays at output frame o.
int played_at(const LowerPlan& plan, int o) {
  for (const LowerSegment& s : plan.segments)
    if (o >= s.start && o < s.start + s.length) return s.source + (o - s.start);
  return -1;
}

TEST(LowerBody, ALongRunPlaysThrough) {
  // One capture run of 1000 frames, 300 output frames, no rest: nothing asks for a change.
  const Stance st = made_stance(1000, 0, 0);
  const CaptureRuns runs(1000, {999});
  std::mt19937_64 rng(1);
  const LowerPlan plan = plan_lower_body(st, runs, {}, 300, kFps, LowerBodyParams{}, rng);
  ASSERT_EQ(plan.segments.size(), 1u);
  expect_covering(plan, runs, 300);
  EXPECT_EQ(st.planted[static_cast<std::size_t>(plan.segments[0].source)], 1);
}

TEST(LowerBody, ChangesAtRunEndsOnlyAtStanceFrames) {
  // Three runs of 200 frames, 900 output frames: at least four changes, each where the stretch left
  // reaches a stance frame, each into a stance frame.
  const Stance st = made_stance(600, 0, 0);
  const CaptureRuns runs(600, {199, 399, 599});
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    std::mt19937_64 rng(seed);
    const LowerPlan plan = plan_lower_body(st, runs, {}, 900, kFps, LowerBodyParams{}, rng);
    expect_covering(plan, runs, 900);
    ASSERT_GE(plan.segments.size(), 5u);
    for (std::size_t k = 1; k < plan.segments.size(); ++k) {
      const LowerSegment& before = plan.segments[k - 1];
      const LowerSegment& now = plan.segments[k];
      EXPECT_EQ(now.change, LowerChange::RunEnd);
      const int left = before.source + before.length;  // where the old stretch would have gone on
      EXPECT_EQ(st.planted[static_cast<std::size_t>(left)], 1) << "seed " << seed << " change " << k;
      EXPECT_EQ(st.planted[static_cast<std::size_t>(now.source)], 1) << "seed " << seed << " change " << k;
      EXPECT_EQ(now.gap, 0.0);
    }
  }
}

// Three runs of 200 frames (made_stance), the feet of the last one 1 leg length wider (pose
// dimension 0).
Stance wide_last_run() {
  Stance st = made_stance(600, 0, 0);
  std::vector<float> pose(st.pose.begin(), st.pose.end());
  for (int f = 400; f < 600; ++f) pose[static_cast<std::size_t>(f) * kStanceDims] = 1.0f;
  st.pose = pose;
  return st;
}

TEST(LowerBody, ChangesGoToTheNearestStance) {
  // Three runs of 200 frames; the feet of the last run stand 1 leg length wider (pose dimension 0),
  // so a change from the first two goes into one of them, and a change from the last into the last:
  // every change's gap is 0 and keeps the pose.
  const Stance st = wide_last_run();
  const CaptureRuns runs(600, {199, 399, 599});
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    std::mt19937_64 rng(seed);
    const LowerPlan plan = plan_lower_body(st, runs, {}, 900, kFps, no_variety(), rng);
    expect_covering(plan, runs, 900);
    for (std::size_t k = 1; k < plan.segments.size(); ++k) {
      const LowerSegment& before = plan.segments[k - 1];
      const int left = before.source + before.length;
      EXPECT_EQ(plan.segments[k].gap, 0.0) << "seed " << seed << " change " << k;
      EXPECT_EQ(left >= 400, plan.segments[k].source >= 400) << "seed " << seed << " change " << k;
    }
  }
}

// 900 output frames from the two runs of 200 frames of the nearest stance (wide_last_run). Once
// their stretches have been played a couple of times, reuse makes the rarely played last frames of
// a run attractive; a change there (9 frames before the run ends) forces the next one from the
// run's last frame, no stance frame, and the plan ping-pongs between the two run ends in 9-frame
// segments. A run-end change goes to a stance with a long run ahead: no segment but the last
// shorter than a second, every change made at a stance frame.
TEST(LowerBody, RunEndChangesGoToLongRuns) {
  const Stance st = wide_last_run();
  const CaptureRuns runs(600, {199, 399, 599});
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    std::mt19937_64 rng(seed);
    const LowerPlan plan = plan_lower_body(st, runs, {}, 900, kFps, no_variety(), rng);
    expect_covering(plan, runs, 900);
    for (std::size_t k = 0; k + 1 < plan.segments.size(); ++k) {
      const LowerSegment& s = plan.segments[k];
      EXPECT_GE(s.length, 30) << "seed " << seed << ": output " << s.start << " plays " << s.length << " frames from "
                              << s.source;
      EXPECT_EQ(st.planted[static_cast<std::size_t>(s.source + s.length)], 1) << "seed " << seed;
    }
  }
}

// Whether the legs are still at every output frame of [from, to), for seeds 1..20.
void expect_still(const Stance& st, const CaptureRuns& runs, const std::vector<Anchor>& rests, int from, int to) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    std::mt19937_64 rng(seed);
    const LowerPlan plan = plan_lower_body(st, runs, rests, 900, kFps, no_variety(), rng);
    expect_covering(plan, runs, 900);
    int moving = 0;
    for (int o = from; o < to; ++o) {
      const int g = played_at(plan, o);
      ASSERT_GE(g, 0);
      moving += st.speed[static_cast<std::size_t>(g)] < st.still_speed ? 0 : 1;
    }
    EXPECT_EQ(moving, 0) << "seed " << seed << ": moving legs at " << moving << " frames of the rest";
  }
}

TEST(LowerBody, RestsGetStillStances) {
  // Runs of 300 and 900 frames; the legs are still only at [400, 500). The output rests at
  // [450, 510) (lead 10 from 440): every seed changes into the still stretch for it.
  const Stance st = made_stance(1200, 400, 500);
  expect_still(st, CaptureRuns(1200, {299, 1199}), {{440, 70, Fixed::Rest, -1, 10}}, 450, 510);
}

// A change at a capture run's end sought in the run's last seconds must not fall inside a rest the
// plan has just changed into a still stance for. Two runs of 300 frames, still legs at [400, 500),
// a rest at [450, 510): the change into source 410 at output 450 plays a run that ends 190 frames
// later, whose end window [460, 638] holds the rest's frames.
TEST(LowerBody, ARunEndChangeDoesNotBreakARest) {
  const Stance st = made_stance(600, 400, 500);
  expect_still(st, CaptureRuns(600, {299, 599}), {{440, 70, Fixed::Rest, -1, 10}}, 450, 510);
}

TEST(LowerBody, SameSeedSamePlan) {
  const Stance st = made_stance(600, 400, 500);
  const CaptureRuns runs(600, {299, 599});
  const std::vector<Anchor> rests = {{440, 70, Fixed::Rest, -1, 10}};
  std::mt19937_64 a(7), b(7);
  const LowerPlan p = plan_lower_body(st, runs, rests, 900, kFps, LowerBodyParams{}, a);
  const LowerPlan q = plan_lower_body(st, runs, rests, 900, kFps, LowerBodyParams{}, b);
  ASSERT_EQ(p.segments.size(), q.segments.size());
  for (std::size_t k = 0; k < p.segments.size(); ++k) {
    EXPECT_EQ(p.segments[k].start, q.segments[k].start);
    EXPECT_EQ(p.segments[k].source, q.segments[k].source);
  }
}

TEST(LowerBody, NothingToPlan) {
  const Stance st = made_stance(100, 0, 0);
  std::mt19937_64 rng(1);
  EXPECT_TRUE(plan_lower_body(st, CaptureRuns(100, {99}), {}, 0, kFps, LowerBodyParams{}, rng).segments.empty());
}

TEST(LowerBody, BadInputThrows) {
  Stance st = made_stance(100, 0, 0);
  std::mt19937_64 rng(1);
  // A rest outside the output.
  EXPECT_THROW(plan_lower_body(st, CaptureRuns(100, {99}), {{50, 20, Fixed::Rest, -1, 0}}, 60, kFps, {}, rng), Error);
  EXPECT_THROW(plan_lower_body(st, CaptureRuns(100, {99}), {{-1, 20, Fixed::Rest, -1, 0}}, 60, kFps, {}, rng), Error);
  // A stance over other frames than the runs'.
  EXPECT_THROW(plan_lower_body(st, CaptureRuns(120, {119}), {}, 60, kFps, {}, rng), Error);
  st.known = false;
  EXPECT_THROW(plan_lower_body(st, CaptureRuns(100, {99}), {}, 60, kFps, {}, rng), Error);
}

}  // namespace
}  // namespace gmg
