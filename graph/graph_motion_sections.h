// The sections of a graph file read in place from its mapping and checked apart from the rest
// (docs/graph_format.md): the key nodes' junction poses with their checksums, the key poses'
// sketch, and last the motion, with a checksum per block of frames (checked by graph_check.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "engine/core/error.h"
#include "engine/motion/motion.h"
#include "graph/graph_archive.h"
#include "graph/graph_io.h"
#include "graph/motion_graph.h"

namespace gmg {

// Frames per checked block of the motion: a reenactment that plays a stretch checks little more
// than it reads, and the table of blocks stays small (docs/decisions.md, "The graph file").
constexpr std::uint32_t kMotionBlockFrames = 64;

// Format 9's key poses, where the file's checksum covers them: their count of values and each key's
// checksum (key_pose_sum; zeros when counting). The values follow the motion's block checksums,
// outside the file's checksum (write_motion).
void write_key_pose_sums(ArchiveWriter& w, const MotionGraph& g);

// Format 9's key pose count and checksums (write_key_pose_sums), in the part the file's checksum
// covers; the values are read after the motion's block checksums (read_motion).
struct KeyPoseTail {
  std::size_t values = 0;
  std::shared_ptr<KeyPoseChecks> checks;
};
KeyPoseTail read_key_pose_sums(ArchiveReader& r, const std::string& path, const MotionGraph& g);

// Formats 7 and 8 keep the key nodes' junction poses where the file's checksum covers them (the
// writer: ArchiveWriter::aligned): none, or keys x junction_pose_dims finite values.
void read_key_poses(ArchiveReader& r, const ArchiveSource& src, MotionGraph& g);

// The key poses' sketch: axes per part (u32), the basis (u64 count, doubles), the scale, the
// values (aligned: read in place). The reader takes none (axes 0: a graph made by hand may have key
// poses without one), or `axes` (1 to 64, at most half the pose's values) per part, an orthonormal
// basis zero off its part, a finite scale and keys x 2 axes finite values.
void write_key_sketch(ArchiveWriter& w, const KeyPoseSketch& s);
void read_key_sketch(ArchiveReader& r, const ArchiveSource& src, MotionGraph& g, bool has_key_poses);

// The motion, last: frames per block, each block's checksum (the last values the file's checksum
// covers), then the rotations and the translations (aligned), which the blocks' checksums cover.
// Counting (nothing written), the checksums are zeros of the same size. `key_poses` (format 9's)
// go between the block checksums and the motion's values.
void write_motion(ArchiveWriter& w, const Motion& m, const Samples<double>* key_poses);

// The motion, the payload's last section (write_motion). `summed_to(bytes)` is called where the
// file's checksum stops, before any motion value is read; it checks the checksum, so the block
// checksums are the file's. The motion's values are then checked by blocks, all of them now
// (MotionCheck::OnLoad, or a graph that lacks what a reenactment would otherwise compute from
// every frame) or each when first used (graph_check_frames). `key_poses`: format 9's, whose values
// come first and are checked likewise (null for older formats); `damaged` makes the error a wrong
// checksum throws.
void read_motion(ArchiveReader& r, MotionGraph& g, const std::string& path, MotionCheck mode,
                 const std::function<void(std::size_t)>& summed_to, const std::function<Error()>& damaged,
                 KeyPoseTail* key_poses);

}  // namespace gmg
