// Saving and loading built graphs (a versioned binary file with a checksum, "GMGRAPH" magic).
#pragma once

#include <string>

#include "graph/motion_graph.h"

namespace gmg {

// Writes atomically. Throws gmg::Error naming the file when it cannot be written.
void graph_save(const std::string& path, const MotionGraph& g);

// Rejects a file of another format or version, a truncated or damaged one, with a gmg::Error
// naming it.
MotionGraph graph_load(const std::string& path);

// GraphViz DOT and GraphML (Boost's writers) of frames [from, to) (graph_export.cpp). Throws
// gmg::Error when the range is outside the graph or the file cannot be written.
void graph_write_dot(const std::string& path, const MotionGraph& g, int from, int to);
void graph_write_graphml(const std::string& path, const MotionGraph& g, int from, int to);

}  // namespace gmg
