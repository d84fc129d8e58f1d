// Key node detection on the graph (paper 4.1.1; SPEC "Key nodes"): onset, keyword and break
// nodes. The detectors themselves live with their inputs (audio/onset.h, text/keywords.h,
// graph/breaks.h); this step marks their frames on the nodes.
#pragma once

#include <vector>

#include "graph/motion_graph.h"

namespace gmg {

// Marks the key nodes (nodes[f] is global frame f) of one clip whose first frame is global frame `offset`: its onset
// frames, its keyword frames (one label per node: the first keyword listed for a frame wins), and break nodes at the
// capture jumps and at the clip's last frame. Throws gmg::Error naming the clip when an event frame lies outside it.
void mark_key_nodes(std::vector<NodeInfo>& nodes, int offset, const ClipEvents& clip,
                    const std::vector<int>& capture_jumps);

}  // namespace gmg
