// Graph construction (paper 4.1): the steps of graph/ in order.
#pragma once

#include <vector>

#include "graph/motion_graph.h"
#include "graph/params.h"

namespace gmg {

// Builds the graph from clips that share one skeleton and fps (gmg::Error otherwise, naming the
// clip; each clip needs >= 2 frames). Key nodes, break nodes, natural edges inside continuous
// runs, then the continuity analysis with both prunings (SPEC "Key nodes" and "Edges"). The
// params are validated first.
MotionGraph graph_build(std::vector<ClipEvents> clips, const GraphParams& params);

}  // namespace gmg
