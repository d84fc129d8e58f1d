// Test fixtures shared by the graph tests: hand-checkable features, motions and graphs.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <boost/range/iterator_range.hpp>
#include <glm/gtc/quaternion.hpp>

#include "graph/build.h"
#include "graph/features.h"
#include "graph/graph_builder.h"

namespace gmg::testing {

// Features of a "motion" given directly as 1-D positions (one joint coordinate per frame), so
// distances can be worked out by hand: d(l, r) = |x_l - x_r| + |v_l - v_r|.
inline PoseFeatures line_features(const std::vector<double>& x) {
  PoseFeatures f;
  const int n = static_cast<int>(x.size());
  f.positions = Eigen::MatrixXd::Zero(3, n);
  f.velocities = Eigen::MatrixXd::Zero(3, n);
  for (int i = 0; i < n; ++i) f.positions(0, i) = x[static_cast<std::size_t>(i)];
  for (int i = 1; i < n; ++i) f.velocities(0, i) = x[static_cast<std::size_t>(i)] - x[static_cast<std::size_t>(i - 1)];
  if (n > 1) f.velocities(0, 0) = f.velocities(0, 1);
  return f;
}

// run_end of one continuous run of n frames.
inline std::vector<int> one_run(int n) { return std::vector<int>(static_cast<std::size_t>(n), n - 1); }

// A tiny skeleton motion: the root turns about Z by x radians, swinging the hand around it.
inline Motion line_motion(const std::vector<double>& x) {
  Skeleton sk;
  Joint root;
  root.name = "root";
  root.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition,
                   Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  Joint hand;
  hand.name = "hand";
  hand.parent = 0;
  hand.offset = glm::dvec3(0, 1, 0);
  hand.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  sk.joints = {root, hand};
  Motion m = motion_rest(sk, 30.0, static_cast<int>(x.size()));
  for (int f = 0; f < m.frame_count; ++f)
    m.rotations[m.index(f, 0)] = glm::angleAxis(x[static_cast<std::size_t>(f)], glm::dvec3(0, 0, 1));
  return m;
}

inline std::vector<double> wave(int n, double phase) {
  std::vector<double> x;
  x.reserve(static_cast<std::size_t>(std::max(n, 0)));
  for (int i = 0; i < n; ++i) x.push_back(0.8 * std::sin(i * 0.2 + phase));
  return x;
}

// Two clips (100 and 80 frames) with onsets at a: 10, 40, 70 / b: 5, 30 and keywords
// a: 20 big, 60 this / b: 50 big.
inline MotionGraph two_clip_graph() {
  ClipEvents a{"a.bvh", line_motion(wave(100, 0.0)), {10, 40, 70}, {{20, "big"}, {60, "this"}}};
  ClipEvents b{"b.bvh", line_motion(wave(80, 1.0)), {5, 30}, {{50, "big"}}};
  return graph_build({a, b}, GraphParams{});
}

// A body with legs: pelvis (the root, moving), a spine and a head, and two legs of 0.5 + 0.4 (hip,
// knee, ankle: find_legs finds them). n frames: the spine sways, the knees bend and straighten, the
// pelvis steps forward every 40 frames; speech features (loudness, onsets) under every frame, so
// the graph has activity and beat end costs.
inline ClipEvents legged_clip(const std::string& name, int n, double phase) {
  Skeleton sk;
  auto joint = [&](const char* joint_name, int parent, glm::dvec3 offset) {
    Joint j;
    j.name = joint_name;
    j.parent = parent;
    j.offset = offset;
    j.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
    if (parent < 0) j.channels.insert(j.channels.begin(), {Channel::Xposition, Channel::Yposition, Channel::Zposition});
    sk.joints.push_back(j);
  };
  joint("pelvis", -1, glm::dvec3(0.0));
  joint("spine", 0, glm::dvec3(0, 0.3, 0));
  joint("head", 1, glm::dvec3(0, 0.4, 0));
  joint("left_hip", 0, glm::dvec3(0.1, 0, 0));
  joint("left_knee", 3, glm::dvec3(0, -0.5, 0));
  joint("left_ankle", 4, glm::dvec3(0, -0.4, 0));
  joint("right_hip", 0, glm::dvec3(-0.1, 0, 0));
  joint("right_knee", 6, glm::dvec3(0, -0.5, 0));
  joint("right_ankle", 7, glm::dvec3(0, -0.4, 0));
  Motion m = motion_rest(sk, 30.0, n);
  for (int f = 0; f < n; ++f) {
    const double t = f * 0.15 + phase;
    m.translations[m.index(f, 0)] = glm::dvec3(0.05 * std::floor(f / 40.0), 1.0, 0.0);
    m.rotations[m.index(f, 1)] = glm::angleAxis(0.4 * std::sin(t), glm::dvec3(0, 0, 1));
    m.rotations[m.index(f, 4)] = glm::angleAxis(0.3 + 0.3 * std::sin(0.5 * t), glm::dvec3(1, 0, 0));
  }
  ClipEvents c{name, m, {10, 35, 60}, {{25, "big"}}};
  c.speech_dims = 2;
  for (int f = 0; f < n; ++f) {
    c.speech.push_back(static_cast<float>(-1.0 + std::sin(0.1 * f + phase)));
    c.speech.push_back(static_cast<float>(0.5 * std::cos(0.3 * f)));
  }
  return c;
}

inline MotionGraph legged_graph() {
  return graph_build({legged_clip("a.bvh", 120, 0.0), legged_clip("b.bvh", 90, 1.0)}, GraphParams{});
}

// Gives g one more edge, out of `from` after its own (storage is immutable once built: tests that
// damage a graph rebuild it).
inline void add_edge_to(MotionGraph& g, int from, int to, const EdgeInfo& extra) {
  const int n = static_cast<int>(g.graph.vertex_count());
  GraphBuilder b(n);
  for (int f = 0; f < n; ++f) {
    b.node(f) = g.graph[static_cast<GraphVertex>(f)];
    for (const GraphEdge e : g.graph.out_edges(static_cast<GraphVertex>(f)))
      b.add_edge(f, static_cast<int>(g.graph.target(e)), EdgeInfo{g.weight(e)});
    if (f == from) b.add_edge(from, to, extra);
  }
  b.finish(g);
}

}  // namespace gmg::testing
