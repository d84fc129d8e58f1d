// Planning a whole reenactment: continuation, retries, determinism.
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

}  // namespace
}  // namespace gmg
