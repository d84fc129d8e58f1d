// Graph construction (paper 4.1): the steps of graph/ in order.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "graph/motion_graph.h"
#include "graph/params.h"

namespace gmg {

// Told how a build advances: a stage ("read": clips read, "analyse": frames whose transitions
// are known) and (done, total) in its units. Called from the building thread.
using BuildProgress = std::function<void(const std::string& stage, long done, long total)>;

// Builds the graph from clips that share one skeleton and fps (gmg::Error otherwise, naming the
// clip; each clip needs >= 2 frames). Key nodes, break nodes, natural edges inside continuous
// runs, then the continuity analysis with both prunings (SPEC "Key nodes" and "Edges"). The
// params are validated first.
MotionGraph graph_build(std::vector<ClipEvents> clips, const GraphParams& params, const BuildProgress& progress = {});

}  // namespace gmg
