// Saving and loading built graphs (a versioned binary file with a checksum, "GMGRAPH" magic; its
// layout: docs/graph_format.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "graph/motion_graph.h"

namespace gmg {

// The graph file format this gmg writes, and the oldest it reads; docs/graph_format.md describes
// the layout and what each version changed.
constexpr std::uint32_t kGraphFormatVersion = 12;
constexpr std::uint32_t kOldestGraphFormatRead = 7;

// Writes atomically, in format `version` (kOldestGraphFormatRead to kGraphFormatVersion: 7 leaves
// out the key sketch, for a gmg that reads only that). Throws gmg::Error naming the file when it
// cannot be written or for a version it does not write.
void graph_save(const std::string& path, const MotionGraph& g, std::uint32_t version = kGraphFormatVersion);

// When the motion's values and the key poses are checked (the rest of the file is checked by every
// load).
enum class MotionCheck {
  OnLoad,  // all of them, by the load
  OnUse,   // a block of frames at a time, by graph_check_frames, and a key pose at a time, by
           // graph_check_key_poses, before they are read: a load that reads the motion only where it
           // is played and the key poses only where they are ranked (a reenactment from a long
           // reference)
};

// Rejects a file of another format or version, a truncated or damaged one, with a gmg::Error
// naming it. A file with a valid checksum is still checked field by field (it may have been
// made by hand): counts within engine/core/limits.h (joints, depth, frames, fps 1 to 1000),
// finite unit rotations, clips that cover the frames exactly, valid nodes and edges. With
// MotionCheck::OnUse the motion's checksums and values are checked by graph_check_frames
// (graph/graph_check.h; all of it by the load when the graph lacks the key poses or the capture
// facts, which are then computed from every frame).
MotionGraph graph_load(const std::string& path, MotionCheck motion = MotionCheck::OnLoad);

// graph_load (MotionCheck::OnLoad) of a file's bytes already in memory; `path` labels errors.
MotionGraph graph_parse(const std::string& bytes, const std::string& path);

// GraphViz DOT and GraphML (Boost's writers) of frames [from, to) (graph_export.cpp). Throws
// gmg::Error when the range is outside the graph or the file cannot be written.
void graph_write_dot(const std::string& path, const MotionGraph& g, int from, int to);
void graph_write_graphml(const std::string& path, const MotionGraph& g, int from, int to);

}  // namespace gmg
