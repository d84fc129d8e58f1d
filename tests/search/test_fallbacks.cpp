// The three termination fallbacks and the failure count with fallbacks off.
#include <gtest/gtest.h>

#include "engine/pipeline/pipeline.h"
#include "search/fallbacks.h"
#include "search/planner.h"
#include "tests/search/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(Fallbacks, KeywordFallsBackToRhythm) {
  const MotionGraph g = chain_graph(60, {10, 20, 30, 40, 50}, {{15, "big"}}, {});
  const Plan plan = plan_one(g, {{0, 10, Termination::Keyword, "zebra"}}, true);
  EXPECT_EQ(plan.segments[0].fallback, Fallback::KeywordToRhythm);
  EXPECT_TRUE(plan.segments[0].accepted);
  EXPECT_EQ(plan.fallback_count(Fallback::KeywordToRhythm), 1);
  const Plan off = plan_one(g, {{0, 10, Termination::Keyword, "zebra"}}, false);
  EXPECT_EQ(off.failure_count(), 1);
  EXPECT_TRUE(off.segments[0].failure);
  EXPECT_EQ(off.fallback_count(Fallback::KeywordToRhythm), 0);
}

TEST(Fallbacks, PathsStoppingTooEarlyIgnoreStops) {
  // Onsets every 4 frames: every path terminates after <= 5 nodes; a 30-frame target needs
  // paths that run through stops.
  std::vector<int> onsets;
  for (int f = 4; f < 200; f += 4) onsets.push_back(f);
  const MotionGraph g = chain_graph(200, onsets, {}, {});
  const Plan plan = plan_one(g, {{0, 30, Termination::Rhythm, ""}}, true);
  EXPECT_EQ(plan.segments[0].fallback, Fallback::IgnoreStops);
  EXPECT_TRUE(plan.segments[0].accepted);
  const std::size_t n = plan.segments[0].path.size();
  EXPECT_GE(n, 27u);
  EXPECT_LE(n, 33u);
  EXPECT_EQ(plan.fallback_count(Fallback::IgnoreStops), 1);
  EXPECT_EQ(plan_one(g, {{0, 30, Termination::Rhythm, ""}}, false).failure_count(), 1);
}

// The paper's fallback 3.
TEST(Fallbacks, HopelessTargetHoldsTheLastFrame) {
  const MotionGraph g = chain_graph(20, {5, 10}, {}, {});
  const Plan plan =
      plan_one(g, {{0, 10, Termination::Rhythm, ""}, {10, 300, Termination::Rhythm, ""}}, true, PlannerMode::Paper);
  ASSERT_EQ(plan.segments.size(), 2u);
  EXPECT_TRUE(plan.segments[0].accepted);
  EXPECT_EQ(plan.segments[1].fallback, Fallback::HoldLastFrame);
  EXPECT_EQ(plan.segments[1].path, std::vector<int>{plan.segments[0].path.back()});
  EXPECT_EQ(plan.fallback_count(Fallback::HoldLastFrame), 1);
  const Plan off =
      plan_one(g, {{0, 10, Termination::Rhythm, ""}, {10, 300, Termination::Rhythm, ""}}, false, PlannerMode::Paper);
  EXPECT_EQ(off.failure_count(), 1);
  // Even a failure yields frames: the assembled motion has the full length.
  EXPECT_EQ(assemble_motion(g, off, BlendParams{}).frame_count, 310);
}

// The natural planner's fallback 3: the capture plays on from where the output was, instead of
// freezing on a held frame (here until the capture ends: no 300-frame path exists in 200 frames).
TEST(Fallbacks, HopelessTargetContinuesTheMotion) {
  const MotionGraph g = chain_graph(200, {5, 10}, {}, {});
  const Plan plan = plan_one(g, {{0, 10, Termination::Rhythm, ""}, {10, 300, Termination::Rhythm, ""}}, true);
  ASSERT_EQ(plan.segments.size(), 2u);
  ASSERT_TRUE(plan.segments[0].accepted);
  EXPECT_EQ(plan.segments[1].fallback, Fallback::ContinueMotion);
  const std::vector<int>& first = plan.segments[0].path;
  const std::vector<int>& second = plan.segments[1].path;
  EXPECT_EQ(second.front(), first.back() + 1);
  EXPECT_EQ(second.back(), 199);
  for (std::size_t i = 1; i < second.size(); ++i) EXPECT_EQ(second[i], second[i - 1] + 1);
  EXPECT_TRUE(plan.segments[1].continued);
  EXPECT_EQ(plan.fallback_count(Fallback::ContinueMotion), 1);
}

}  // namespace
}  // namespace gmg
