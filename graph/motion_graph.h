// The gesture motion graph (paper 4.1): one node per reference frame, natural edges i -> i+1
// inside continuous runs, unnatural edges where two frames are close enough to jump between.
//
// Stored as a Boost.Graph adjacency_list (vecS/vecS, so vertex descriptor == global frame
// index). Edges are O(N * mean degree), frames O(N): memory is linear in the reference length.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <boost/graph/adjacency_list.hpp>

#include "graph/params.h"
#include "engine/motion/motion.h"

namespace gmg {

enum NodeKind : std::uint8_t {
  kOnsetNode = 1,    // an audio onset (backtracked) falls on this frame
  kKeywordNode = 2,  // a keyword (or the first of a run of it) starts on this frame
  kBreakNode = 4,    // not naturally continuous with the next frame (clip end, capture jump)
};

struct NodeInfo {
  std::uint8_t kinds = 0;  // NodeKind bits; 0 = regular node
  std::string keyword;     // the keyword label; non-empty exactly when kinds has kKeywordNode
};

struct EdgeInfo {
  double weight = 0.0;     // 0 for natural edges, the pose distance d(l, r) for unnatural ones
  bool natural = false;    // true for i -> i+1 inside a continuous run
};

using GraphStorage = boost::adjacency_list<boost::vecS, boost::vecS, boost::bidirectionalS, NodeInfo, EdgeInfo>;

struct ClipInfo {
  std::string name;        // for reports: the motion file it came from
  int first_frame = 0;     // global index of its first frame
  int frame_count = 0;
};

struct MotionGraph {
  Motion motion;                 // every reference clip, concatenated in order (node i = frame i)
  std::vector<ClipInfo> clips;   // in order, contiguous, covering all frames
  GraphStorage graph;            // num_vertices == motion.frame_count
  GraphParams params;            // what it was built with

  int frame_count() const { return motion.frame_count; }
  const NodeInfo& node(int frame) const { return graph[static_cast<std::size_t>(frame)]; }
  bool is_key(int frame) const { return node(frame).kinds != 0; }
  // Key nodes of any kind, ascending.
  std::vector<int> key_frames() const;
};

// What one reference clip contributes: its motion and its timed events as motion frames.
struct ClipEvents {
  std::string name;
  Motion motion;
  std::vector<int> onset_frames;                             // clip-local frames
  std::vector<std::pair<int, std::string>> keyword_frames;   // clip-local frame, keyword
};

// Builds the graph from clips that share one skeleton and fps (gmg::Error otherwise, naming
// the clip). Key nodes, break nodes, natural edges, continuity analysis and pruning as in
// SPEC "Key nodes" and "Edges".
MotionGraph graph_build(std::vector<ClipEvents> clips, const GraphParams& params);

// ---- pieces of graph_build, exposed for tests ----

// Pose features (SPEC "Motion representation"): per frame, world joint positions minus the
// root joint's, and their velocity v_t = p_t - p_{t-1} (v_0 = v_1; per clip).
struct PoseFeatures {
  Eigen::MatrixXd positions;   // frames x 3J
  Eigen::MatrixXd velocities;  // frames x 3J
};
PoseFeatures pose_features(const Motion& m);

// d(l, r) = lambda_pos * ||p_l - p_r|| + lambda_vel * ||v_l - v_r||.
double pose_distance(const PoseFeatures& f, int l, int r, const GraphParams& params);

// Frames whose position distance ||p_i - p_{i+1}|| is above break_jump_factor x the median.
std::vector<int> capture_jump_frames(const PoseFeatures& f, const GraphParams& params);

// One unnatural edge before it is added.
struct Transition {
  int from = 0, to = 0;
  double weight = 0.0;
};

// The continuity analysis over frames with the given run structure: run_end[i] is the last
// frame of the continuous run containing i. Returns the surviving unnatural edges, ordered by
// (from, to). Distances are computed in blocks with a PCA lower bound, never as an N x N matrix.
std::vector<Transition> continuity_analysis(const PoseFeatures& f, const std::vector<int>& run_end,
                                            const GraphParams& params);

// Counts of a built graph, as `gmg inspect` prints them.
struct GraphStats {
  int frames = 0, clips = 0;
  int onset_nodes = 0, keyword_nodes = 0, break_nodes = 0, key_nodes = 0;
  long natural_edges = 0, unnatural_edges = 0;
  double mean_out_degree = 0.0;
  double share_with_transition = 0.0;  // frames with at least one unnatural out-edge
  int shortest_subsequence = 0, longest_subsequence = 0;  // between consecutive key nodes
};
GraphStats graph_stats(const MotionGraph& g);

// Save/load: a versioned binary file with a checksum ("GMGRAPH" magic). Load rejects a file of
// another format or version, a truncated or damaged one, with a gmg::Error naming it.
void graph_save(const std::string& path, const MotionGraph& g);
MotionGraph graph_load(const std::string& path);

// GraphViz DOT and GraphML (Boost's writers) of frames [from, to).
void graph_write_dot(const std::string& path, const MotionGraph& g, int from, int to);
void graph_write_graphml(const std::string& path, const MotionGraph& g, int from, int to);

}  // namespace gmg
