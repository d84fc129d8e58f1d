// Planning a whole reenactment: continuation, retries, determinism.
#include <random>

#include <gtest/gtest.h>

#include "search/planner.h"
#include "tests/search/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(Planner, ContinuesFromThePreviousPathsSuccessors) {
  // The last onset is far from the clip end, so every accepted first path ends on an onset
  // with successors.
  const MotionGraph g = chain_graph(150, {10, 20, 30, 40, 50, 60, 70, 80, 90, 100}, {}, {});
  const Plan plan = plan_one(g, {{0, 10, Termination::Rhythm, ""}, {10, 10, Termination::Rhythm, ""}}, true);
  ASSERT_TRUE(plan.segments[1].accepted);
  EXPECT_TRUE(plan.segments[1].continued);
  EXPECT_EQ(plan.segments[1].path.front(), plan.segments[0].path.back() + 1);
}

// Three start nodes make equally good first paths (20->30, 30->40, 100->110, each 11 frames); only
// the first one's stop node (30) continues naturally into the second subsequence (the next onset,
// 40, lies 10 frames on; after 40 and 110 the next ones are 60 and 30 frames away). The natural
// planner looks one subsequence ahead among near-equal candidates, whatever the seed.
TEST(Planner, PrefersThePathTheNextSubsequenceCanContinue) {
  const MotionGraph g = chain_graph(200, {20, 30, 40, 100, 110, 140}, {}, {});
  SearchParams p;
  p.l_npaths = 3;
  p.l_feat = 1;
  p.w_full = {1.0};
  p.merge_below = 0;
  p.variety = 0.0;  // every start node available to every seed
  const std::vector<Subsequence> subs = {{0, 10, Termination::Rhythm, ""}, {10, 10, Termination::Rhythm, ""}};
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    std::mt19937_64 rng(seed);
    const Plan plan = plan_reenactment(g, subs, p, rng);
    ASSERT_EQ(plan.segments.size(), 2u);
    EXPECT_EQ(plan.segments[0].path.front(), 20) << "seed " << seed;
    EXPECT_TRUE(plan.segments[1].continued) << "seed " << seed;
  }
}

}  // namespace
}  // namespace gmg
