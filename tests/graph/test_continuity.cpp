// Continuity analysis: thresholds, candidates and both prunings on hand-worked features.
#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "graph/continuity.h"
#include "tests/graph/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(Continuity, HandWorkedSawtooth) {
  // x = 0 1 2 3 4 0 1 2 3 4: velocities 1 1 1 1 1 -4 1 1 1 1.
  // l_cn = 1: theta_l = d(l, l+1) = |x_l - x_{l+1}| + |v_l - v_{l+1}|.
  //  theta_0 = 1, theta_1 = 1, theta_2 = 1, theta_3 = 1, theta_4 = 4 + 5 = 9,
  //  theta_5 = 1 + 5 = 6, theta_6..8 = 1, theta_9 (last: uses d(9, 8)) = 1.
  // With l_pn = 1 and exclude_near (|r - l| <= 1 excluded):
  //  l = 0 (x 0, v 1): r = 6 (x 1, v 1) d = 1 <= 1 -> candidate; r = 5 (x 0, v -4) d = 5 no.
  //   r = 2: excluded? |2-0| = 2 > 1, d = 2 > 1 no.  -> edge 0->6 (weight 1)
  //  l = 1 (x 1): r = 5 d = 1 + 5 = 6 no; r = 6: d = 0 -> but pruning 2: edge 0->6 has
  //   |0 - 1| <= 1 and |6 - 6| <= 1 -> dropped; r = 7 (x 2) d = 1 -> also near 0->6 (|7-6| <= 1) dropped;
  //   r = 3? d = 2 no.  So nothing from l = 1.
  const PoseFeatures f = line_features({0, 1, 2, 3, 4, 0, 1, 2, 3, 4});
  GraphParams p;
  p.l_cn = 1;
  p.l_pn = 1;
  p.max_transitions = 0;  // the paper's analysis, every survivor (the bound is worked below)
  const std::vector<Transition> edges = continuity_analysis(f, one_run(10), p);
  ASSERT_FALSE(edges.empty());
  EXPECT_EQ(edges[0].from, 0);
  EXPECT_EQ(edges[0].to, 6);
  EXPECT_DOUBLE_EQ(edges[0].weight, 1.0);
  for (const Transition& t : edges) {
    EXPECT_NE(t.from, 1) << "pruning 2 must drop 1->6 and 1->7 next to 0->6";
    EXPECT_GT(std::abs(t.to - t.from), 1) << "no stutter jumps";
    // Every surviving edge satisfies its threshold: recompute by hand.
    const double d = std::abs(f.positions(0, t.from) - f.positions(0, t.to)) +
                     std::abs(f.velocities(0, t.from) - f.velocities(0, t.to));
    EXPECT_DOUBLE_EQ(t.weight, d);
  }
  // l = 4 (x 4, v 1, theta 9): candidates are all r with d <= 9 except 3, 4, 5 -> 0,1,2 (d 4,3,2
  // + 0) and 6,7,8,9 (d 3,2,1,0). Pruning 1 with l_pn = 1 keeps every one; pruning 2 drops those
  // next to earlier edges (0->6: from 0..1 not near 4) and the reverse check: edge a->b with
  // |a - r| <= 1 and |b - 4| <= 1: none ends near 4 before l = 4. So 4 -> {0, 1, 2, 6, 7, 8, 9}.
  std::vector<int> from4;
  for (const Transition& t : edges)
    if (t.from == 4) from4.push_back(t.to);
  EXPECT_EQ(from4, (std::vector<int>{0, 1, 2, 6, 7, 8, 9}));
  // The default bound, 4 transitions: the nearest four of those by (weight, target) are 9 (d 0),
  // 8 (1), 2 (2) and 7 (2); 6 and 1 (3) and 0 (4) go.
  p.max_transitions = 4;
  std::vector<int> bounded4;
  for (const Transition& t : continuity_analysis(f, one_run(10), p))
    if (t.from == 4) bounded4.push_back(t.to);
  EXPECT_EQ(bounded4, (std::vector<int>{2, 7, 8, 9}));
}

TEST(Continuity, HandWorkedPruningSteps) {
  // Positions only (lambda_vel 0), l_cn 1, l_pn 3, 26 frames in one run:
  //   x_0 = 0, x_1 = 1, x_2..9 = 100, x_10..17 = 0.5, x_18..25 = 100.
  // l = 0: theta_0 = |x_0 - x_1| = 1. Candidates (|r| > 3, d <= 1): r = 10..17 (d 0.5), one run.
  //   Pruning 1 keeps the first, drops the next l_pn - 1 = 2, keeps again: 10, 13, 16.
  //   Pruning 2: no earlier edge. -> 0 -> {10, 13, 16}, weight 0.5 each.
  // l = 1: theta_1 = |x_1 - x_2| = 99: every r with |r - 1| > 3 is a candidate: 5..25, one run.
  //   Pruning 1: 5, 8, 11, 14, 17, 20, 23.
  //   Pruning 2 (edges from a within 3 of l = 1, i.e. 0 -> {10, 13, 16}): drops r within 3 of
  //   10, 13 or 16: 8, 11, 14, 17. The reverse test (an edge from near r to near 1) finds none.
  //   -> 1 -> {5, 20, 23}, weights 99, 99, 99.
  std::vector<double> x(26, 100.0);
  x[0] = 0.0;
  x[1] = 1.0;
  for (int i = 10; i <= 17; ++i) x[static_cast<std::size_t>(i)] = 0.5;
  const PoseFeatures f = line_features(x);
  GraphParams p;
  p.lambda_vel = 0.0;
  p.l_cn = 1;
  p.l_pn = 3;
  const std::vector<Transition> edges = continuity_analysis(f, one_run(26), p);
  std::vector<int> from0, from1;
  std::vector<double> w0, w1;
  for (const Transition& t : edges) {
    if (t.from == 0) from0.push_back(t.to), w0.push_back(t.weight);
    if (t.from == 1) from1.push_back(t.to), w1.push_back(t.weight);
  }
  EXPECT_EQ(from0, (std::vector<int>{10, 13, 16}));
  EXPECT_EQ(w0, (std::vector<double>{0.5, 0.5, 0.5}));
  EXPECT_EQ(from1, (std::vector<int>{5, 20, 23}));
  EXPECT_EQ(w1, (std::vector<double>{99.0, 99.0, 99.0}));
}

// A nearly still pose is within threshold of almost every frame: the densest case for the
// pruning-2 invariant, checked over every pair of edges.
TEST(Continuity, NoTwoTransitionsNearEachOtherOnAStillPose) {
  // A still pose (all frames identical except the tiny drift that makes thresholds positive):
  // x_i = 1e-3 * i. Every frame is within threshold of many others, in one long run.
  std::vector<double> x;
  x.reserve(60);
  for (int i = 0; i < 60; ++i) x.push_back(1e-3 * (i % 3));
  const PoseFeatures f = line_features(x);
  GraphParams p;
  p.l_cn = 5;
  p.l_pn = 10;
  const std::vector<Transition> edges = continuity_analysis(f, one_run(60), p);
  // Out of frame 0 only frames beyond l_pn are reachable (exclude_near).
  std::vector<int> from0;
  for (const Transition& t : edges)
    if (t.from == 0) from0.push_back(t.to);
  ASSERT_FALSE(from0.empty());
  for (int r : from0) EXPECT_GT(r, 10);
  // Pruning 2: no two edges from different left frames with both ends within l_pn.
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      if (edges[i].from == edges[j].from) continue;  // same left frame: pruning 1 governs those
      const bool near = std::abs(edges[i].from - edges[j].from) <= 10 && std::abs(edges[i].to - edges[j].to) <= 10;
      const bool near_reverse =
          std::abs(edges[j].from - edges[i].to) <= 10 && std::abs(edges[j].to - edges[i].from) <= 10;
      EXPECT_FALSE(near || near_reverse) << edges[j].from << "->" << edges[j].to << " vs " << edges[i].from << "->"
                                         << edges[i].to;
    }
}

TEST(Continuity, WeakPruningKeepsMoreEdges) {
  std::vector<double> x;
  x.reserve(200);
  for (int i = 0; i < 200; ++i) x.push_back(std::sin(i * 0.3));
  const PoseFeatures f = line_features(x);
  GraphParams strong;
  GraphParams weak;
  weak.l_pn = 1;
  EXPECT_GT(continuity_analysis(f, one_run(200), weak).size(), continuity_analysis(f, one_run(200), strong).size());
}

TEST(Continuity, MatchesBruteForceCandidatesOnRandomWalk) {
  // The blocked PCA-bounded search must find exactly the candidates a brute-force scan finds;
  // with l_pn = 1 and pruning off in effect (widely separated), compare the threshold test.
  std::srand(7);
  const int n = 300;
  PoseFeatures f;
  f.positions = Eigen::MatrixXd::Zero(30, n);
  for (int i = 1; i < n; ++i) f.positions.col(i) = f.positions.col(i - 1) + 0.1 * Eigen::VectorXd::Random(30);
  f.velocities = Eigen::MatrixXd::Zero(30, n);
  for (int i = 1; i < n; ++i) f.velocities.col(i) = f.positions.col(i) - f.positions.col(i - 1);
  f.velocities.col(0) = f.velocities.col(1);
  GraphParams p;
  p.l_pn = 1;
  p.exclude_near = true;
  p.max_transitions = 0;  // every candidate: the paper's analysis
  const std::vector<Transition> edges = continuity_analysis(f, one_run(n), p);
  auto theta_of = [&](int l) {
    double theta = 0.0;
    int count = 0;
    for (int k = 1; k <= p.l_cn && l + k < n; ++k, ++count) theta += pose_distance(f, l, l + k, p);
    if (count == 0)  // the run's last frame looks back instead
      for (int k = 1; k <= p.l_cn && l - k >= 0; ++k, ++count) theta += pose_distance(f, l, l - k, p);
    return theta / count;
  };
  for (const Transition& t : edges) {
    EXPECT_LE(pose_distance(f, t.from, t.to, p), theta_of(t.from) + 1e-12);
    EXPECT_NEAR(t.weight, pose_distance(f, t.from, t.to, p), 1e-9);
  }
  // Frame 0 is the first left frame: no earlier edge can prune it and l_pn = 1 keeps every
  // candidate, so its edges are exactly the brute-force candidates.
  std::vector<int> brute, found;
  for (int r = 2; r < n; ++r)
    if (pose_distance(f, 0, r, p) <= theta_of(0)) brute.push_back(r);
  for (const Transition& t : edges)
    if (t.from == 0) found.push_back(t.to);
  EXPECT_EQ(found, brute);
  EXPECT_GT(edges.size(), 0u);
}

}  // namespace
}  // namespace gmg
