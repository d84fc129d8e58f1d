// Pruning 1 (runs of consecutive candidates) and pruning 2 (an edge already nearby).
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "graph/pruning.h"

namespace gmg {
namespace {

TEST(Pruning, RunsKeepEveryLpnthFrame) {
  // Runs 3..7, 9..10 and 20. With l_pn 3, each run keeps positions 0, 3, 6, ...: 3, 6 | 9 | 20.
  EXPECT_EQ(prune_runs({3, 4, 5, 6, 7, 9, 10, 20}, 3), (std::vector<int>{3, 6, 9, 20}));
  // l_pn 1 keeps everything; an empty list stays empty.
  EXPECT_EQ(prune_runs({3, 4, 5, 9}, 1), (std::vector<int>{3, 4, 5, 9}));
  EXPECT_TRUE(prune_runs({}, 10).empty());
}

TEST(Pruning, AnEdgeNearbyCoversCandidatesBothWays) {
  EdgeIndex index(100);
  index.add(10, 50);
  index.add(10, 60);
  // 12 -> 52: 10 -> 50 starts within 3 of 12 and ends within 3 of 52.
  EXPECT_TRUE(index.covers(12, 52, 3));
  // 12 -> 56: no edge from 9..15 ends in 53..59, none from 53..59 ends in 9..15.
  EXPECT_FALSE(index.covers(12, 56, 3));
  // With a wider neighbourhood 60 is within 4 of 56.
  EXPECT_TRUE(index.covers(12, 56, 4));
  // The reverse: 50 -> 12 covers 14 -> 48 (an edge from near 48 to near 14).
  index.add(50, 12);
  EXPECT_TRUE(index.covers(14, 48, 3));
  EXPECT_FALSE(index.covers(20, 48, 3));
  // Ranges past the ends of the graph are clipped, not read out of bounds.
  EXPECT_FALSE(index.covers(98, 2, 5));
}

TEST(Pruning, TheIndexReadsEachSourcesOwnTargets) {
  EdgeIndex index(100);
  index.add(3, 40);
  index.add(7, 20);  // sources 4-6 have none
  index.add(7, 90);
  index.add(8, 41);
  // 7's targets are 20 and 90, not 3's 40 nor 8's 41 beside them.
  EXPECT_FALSE(index.any(7, 7, 30, 80));
  EXPECT_TRUE(index.any(7, 7, 85, 95));
  EXPECT_FALSE(index.any(4, 6, 0, 99));
  EXPECT_TRUE(index.any(3, 3, 40, 40));
  // The last source added reaches to the end; sources after it have none yet.
  EXPECT_TRUE(index.any(8, 8, 41, 41));
  EXPECT_FALSE(index.any(9, 99, 0, 99));
}

TEST(Pruning, TheIndexRefusesSourcesOutOfOrderOrRange) {
  EdgeIndex index(10);
  index.add(5, 1);
  index.add(5, 2);  // the same source again: its next target
  EXPECT_THROW(index.add(4, 1), Error);
  EXPECT_THROW(index.add(10, 1), Error);
  EXPECT_THROW(index.add(-1, 1), Error);
  EXPECT_TRUE(index.any(5, 5, 2, 2));
}

}  // namespace
}  // namespace gmg
