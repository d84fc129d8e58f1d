// Test fixtures shared by the search tests: hand-made graphs whose paths can be worked out.
#pragma once

#include <random>
#include <string>
#include <utility>
#include <vector>

#include "graph/graph_builder.h"
#include "graph/motion_graph.h"
#include "search/planner.h"

namespace gmg::testing {

// A graph of n frames in one natural chain, with given onset/keyword/break nodes and extra
// unnatural edges. The motion is a rest pose (search does not look at it).
inline MotionGraph chain_graph(int n, const std::vector<int>& onsets,
                               const std::vector<std::pair<int, std::string>>& keywords,
                               const std::vector<Transition>& jumps) {
  MotionGraph g;
  Skeleton sk;
  Joint root;
  root.name = "root";
  root.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition,
                   Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  sk.joints = {root};
  g.motion = motion_rest(sk, 30.0, n);
  for (int f = 0; f < n; ++f) g.motion.translations[static_cast<std::size_t>(f)] = glm::dvec3(f, 0, 0);
  g.clips = {{"chain", 0, n}};
  GraphBuilder b(n);
  for (int f : onsets) b.node(f).kinds |= kOnsetNode;
  for (const auto& [f, w] : keywords) {
    b.node(f).kinds |= kKeywordNode;
    b.node(f).keyword = w;
  }
  b.node(n - 1).kinds |= kBreakNode;
  for (int f = 0; f + 1 < n; ++f) b.add_edge(f, f + 1, EdgeInfo{0.0});
  for (const Transition& t : jumps) b.add_edge(t.from, t.to, EdgeInfo{t.weight});
  b.finish(g);
  return g;
}

// Plans with default search parameters (fallbacks on or off, natural or paper planner) and seed 1.

inline Plan plan_one(const MotionGraph& g, const std::vector<Subsequence>& subs, bool fallbacks,
                     PlannerMode planner = PlannerMode::Natural) {
  SearchParams p;
  p.fallbacks = fallbacks;
  p.planner = planner;
  std::mt19937_64 rng(1);
  return plan_reenactment(g, subs, p, rng);
}

}  // namespace gmg::testing
