// Checking a graph file's motion and key poses against their checksums and for sound values: all
// of them by the load (MotionCheck::OnLoad), or a block of frames or a key at a time, when first
// used, for a graph served from its file (MotionCheck::OnUse, graph_io.h), so that a reenactment
// from a long reference reads only the stretches it plays and the poses it ranks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/motion/motion.h"
#include "graph/motion_graph.h"

namespace gmg {

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

// The checks the load runs on the whole motion and all key poses, and the writer's block sums.

// The checksum of the frames of one motion block: their rotations, then their translations.
std::uint64_t motion_block_sum(const Motion& m, std::size_t first, std::size_t frames);

// Blocks whose pages a pass over the motion gives back together.
constexpr std::size_t kReleaseBlocks = 32;

// Gives back the pages of motion values from .. to - 1 (of both arrays) when they are read in place
// from a file's mapping, from the page boundary at or before `from` (blocks do not end on page
// boundaries: a stretch's last page, part of the next block's, goes with the next stretch).
void release_motion(const Motion& m, std::size_t from, std::size_t to);

// What checking motion blocks found.
struct BlockCheck {
  bool sound = true;
  bool damaged = false;                         // a block's checksum is wrong (else: a value is bad)
  std::size_t first_frame = 0, last_frame = 0;  // the damaged block's frames
  std::size_t bad_frame = 0;                    // the first frame with a value that is not sound
};

// Checks blocks b0 .. b1 - 1 of g's motion: each block's checksum, then its values (unit
// rotations, finite translations); stops at the first that fails. `release`: each block's pages
// are given back after it (a pass over all of a served graph's motion leaves nothing resident).
BlockCheck check_motion_blocks(const Motion& m, const MotionBlocks& mb, std::size_t b0, std::size_t b1, bool release);

// What checking key poses found.
struct KeyCheck {
  bool sound = true;
  bool damaged = false;  // the key's checksum is wrong (else: a value is not finite)
  std::size_t key = 0;   // the first key that is not sound
};

// Checks the poses of keys k0 .. k1 - 1 against their checksums and for finite values; stops at the
// first that fails. `release`: the pages are given back every few MB (a pass over all of them
// leaves nothing resident).
KeyCheck check_key_poses(const MotionGraph& g, const KeyPoseChecks& kc, std::size_t k0, std::size_t k1, bool release);

// Which key pose check_key_poses did not find sound, for errors.
std::string key_pose_named(const MotionGraph& g, const KeyCheck& c);

}  // namespace gmg
