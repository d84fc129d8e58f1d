// Saving and loading built graphs (a versioned binary file with a checksum, "GMGRAPH" magic).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "graph/motion_graph.h"

namespace gmg {

// The graph file format this gmg writes and reads (graph_io.cpp): 3 added the reference speech
// features, 4 aligned arrays read in place, 5 the SMPL-X body (shape, per-frame face), 6 the
// reference facts (the assembly's capture facts and the beat end costs, graph/reference_facts.h),
// 7 the XXH3 checksum (engine/core/checksum.h) and the motion last, with a checksum per block of
// frames, 8 the key poses' sketch (graph/key_poses.h), 9 the key poses after the part the file's
// checksum covers, with a checksum per key (checked when read: graph_check_key_poses), 10 the
// edges' row starts and targets aligned, read in place. Files of formats 7 to 9 are still read (7
// without a sketch: a reenactment from them gives the same motion, computing more junction costs;
// 7 and 8 have their key poses checked by every load; up to 9 the row starts and targets are
// copied).
constexpr std::uint32_t kGraphFormatVersion = 10;
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
// MotionCheck::OnUse the motion's checksums and values are checked by graph_check_frames (and
// all of it by the load when the graph lacks the key poses or the capture facts, which are then
// computed from every frame).
MotionGraph graph_load(const std::string& path, MotionCheck motion = MotionCheck::OnLoad);

// Checks frames first .. last (clamped to the graph) of a graph loaded with MotionCheck::OnUse,
// the blocks not checked before; nothing for any other graph. Throws gmg::Error naming the file
// when a block's checksum is wrong ("damaged") or a frame holds a value that is not finite or not
// a unit rotation. Safe to call from several threads.
void graph_check_frames(const MotionGraph& g, int first, int last);

// Checks the junction poses of key nodes first .. last (indices into the graph's key frames,
// clamped to them) of a graph loaded with MotionCheck::OnUse from a file of format 9, those not
// checked before; nothing for any other graph. Throws gmg::Error naming the file when a key's
// checksum is wrong ("damaged") or its pose holds a value that is not finite. Safe to call from
// several threads.
void graph_check_key_poses(const MotionGraph& g, std::size_t first, std::size_t last);

// graph_load (MotionCheck::OnLoad) of a file's bytes already in memory; `path` labels errors.
MotionGraph graph_parse(const std::string& bytes, const std::string& path);

// GraphViz DOT and GraphML (Boost's writers) of frames [from, to) (graph_export.cpp). Throws
// gmg::Error when the range is outside the graph or the file cannot be written.
void graph_write_dot(const std::string& path, const MotionGraph& g, int from, int to);
void graph_write_graphml(const std::string& path, const MotionGraph& g, int from, int to);

}  // namespace gmg
