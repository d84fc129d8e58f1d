// Test fixtures shared by the graph tests: hand-checkable features, motions and graphs.
#pragma once

#include <algorithm>
#include <cmath>
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

// The storage of g with one more edge, out of `from` after its own (storage is immutable once
// built: tests that damage a graph rebuild it).
inline GraphStorage with_edge(const GraphStorage& g, int from, int to, const EdgeInfo& extra) {
  const int n = static_cast<int>(boost::num_vertices(g));
  GraphBuilder b(n);
  for (int f = 0; f < n; ++f) {
    b.node(f) = g[static_cast<std::size_t>(f)];
    for (const auto& e : boost::make_iterator_range(boost::out_edges(static_cast<std::size_t>(f), g)))
      b.add_edge(f, static_cast<int>(boost::target(e, g)), g[e]);
    if (f == from) b.add_edge(from, to, extra);
  }
  return b.finish();
}

}  // namespace gmg::testing
