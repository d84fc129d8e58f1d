// Saving and loading built graphs (a versioned binary file with a checksum, "GMGRAPH" magic).
#pragma once

#include <cstdint>
#include <string>

#include "graph/motion_graph.h"

namespace gmg {

// The graph file format this gmg writes and reads (graph_io.cpp): 3 added the reference speech
// features, 4 aligned arrays read in place, 5 the SMPL-X body (shape, per-frame face), 6 the
// reference facts (the assembly's capture facts and the beat end costs, graph/reference_facts.h).
constexpr std::uint32_t kGraphFormatVersion = 6;

// Writes atomically. Throws gmg::Error naming the file when it cannot be written.
void graph_save(const std::string& path, const MotionGraph& g);

// Rejects a file of another format or version, a truncated or damaged one, with a gmg::Error
// naming it. A file with a valid checksum is still checked field by field (it may have been
// made by hand): counts within engine/core/limits.h (joints, depth, frames, fps 1 to 1000),
// finite unit rotations, clips that cover the frames exactly, valid nodes and edges.
MotionGraph graph_load(const std::string& path);

// The same for a file's bytes already in memory; `path` labels errors.
MotionGraph graph_parse(const std::string& bytes, const std::string& path);

// GraphViz DOT and GraphML (Boost's writers) of frames [from, to) (graph_export.cpp). Throws
// gmg::Error when the range is outside the graph or the file cannot be written.
void graph_write_dot(const std::string& path, const MotionGraph& g, int from, int to);
void graph_write_graphml(const std::string& path, const MotionGraph& g, int from, int to);

}  // namespace gmg
