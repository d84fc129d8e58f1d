// The poses the junction cost compares (search/junction.h), kept in the graph for its key nodes.
//
// A planning job ranks every key node as a start by its pose distance to where the output is; an
// hour of reference has tens of thousands of key nodes spread over the whole motion, so computing
// their poses at reenactment would read (and keep resident) every page of the motion. The graph
// holds them instead, computed when it is built, and a loaded graph reads them in place from its
// file: a reenactment touches this one compact section and the frames of its paths.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "graph/motion_graph.h"

namespace gmg {

// Values per frame: the root-relative joint positions (3 per joint), then their velocities.
inline int junction_pose_dims(const Skeleton& s) { return 6 * s.joint_count(); }

// Frame f's pose as the junction cost compares it: positions and velocity from forward kinematics
// of f and its natural neighbour (the previous frame when f has one in its run, else the next),
// so the velocity is the capture's own, as in the graph's d_pose.
Eigen::VectorXd junction_pose(const MotionGraph& g, int f);

// junction_pose of every key frame (MotionGraph::key_frames order), one after another.
std::vector<double> key_junction_poses(const MotionGraph& g);

// The sketch of key poses (keys x pose_dims values): the kSketchAxes principal axes of the
// positions and of the velocities of up to 4096 keys spread evenly over them, and every key's
// coordinates along them. No sketch (axes 0) without keys.
inline constexpr int kSketchAxes = 8;
KeyPoseSketch key_pose_sketch(const Samples<double>& key_poses, int pose_dims);

// The same for one clip of a graph being built: its motion, and the nodes of its frames
// (nodes[offset + i] is its frame i); its key frames' poses appended to `out` in frame order.
void append_key_junction_poses(const Motion& clip, const std::vector<NodeInfo>& nodes, int offset,
                               std::vector<double>& out);

}  // namespace gmg
