// The gesture motion graph (paper 4.1): one node per reference frame, natural edges i -> i+1
// inside continuous runs, unnatural edges where two frames are close enough to jump between.
//
// Stored in compressed sparse row form (GraphStorage): vertex == global frame index, one array of
// row starts and one of targets in source order, and beside them (MotionGraph::edge_weights) the
// edges' weights in the same order, so a graph is a few flat arrays (12 bytes an edge), moves
// without copying, and a loaded graph reads all three in place from its file. It is immutable:
// graph/graph_builder.h makes one from edges in any order. Out-edges of a frame keep the order
// they were added in: the natural edge first, then transitions by ascending target. With
// max_transitions (graph/params.h) edges grow linearly with frames.
//
// The steps that build it live in files named after them: features (pose features and d_pose),
// key_nodes (onset, keyword and break nodes), breaks (capture jumps), continuity (thresholds and
// candidate transitions), pruning (both prunings), build (the whole construction), graph_io
// (save/load), graph_export (DOT/GraphML, through Boost.Graph's writers), stats (counts),
// graph_builder (the storage from edges), neighbours (candidate transitions: exact pass and
// approximate index).
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <boost/range/irange.hpp>

#include "engine/core/files.h"
#include "engine/motion/capture_facts.h"
#include "engine/motion/capture_runs.h"
#include "engine/motion/motion.h"
#include "engine/motion/npz.h"
#include "engine/motion/samples.h"
#include "engine/motion/stance.h"
#include "engine/motion/up_axis.h"
#include "graph/face_speech.h"
#include "graph/keyword_label.h"
#include "graph/params.h"

namespace gmg {

enum NodeKind : std::uint8_t {
  kOnsetNode = 1,    // an audio onset (backtracked) falls on this frame
  kKeywordNode = 2,  // a keyword (or the first of a run of it) starts on this frame
  kBreakNode = 4,    // not naturally continuous with the next frame (clip end, capture jump)
};

struct NodeInfo {
  std::uint8_t kinds = 0;  // NodeKind bits; 0 = regular node
  KeywordLabel keyword;    // the keyword label; non-empty exactly when kinds has kKeywordNode
};

// An edge as graph/graph_builder.h takes it.
struct EdgeInfo {
  double weight = 0.0;  // 0 for natural edges, the pose distance d(l, r) for unnatural ones
};

// An edge is natural (i -> i+1 inside a continuous run) exactly when it steps to the next frame:
// a transition never does (graph/neighbours.h: r != l + 1; graph_builder and the loader refuse
// one), so the storage holds no flag for it.
inline bool is_natural_edge(std::size_t from, std::size_t to) { return to == from + 1; }

// Vertices and edge indices are 32-bit (a graph holds fewer than 2^31 frames, limits.h, and fewer
// than 2^32 edges, graph_builder checks): 4 bytes an edge, and 8 for its weight beside it.
using GraphVertex = std::uint32_t;
using GraphEdge = std::uint32_t;  // an edge's index: into the targets and MotionGraph::edge_weights

// The edges and nodes in compressed sparse row form: the out-edges of vertex v are the edge
// indices row_starts()[v] .. row_starts()[v + 1] - 1, each with its target in targets(). Boost's
// compressed_sparse_row_graph holds the same two arrays but only as vectors of its own; this one
// holds them as Samples, so a graph served from its file (graph_io.h, format 10) reads them in
// place from the mapping: no private copy, and batch workers on one file share its pages.
//
// The constructor checks that the arrays agree (graph_io's load does so before making one). A
// file changed in place under a running gmg can still change the values read from its mapping
// afterwards, so every accessor keeps its result inside the arrays (an edge range within the
// targets, a target within the vertices): such a change gives wrong edges, never an out-of-bounds
// read, and MotionGraph::check_unchanged reports it before anything is written.
class GraphStorage {
 public:
  GraphStorage() = default;
  // Throws gmg::Error when they disagree: rowstart not vertices + 1 values ascending from 0 to the
  // edge count, or a target outside the vertices.
  GraphStorage(std::vector<NodeInfo> nodes, Samples<std::uint32_t> rowstart, Samples<GraphVertex> targets);

  std::size_t vertex_count() const { return nodes_.size(); }
  std::size_t edge_count() const { return targets_.size(); }
  const NodeInfo& operator[](std::size_t v) const { return nodes_[v]; }
  NodeInfo& operator[](std::size_t v) { return nodes_[v]; }  // a label to change (by hand, tests)
  const std::vector<NodeInfo>& nodes() const { return nodes_; }
  // The edge indices of v's out-edges, in their order (a range of GraphEdge).
  boost::integer_range<GraphEdge> out_edges(GraphVertex v) const {
    const std::uint32_t* rows = row_starts_.data();
    const auto edges = static_cast<std::uint32_t>(targets_.size());
    const std::uint32_t first = std::min(rows[v], edges);
    return boost::irange(first, std::max(first, std::min(rows[v + 1], edges)));
  }
  GraphVertex target(GraphEdge e) const {
    return std::min(targets_.data()[e], static_cast<GraphVertex>(nodes_.size() - 1));
  }
  // The arrays themselves, for the file writer and the exporters.
  const Samples<std::uint32_t>& row_starts() const { return row_starts_; }
  const Samples<GraphVertex>& targets() const { return targets_; }

 private:
  std::vector<NodeInfo> nodes_;
  Samples<std::uint32_t> row_starts_{std::vector<std::uint32_t>{0}};  // vertices + 1 values
  Samples<GraphVertex> targets_;
};

// The motion of a graph served from its file and loaded with MotionCheck::OnUse (graph/graph_io.h):
// its frames are checked a block at a time, against the block's checksum in the file and for unit
// rotations and finite translations, when first used (graph_check_frames), so a reenactment reads
// only the stretches it plays. Shared by the copies of the graph; the mutex guards `checked`.
struct MotionBlocks {
  std::string path;                 // the graph file, for errors
  int block_frames = 1;             // frames per block (the last may have fewer)
  std::vector<std::uint64_t> sums;  // each block's checksum: its rotations, then its translations
  std::mutex mutex;
  std::vector<std::uint8_t> checked;  // 1 once the block was found sound
};

// The key poses of a graph served from its file (format 9) and loaded with MotionCheck::OnUse: each
// key's junction pose is checked, against its checksum in the file and for finite values, when first
// read (graph_check_key_poses), so a reenactment reads only the poses its ranking asks for (a
// sample's few ten thousand of a long reference's keys, not all of them at every load). Shared by
// the copies of the graph; the mutex guards `checked`.
struct KeyPoseChecks {
  std::string path;                 // the graph file, for errors
  std::vector<std::uint64_t> sums;  // each key's checksum: its junction_pose_dims values
  std::mutex mutex;
  std::vector<std::uint8_t> checked;  // 1 once the key's pose was found sound
};

// A sketch of every key pose (graph/key_poses.h key_pose_sketch): its coordinates along the first
// `axes` principal axes of the key poses' positions and as many of their velocities. The distance
// between two sketches is at most that between the poses (the axes are orthonormal), so a planning
// job bounds a key's junction cost from below without reading the key's pose
// (search/junction.h key_lower_bounds).
struct KeyPoseSketch {
  int axes = 0;  // per part; 0: no sketch
  // 2 axes rows of junction_pose_dims values, row-major, orthonormal: the first `axes` rows are 0
  // on the velocities, the others 0 on the positions.
  std::vector<double> basis;
  Samples<double> values;  // keys x 2 axes: basis x key pose, key after key
  double scale = 0.0;      // the largest norm of a key pose's positions or velocities (bounds rounding)
};

struct ClipInfo {
  std::string name;     // for reports: the motion file it came from
  int first_frame = 0;  // global index of its first frame
  int frame_count = 0;
};

// A built graph owns its arrays; a loaded one (graph/graph_io.h) reads the motion, the speech
// features and the activity in place from the file's mapping, which `source` keeps (and copies of
// the graph share).
struct MotionGraph {
  Motion motion;                // every reference clip, concatenated in order (node i = frame i)
  std::vector<ClipInfo> clips;  // in order, contiguous, covering all frames
  GraphStorage graph;           // num_vertices == motion.frame_count
  // Every edge's weight (EdgeInfo::weight), in the storage's edge order: graph.edge_count() values,
  // read in place from the file of a loaded graph (format 9 on; copied from older ones).
  Samples<double> edge_weights;
  GraphParams params;  // what it was built with
  // The reference speech under every frame (audio/speech_features.h): frame_count x speech_dims
  // values, frame-major; empty (speech_dims 0) for a graph of clips given without them (a graph
  // file of format 2), which the planner then matches without speech.
  Samples<float> speech;
  int speech_dims = 0;
  // How much the upper body moves at every frame: its mean root-relative joint speed over the
  // graph's median of it (1 = the speaker's typical motion, near 0 = at rest); empty for a graph
  // without speech features. The speech-driven planner prefers rest where the new speech pauses.
  Samples<float> activity;
  // Every key frame's junction pose (graph/key_poses.h), key after key in key_frames() order:
  // keys x junction_pose_dims values; empty for a graph made without them (the planner then
  // computes them from the motion).
  Samples<double> key_poses;
  KeyPoseSketch key_sketch;  // of key_poses; none for a graph made without them, or read from format 7
  // Per-reference values that a reenactment would otherwise recompute from every frame, computed
  // once (graph/reference_facts.h) and, but for the index and the transition scale, kept in the
  // file: the key and break frames (in memory, from the nodes), the mean weight of the transitions,
  // the capture facts of the assembly (root step and extent, foot contacts) and the end cost of
  // every frame (the rhythm cost of stopping a path there: graph/beats.h; empty without activity).
  // A graph made by hand without them (indexed false, capture.known false, beat_cost empty with an
  // activity) has them computed where they are used.
  std::vector<int> keys;           // key frames, ascending
  std::vector<int> breaks;         // break frames, ascending
  double transition_weight = 0.0;  // mean weight of the unnatural edges (0: none)
  bool indexed = false;            // keys, breaks and transition_weight are those of the nodes and edges
  CaptureFacts capture;
  Samples<float> beat_cost;
  // The reference's up axis: its motion here is in Y-up (engine/motion/up_axis.h), and every output
  // is turned back into this axis. Y for graphs of format 10 and older.
  UpAxis up = UpAxis::Y;
  // The lower layer's joints named at build (GraphParams::lower_joints; empty: found from the
  // skeleton, engine/motion/body_layers.h), and the reference's stance under every frame for the
  // lower body's planner (engine/motion/stance.h); unknown without two legs or in graphs of format 10
  // and older (then computed where it is used).
  std::vector<std::string> lower_joints;
  Stance stance;
  // Per frame, 1 where the upper body's jerk spikes (engine/motion/spikes.h); empty in graphs of
  // format 10 and older (then nothing is rationed).
  Samples<std::uint8_t> spikes;
  // The file a loaded graph is served from; null for a graph built in memory.
  std::shared_ptr<const MappedFile> source;
  // Set for a graph loaded with MotionCheck::OnUse: the motion blocks not yet checked. Null when
  // every frame is checked (a built graph, one loaded with MotionCheck::OnLoad).
  std::shared_ptr<MotionBlocks> unchecked_motion;
  // The same for the key poses (format 9 and MotionCheck::OnUse): the keys not yet checked. Null
  // when every key pose is checked.
  std::shared_ptr<KeyPoseChecks> unchecked_key_poses;

  // Throws gmg::Error "FILE: changed while in use" when the file this graph is served from was
  // truncated or written to since it was loaded (its arrays may then hold zeros or other values):
  // called before anything made from the graph is written (graph_io.cpp).
  void check_unchanged() const;
  // The SMPL-X body of references read from .npz (engine/motion/npz.h): their shape, and their face
  // under every frame (body.expressions: frame_count x body.expression_dims, or empty); empty for
  // BVH references. A reenactment plays the face along with the motion.
  SmplxBody body;
  // The reference's speech as the face track reads it (graph/face_speech.h): phones, face features
  // and the jaw's opening under every frame; not known in graphs of format 11 and older.
  FaceSpeech face_speech;

  int frame_count() const { return motion.frame_count; }
  bool has_speech() const { return speech_dims > 0; }
  const float* speech_at(int frame) const {
    return speech.data() + static_cast<std::size_t>(frame) * static_cast<std::size_t>(speech_dims);
  }
  const NodeInfo& node(int frame) const { return graph[static_cast<std::size_t>(frame)]; }
  double weight(GraphEdge e) const { return edge_weights[e]; }
  bool is_key(int frame) const { return node(frame).kinds != 0; }
  // Key nodes of any kind, ascending (a scan of the nodes; graph/reference_facts.h graph_keys reads
  // the index when there is one).
  std::vector<int> key_frames() const;
};

// What one reference clip contributes: its motion and its timed events as motion frames.
struct ClipEvents {
  std::string name;
  Motion motion;
  std::vector<int> onset_frames;                            // clip-local frames
  std::vector<std::pair<int, std::string>> keyword_frames;  // clip-local frame, keyword
  // The up axis the clip was captured in; its motion is already turned into Y-up.
  UpAxis up = UpAxis::Y;
  // The clip's speech features, motion.frame_count x speech_dims (audio/speech_features.h), or
  // empty (speech_dims 0). Every clip of a graph has them, or none does.
  std::vector<float> speech{};
  int speech_dims = 0;
};

// One unnatural edge before it is added.
struct Transition {
  int from = 0, to = 0;
  double weight = 0.0;
};

}  // namespace gmg
