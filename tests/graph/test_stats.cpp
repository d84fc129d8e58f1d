// Graph counts as `gmg inspect` prints them.
#include <gtest/gtest.h>

#include "graph/stats.h"
#include "tests/graph/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(Stats, CountsOfTheTwoClipGraph) {
  const MotionGraph g = two_clip_graph();
  const GraphStats s = graph_stats(g);
  EXPECT_EQ(s.frames, 180);
  EXPECT_EQ(s.clips, 2);
  EXPECT_EQ(s.onset_nodes, 5);
  EXPECT_EQ(s.keyword_nodes, 3);
  EXPECT_EQ(s.break_nodes, 2);  // the two clip ends: the waves have no capture jump
  // Key frames 10 20 40 60 70 99 | 105 130 150 179: gaps 10 20 20 10 29 6 25 20 29.
  EXPECT_EQ(s.key_nodes, 10);
  EXPECT_EQ(s.shortest_subsequence, 6);
  EXPECT_EQ(s.longest_subsequence, 29);
  EXPECT_EQ(s.natural_edges, 99 + 79);
  EXPECT_GT(s.unnatural_edges, 0);
  EXPECT_DOUBLE_EQ(s.mean_out_degree, static_cast<double>(s.natural_edges + s.unnatural_edges) / 180.0);
  EXPECT_GT(s.share_with_transition, 0.0);
  EXPECT_LE(s.share_with_transition, 1.0);
}

}  // namespace
}  // namespace gmg
