// The compact graph storage: built from edges in any order, or from arrays in CSR order.
#include <memory>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "graph/graph_builder.h"

namespace gmg {
namespace {

std::vector<std::pair<int, double>> out_of(const MotionGraph& m, int f) {
  std::vector<std::pair<int, double>> out;
  for (const GraphEdge e : m.graph.out_edges(static_cast<GraphVertex>(f)))
    out.emplace_back(static_cast<int>(m.graph.target(e)), m.weight(e));
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
  EXPECT_EQ(g.vertex_count(), 4u);
  EXPECT_EQ(g.edge_count(), 5u);
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
  m.graph = GraphStorage(std::vector<NodeInfo>(3), std::vector<std::uint32_t>{0, 2, 2, 3}, std::move(targets));
  m.edge_weights = Samples<double>(std::vector<double>{0.0, 1.5, 2.5});
  EXPECT_EQ(std::as_const(m.graph).targets().data(), data) << "the targets array is moved, not copied";
  EXPECT_EQ(out_of(m, 0), (std::vector<std::pair<int, double>>{{1, 0.0}, {2, 1.5}}));
  EXPECT_EQ(out_of(m, 2), (std::vector<std::pair<int, double>>{{0, 2.5}}));
  // Row starts that do not end at the edge count, that go down, or a target past the end.
  auto storage = [](std::vector<std::uint32_t> rows, std::vector<GraphVertex> columns) {
    return GraphStorage(std::vector<NodeInfo>(3), std::move(rows), std::move(columns));
  };
  EXPECT_THROW(storage({0, 2, 2, 2}, {1, 2, 0}), Error);
  EXPECT_THROW(storage({0, 2, 1, 3}, {1, 2, 0}), Error);
  EXPECT_THROW(storage({0, 2, 2, 3}, {1, 2, 3}), Error);
  EXPECT_THROW(storage({1, 2, 2, 3}, {1, 2, 0}), Error) << "the first row starts at 0";
  EXPECT_THROW(storage({0, 2, 3}, {1, 2, 0}), Error) << "a row start a vertex";
}

// Arrays read in place from a file changed under a running gmg may hold any values after the
// checks: the storage still keeps every index inside its arrays.
TEST(GraphBuilder, ValuesChangedAfterTheChecksStayInsideTheArrays) {
  auto rows = std::make_shared<std::vector<std::uint32_t>>(std::vector<std::uint32_t>{0, 2, 2, 3});
  auto columns = std::make_shared<std::vector<GraphVertex>>(std::vector<GraphVertex>{1, 2, 0});
  const GraphStorage g(std::vector<NodeInfo>(3), Samples<std::uint32_t>::view(rows->data(), rows->size(), rows),
                       Samples<GraphVertex>::view(columns->data(), columns->size(), columns));
  EXPECT_EQ(g.out_edges(0).size(), 2);
  (*rows)[1] = 1000;            // past the edges
  (*rows)[3] = 7;               // past the edges
  (*columns)[0] = 0xffffffffu;  // past the vertices
  EXPECT_EQ(g.out_edges(0).size(), 3) << "row 0 ends at the edge count";
  EXPECT_EQ(g.out_edges(1).size(), 0) << "a row that would go backwards is empty";
  EXPECT_EQ(g.out_edges(2).size(), 1);
  EXPECT_EQ(*g.out_edges(2).begin(), 2u);
  EXPECT_EQ(g.target(0), 2u) << "a target past the vertices is the last one";
}

}  // namespace
}  // namespace gmg
