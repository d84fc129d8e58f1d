// The junction cost of the natural planner (SPEC "Junction-aware search"): how far a candidate
// start frame is, in pose, from the frame the output would naturally continue into.
//
// J(c, s) = d_pose(c, s) / w, with the graph's own d_pose (graph/features.h) and w the mean weight
// of its unnatural edges, so one unit of J is what a typical transition of this graph costs.
// Features are computed on demand for the frames asked about (forward kinematics of a frame and
// its neighbour, graph/key_poses.h), so a planning job on an hour-long graph does not pay for every
// frame; those of the key nodes, which every subsequence ranks, are read in place from the graph.
#pragma once

#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "graph/motion_graph.h"

namespace gmg {

class JunctionCost {
 public:
  explicit JunctionCost(const MotionGraph& g);

  // J(c, s); 0 when s is c.
  double cost(int c, int s);

  // J(c, s) for every s in `frames`, vectorised over a cached matrix of those frames' features.
  void costs(int c, const std::vector<int>& frames, std::vector<double>& out);

  // J(c, s) for the key nodes `keys` (indices into the graph's key frames, ascending), vectorised
  // over the key poses where they lie in the graph, a run of consecutive keys at a time, without
  // copying them. Each value is the one `costs` gives for that key. Needs the graph's key poses
  // (has_key_poses); those of a graph served from its file are checked as they are first read
  // (graph/graph_check.h graph_check_key_poses: a damaged one throws gmg::Error naming the file).
  void key_costs(int c, const std::vector<std::size_t>& keys, std::vector<double>& out);
  bool has_key_poses() const { return !keys_.empty(); }

  // A lower bound of J(c, s) for each of the key nodes `keys` (as key_costs), never above the value
  // key_costs gives for it, from the graph's sketch of the key poses (MotionGraph::key_sketch: a
  // few coordinates per key, so a ranking that skips the keys whose bound cannot rank does not
  // read their poses); all 0 for a graph without a sketch.
  void key_lower_bounds(int c, const std::vector<std::size_t>& keys, std::vector<double>& out);

  // The largest root-relative joint distance (file units) between frames a and b: the raw pose
  // gap a report shows.
  double largest_joint_gap(int a, int b);

  double normaliser() const { return normaliser_; }

 private:
  using Pose = Eigen::Map<const Eigen::VectorXd>;
  // Root-relative positions and velocity of frame f, as one column [lambda_pos p; lambda_vel v]:
  // in place in the graph for a key node, else computed once and cached.
  Pose features(int f);

  const MotionGraph& g_;
  double normaliser_ = 1.0;
  std::unordered_map<int, Eigen::VectorXd> cache_;
  std::vector<int> keys_;  // the key frames, when the graph holds their poses
  // The batch matrix of `costs`: columns for the frames of the last list asked about.
  std::vector<int> batch_frames_;
  Eigen::MatrixXd batch_pos_, batch_vel_;
};

}  // namespace gmg
