#include "graph/graph_builder.h"

#include <limits>
#include <string>

#include "engine/core/error.h"

namespace gmg {

GraphBuilder::GraphBuilder(int frames) : nodes_(static_cast<std::size_t>(std::max(frames, 0))) {}

void GraphBuilder::add_edge(int from, int to, const EdgeInfo& info) {
  const int n = frame_count();
  if (from < 0 || to < 0 || from >= n || to >= n)
    throw Error("graph builder: edge " + std::to_string(from) + " -> " + std::to_string(to) + " outside the " +
                std::to_string(n) + " frames");
  if (is_natural_edge(static_cast<std::size_t>(from), static_cast<std::size_t>(to)) && info.weight != 0.0)
    throw Error("graph builder: edge " + std::to_string(from) + " -> " + std::to_string(to) +
                " steps to the next frame, which only the natural edge of weight 0 does");
  from_.push_back(static_cast<std::uint32_t>(from));
  to_.push_back(static_cast<std::uint32_t>(to));
  info_.push_back(info);
}

void GraphBuilder::finish(MotionGraph& out_graph) {
  const std::size_t n = nodes_.size(), e = from_.size();
  if (e >= std::numeric_limits<std::uint32_t>::max())
    throw Error("graph builder: " + std::to_string(e) +
                " edges; a graph holds fewer than 2^32 (lower max_transitions)");
  std::vector<std::uint32_t> rowstart(n + 1, 0);
  for (const std::uint32_t f : from_) ++rowstart[f + 1];
  for (std::size_t f = 0; f < n; ++f) rowstart[f + 1] += rowstart[f];
  std::vector<std::uint32_t> next(rowstart.begin(), rowstart.end() - 1);
  std::vector<GraphVertex> targets(e);
  std::vector<double> weights(e);
  for (std::size_t i = 0; i < e; ++i) {
    const std::uint32_t slot = next[from_[i]]++;
    targets[slot] = to_[i];
    weights[slot] = info_[i].weight;
  }
  from_ = {};
  to_ = {};
  info_ = {};
  out_graph.graph = graph_storage_from_arrays(std::move(nodes_), std::move(rowstart), std::move(targets));
  out_graph.edge_weights = Samples<double>(std::move(weights));
}

GraphStorage graph_storage_from_arrays(std::vector<NodeInfo> nodes, std::vector<std::uint32_t> rowstart,
                                       std::vector<GraphVertex> targets) {
  const std::size_t n = nodes.size();
  if (rowstart.size() != n + 1 || rowstart.front() != 0 || rowstart.back() != targets.size())
    throw Error("graph storage: row starts and targets disagree");
  for (std::size_t f = 0; f < n; ++f)
    if (rowstart[f] > rowstart[f + 1]) throw Error("graph storage: row starts are not ascending");
  for (const GraphVertex t : targets)
    if (t >= n) throw Error("graph storage: an edge target is outside the graph");
  // compressed_sparse_row_graph keeps its arrays in public members (Boost documents them as
  // "should be private"): moving into them is the one way to build it without a copy.
  GraphStorage g;
  g.m_forward.m_rowstart = std::move(rowstart);
  g.m_forward.m_column = std::move(targets);
  g.m_vertex_properties = std::move(nodes);
  return g;
}

}  // namespace gmg
