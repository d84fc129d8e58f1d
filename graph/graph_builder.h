// Making the immutable graph storage (graph/motion_graph.h GraphStorage) from edges added in any
// order. (The file loader makes it from arrays already in compressed sparse row order; the
// storage's constructor, defined here, checks them.)
#pragma once

#include <cstdint>
#include <vector>

#include "graph/motion_graph.h"

namespace gmg {

// Collects node labels and edges, then builds the storage. Out-edges of a frame keep the order
// they were added in (the search visits them in that order).
class GraphBuilder {
 public:
  explicit GraphBuilder(int frames);
  // With the nodes already labelled.
  explicit GraphBuilder(std::vector<NodeInfo> nodes) : nodes_(std::move(nodes)) {}

  int frame_count() const { return static_cast<int>(nodes_.size()); }
  NodeInfo& node(int frame) { return nodes_.at(static_cast<std::size_t>(frame)); }
  std::vector<NodeInfo>& nodes() { return nodes_; }

  // Throws gmg::Error when an end is outside [0, frames), or for a step to the next frame (the
  // natural edge, is_natural_edge) whose weight is not 0.
  void add_edge(int from, int to, const EdgeInfo& info);

  // The storage (a stable counting sort by source) into out_graph.graph and the edges' weights, in
  // its edge order, into out_graph.edge_weights; the builder is left empty.
  void finish(MotionGraph& out_graph);

 private:
  std::vector<NodeInfo> nodes_;
  std::vector<std::uint32_t> from_, to_;
  std::vector<EdgeInfo> info_;
};

}  // namespace gmg
