#include "graph/stats.h"

#include <algorithm>

namespace gmg {

GraphStats graph_stats(const MotionGraph& g) {
  GraphStats s;
  s.frames = g.frame_count();
  s.clips = static_cast<int>(g.clips.size());
  std::vector<char> has_transition(static_cast<std::size_t>(s.frames), 0);
  for (std::size_t f = 0; f < g.graph.vertex_count(); ++f)
    for (const GraphEdge e : g.graph.out_edges(static_cast<GraphVertex>(f))) {
      if (is_natural_edge(f, g.graph.target(e))) {
        ++s.natural_edges;
      } else {
        ++s.unnatural_edges;
        has_transition[f] = 1;
      }
    }
  int previous_key = -1;
  s.shortest_subsequence = 0;
  for (int f = 0; f < s.frames; ++f) {
    const NodeInfo& n = g.node(f);
    if (n.kinds & kOnsetNode) ++s.onset_nodes;
    if (n.kinds & kKeywordNode) ++s.keyword_nodes;
    if (n.kinds & kBreakNode) ++s.break_nodes;
    if (n.kinds) {
      ++s.key_nodes;
      if (previous_key >= 0) {
        const int len = f - previous_key;
        s.shortest_subsequence = s.shortest_subsequence == 0 ? len : std::min(s.shortest_subsequence, len);
        s.longest_subsequence = std::max(s.longest_subsequence, len);
      }
      previous_key = f;
    }
  }
  if (s.frames > 0) {
    s.mean_out_degree = static_cast<double>(s.natural_edges + s.unnatural_edges) / s.frames;
    s.share_with_transition =
        static_cast<double>(std::count(has_transition.begin(), has_transition.end(), 1)) / s.frames;
  }
  return s;
}

}  // namespace gmg
