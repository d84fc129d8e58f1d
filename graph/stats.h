// Counts of a built graph, as `gmg inspect` prints them.
#pragma once

#include "graph/motion_graph.h"

namespace gmg {

struct GraphStats {
  int frames = 0, clips = 0;
  int onset_nodes = 0, keyword_nodes = 0, break_nodes = 0, key_nodes = 0;
  long natural_edges = 0, unnatural_edges = 0;
  double mean_out_degree = 0.0;
  double share_with_transition = 0.0;                     // frames with at least one unnatural out-edge
  int shortest_subsequence = 0, longest_subsequence = 0;  // between consecutive key nodes
};

GraphStats graph_stats(const MotionGraph& g);

}  // namespace gmg
