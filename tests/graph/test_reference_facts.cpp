// The per-reference values a graph keeps: the key and break index, the transition scale, the
// assembly's capture facts and the beat end costs, computed once when the graph is built.
#include <vector>

#include <gtest/gtest.h>

#include "graph/beats.h"
#include "graph/reference_facts.h"
#include "tests/graph/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(ReferenceFacts, TheIndexIsTheNodesKeysAndBreaks) {
  const MotionGraph g = two_clip_graph();
  ASSERT_TRUE(g.indexed);
  EXPECT_EQ(g.keys, g.key_frames());
  std::vector<int> breaks;
  for (int f = 0; f < g.frame_count(); ++f)
    if (g.node(f).kinds & kBreakNode) breaks.push_back(f);
  EXPECT_EQ(g.breaks, breaks);
  EXPECT_EQ(graph_runs(g).breaks(), breaks);
  // A graph made without the index is scanned: the same keys and runs.
  MotionGraph bare = g;
  bare.indexed = false;
  bare.keys.clear();
  bare.breaks.clear();
  EXPECT_EQ(graph_keys(bare), g.keys);
  EXPECT_EQ(graph_runs(bare).breaks(), breaks);
}

TEST(ReferenceFacts, TheTransitionScaleIsTheMeanUnnaturalWeight) {
  const MotionGraph g = two_clip_graph();
  double sum = 0.0;
  long count = 0;
  for (std::size_t f = 0; f < g.graph.vertex_count(); ++f)
    for (const GraphEdge e : g.graph.out_edges(static_cast<GraphVertex>(f)))
      if (g.graph.target(e) != f + 1) {
        sum += g.weight(e);
        ++count;
      }
  ASSERT_GT(count, 0);
  EXPECT_EQ(g.transition_weight, sum / static_cast<double>(count));
  EXPECT_EQ(mean_transition_weight(g), g.transition_weight);
  GraphBuilder none(3);
  none.add_edge(0, 1, EdgeInfo{0.0});
  MotionGraph without;
  none.finish(without);
  EXPECT_EQ(mean_transition_weight(without), 0.0);
}

// The facts a built graph keeps are those of the functions that compute them over every frame.
TEST(ReferenceFacts, ABuiltGraphKeepsItsCaptureFactsAndBeatCosts) {
  const MotionGraph g = legged_graph();
  const CaptureRuns runs = graph_runs(g);
  const CaptureFacts c = capture_facts(g.motion, runs);
  ASSERT_TRUE(g.capture.known);
  EXPECT_EQ(g.capture.largest_root_step, c.largest_root_step);
  EXPECT_EQ(g.capture.largest_root_step, 0.05);  // the pelvis's steps inside a clip
  EXPECT_EQ(g.capture.root_lo, c.root_lo);
  EXPECT_EQ(g.capture.root_hi, c.root_hi);
  ASSERT_EQ(g.capture.knee_hinges.size(), 2u);
  EXPECT_EQ(g.capture.knee_hinges, c.knee_hinges);
  EXPECT_NEAR(g.capture.knee_hinges[0].x, -1.0, 1e-12);  // the left knee bends about x
  EXPECT_EQ(g.capture.knee_hinges[1], glm::dvec3(0.0));  // the right one never bends
  EXPECT_EQ(g.capture.foot_flags, c.foot_flags);
  EXPECT_EQ(g.capture.foot_flags.size(), static_cast<std::size_t>(g.frame_count()));
  ASSERT_EQ(g.activity.size(), static_cast<std::size_t>(g.frame_count()));
  EXPECT_EQ(g.beat_cost, Samples<float>(beat_end_costs(g.activity, runs, g.motion.fps)));
}

}  // namespace
}  // namespace gmg
