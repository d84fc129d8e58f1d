#include "graph/graph_builder.h"

#include <limits>
#include <string>
#include <utility>

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
  out_graph.graph = GraphStorage(std::move(nodes_), std::move(rowstart), std::move(targets));
  out_graph.edge_weights = Samples<double>(std::move(weights));
}

GraphStorage::GraphStorage(std::vector<NodeInfo> nodes, Samples<std::uint32_t> rowstart, Samples<GraphVertex> targets)
    : nodes_(std::move(nodes)), row_starts_(std::move(rowstart)), targets_(std::move(targets)) {
  const std::size_t n = nodes_.size();
  const Samples<std::uint32_t>& rows = row_starts_;
  if (rows.size() != n + 1 || rows.front() != 0 || rows.back() != targets_.size())
    throw Error("graph storage: row starts and targets disagree");
  for (std::size_t f = 0; f < n; ++f)
    if (rows[f] > rows[f + 1]) throw Error("graph storage: row starts are not ascending");
  for (const GraphVertex t : std::as_const(targets_))
    if (t >= n) throw Error("graph storage: an edge target is outside the graph");
}

}  // namespace gmg
