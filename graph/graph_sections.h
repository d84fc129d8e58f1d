// The sections of a graph file that describe the graph (docs/graph_format.md), in the order the
// payload holds them: each section's writer beside its reader, which checks every field as it
// reads it (a file with a valid checksum may still have been made by hand). The key poses, their
// sketch and the motion, read in place and checked by blocks, are in graph_motion_sections.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/motion/motion.h"
#include "engine/motion/npz.h"
#include "graph/graph_archive.h"
#include "graph/motion_graph.h"
#include "graph/params.h"

namespace gmg {

// The build parameters; read_params validates them (graph_params_validate).
void write_params(ArchiveWriter& w, const GraphParams& p);
GraphParams read_params(ArchiveReader& r);

// The skeleton: each joint's name, parent, offset, channels and end site. The reader keeps every
// count within engine/core/limits.h and the hierarchy in order.
void write_skeleton(ArchiveWriter& w, const Skeleton& sk);
Skeleton read_skeleton(ArchiveReader& r);

// The clip table: each clip's name, first frame and frame count. The reader checks the clips are
// contiguous (summed in 64 bits, so counts near 2^31 cannot wrap) and gives the frames they cover
// in `covered`; the caller checks they cover the motion.
void write_clips(ArchiveWriter& w, const std::vector<ClipInfo>& clips);
std::vector<ClipInfo> read_clips(ArchiveReader& r, long long& covered);

// The motion's frame rate and frame count (its values are the file's last section:
// graph_motion_sections.h).
void write_motion_header(ArchiveWriter& w, const Motion& m);
void read_motion_header(ArchiveReader& r, Motion& m);

// Nodes: every frame's kinds, then the labels of the keyword nodes only. The reader also puts
// their index into g (MotionGraph::keys, breaks).
void write_nodes(ArchiveWriter& w, const MotionGraph& g);
std::vector<NodeInfo> read_nodes(ArchiveReader& r, std::size_t frames, MotionGraph& g);

// The edges: row starts, targets, weights and each edge's natural flag. The reader builds the
// graph's storage from `nodes` and them, and takes the mean weight of the unnatural edges
// (MotionGraph::transition_weight, summed in edge order as mean_transition_weight does). Each
// edge's natural flag must be is_natural_edge's: a natural edge steps to the next frame with
// weight 0, a transition never steps to the next frame. Format 10's row starts and targets and
// format 9's weights are read in place (aligned, their pages kept mapped for the flags' pass that
// follows); older formats' are copied.
void write_edges(ArchiveWriter& w, const MotionGraph& g, std::uint32_t version);
void read_edges(ArchiveReader& r, const ArchiveSource& src, std::uint32_t version, std::vector<NodeInfo> nodes,
                MotionGraph& out);

// The speech features (none, or frames x dims finite values) and the motion activity (none, or a
// finite value of at least 0 a frame).
void write_speech(ArchiveWriter& w, const MotionGraph& g);
void read_speech(ArchiveReader& r, const ArchiveSource& src, MotionGraph& g);

// The reference facts (graph/reference_facts.h): whether they are known (0 for a graph made by
// hand without them: then nothing else is), the largest root step, the root's extent (low, high),
// the legs' knee hinges (u32 count, then 3 doubles each), the foot contacts (u8 a frame, aligned)
// and the beat end costs (f32 a frame, aligned). The reader takes all of it, or (a graph made by
// hand) none of it, and checks each value as the assembly and the planner use it.
void write_reference_facts(ArchiveWriter& w, const MotionGraph& g);
void read_reference_facts(ArchiveReader& r, const ArchiveSource& src, MotionGraph& g);

// The body: face dims, the face (frames x dims doubles, aligned), betas, gender, model; all empty
// for a graph of BVH references. The reader copies the face: SmplxBody owns its arrays.
void write_body(ArchiveWriter& w, const SmplxBody& b);
void read_body(ArchiveReader& r, MotionGraph& g);

// The body's layers (format 11 on): the reference's up axis, the lower joints named at build, and
// the stance of every frame (engine/motion/stance.h), read in place. Older formats have none: Y-up,
// layers from the skeleton, the stance unknown.
void write_layers(ArchiveWriter& w, const MotionGraph& g);
void read_layers(ArchiveReader& r, const ArchiveSource& src, MotionGraph& g);

// The reference's face speech (format 12 on, graph/face_speech.h; graph_face_section.cpp): feature
// dims, the features (f32 a dim and frame, aligned), the jaw angle (f32 a frame, aligned, or none),
// the phone symbols, and the phones' starts, ends (f64 graph frames) and symbols (u32). The reader
// checks every value as the face track uses it; older formats have none (not known).
void write_face_speech(ArchiveWriter& w, const MotionGraph& g);
void read_face_speech(ArchiveReader& r, const ArchiveSource& src, MotionGraph& g);

}  // namespace gmg
