// The compact graph storage: built from edges in any order, or from arrays in CSR order.
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "graph/graph_builder.h"

namespace gmg {
namespace {

std::vector<std::pair<int, double>> out_of(const MotionGraph& m, int f) {
  std::vector<std::pair<int, double>> out;
  for (auto [it, end] = boost::out_edges(static_cast<GraphVertex>(f), m.graph); it != end; ++it)
    out.emplace_back(static_cast<int>(boost::target(*it, m.graph)), m.weight(*it));
  return out;
}

TEST(GraphBuilder, OutEdgesKeepTheOrderTheyWereAddedIn) {
  GraphBuilder b(4);
  b.node(2).kinds = kKeywordNode;
  b.node(2).keyword = "big";
  b.add_edge(1, 3, {0.5});
  b.add_edge(0, 1, {0.0});
  b.add_edge(1, 2, {0.0});
  b.add_edge(1, 0, {0.25});
  b.add_edge(3, 0, {0.75});
  MotionGraph m;
  b.finish(m);
  const GraphStorage& g = m.graph;
  EXPECT_EQ(boost::num_vertices(g), 4u);
  EXPECT_EQ(boost::num_edges(g), 5u);
  EXPECT_EQ(m.edge_weights.size(), 5u);
  EXPECT_EQ(out_of(m, 0), (std::vector<std::pair<int, double>>{{1, 0.0}}));
  EXPECT_EQ(out_of(m, 1), (std::vector<std::pair<int, double>>{{3, 0.5}, {2, 0.0}, {0, 0.25}}));
  EXPECT_TRUE(out_of(m, 2).empty());
  EXPECT_EQ(out_of(m, 3), (std::vector<std::pair<int, double>>{{0, 0.75}}));
  EXPECT_EQ(g[2].keyword, "big");
  EXPECT_EQ(g[2].kinds, kKeywordNode);
  EXPECT_EQ(b.frame_count(), 0) << "finish leaves the builder empty";
}

TEST(GraphBuilder, EdgesOutsideTheGraphAreRejected) {
  GraphBuilder b(3);
  EXPECT_THROW(b.add_edge(0, 3, {}), Error);
  EXPECT_THROW(b.add_edge(-1, 0, {}), Error);
}

// A step to the next frame is the natural edge (is_natural_edge): weight 0, never a transition.
TEST(GraphBuilder, AStepToTheNextFrameIsTheNaturalEdgeOfWeightZero) {
  GraphBuilder b(4);
  EXPECT_THROW(b.add_edge(1, 2, EdgeInfo{0.5}), Error);
  b.add_edge(1, 2, EdgeInfo{0.0});
  b.add_edge(2, 1, EdgeInfo{0.5});  // a step back is a transition
  b.add_edge(0, 2, EdgeInfo{0.25});
  MotionGraph m;
  b.finish(m);
  EXPECT_EQ(out_of(m, 1), (std::vector<std::pair<int, double>>{{2, 0.0}}));
  EXPECT_EQ(out_of(m, 2), (std::vector<std::pair<int, double>>{{1, 0.5}}));
  EXPECT_TRUE(is_natural_edge(1, 2));
  EXPECT_FALSE(is_natural_edge(2, 1));
  EXPECT_FALSE(is_natural_edge(0, 2));
  EXPECT_FALSE(is_natural_edge(3, 3));
}

TEST(GraphBuilder, ArraysInCsrOrderAreMovedInAndChecked) {
  std::vector<GraphVertex> targets = {1, 2, 0};
  const GraphVertex* data = targets.data();
  MotionGraph m;
  m.graph = graph_storage_from_arrays(std::vector<NodeInfo>(3), {0, 2, 2, 3}, std::move(targets));
  m.edge_weights = Samples<double>(std::vector<double>{0.0, 1.5, 2.5});
  EXPECT_EQ(m.graph.m_forward.m_column.data(), data) << "the targets array is moved, not copied";
  EXPECT_EQ(out_of(m, 0), (std::vector<std::pair<int, double>>{{1, 0.0}, {2, 1.5}}));
  EXPECT_EQ(out_of(m, 2), (std::vector<std::pair<int, double>>{{0, 2.5}}));
  // Row starts that do not end at the edge count, that go down, or a target past the end.
  EXPECT_THROW(graph_storage_from_arrays(std::vector<NodeInfo>(3), {0, 2, 2, 2}, {1, 2, 0}), Error);
  EXPECT_THROW(graph_storage_from_arrays(std::vector<NodeInfo>(3), {0, 2, 1, 3}, {1, 2, 0}), Error);
  EXPECT_THROW(graph_storage_from_arrays(std::vector<NodeInfo>(3), {0, 2, 2, 3}, {1, 2, 3}), Error);
}

}  // namespace
}  // namespace gmg
