// Bounded transitions: candidate sets K_l (graph/neighbours.h), both searches, and the bound on
// transitions out of a frame, against a brute-force reference written from the definitions.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "engine/motion/bvh.h"
#include "engine/synth/synth.h"
#include "graph/continuity.h"
#include "graph/neighbours.h"
#include "graph/pruning.h"
#include "tests/graph/fixtures.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using namespace gmg::testing;

// n frames of a motion that keeps coming back near earlier poses (three incommensurate
// oscillations in 30 dimensions plus noise), so frames have many candidates; no structure a
// search could lean on beyond that.
PoseFeatures looping_motion(int n, unsigned seed) {
  std::srand(seed);
  const Eigen::MatrixXd mix = Eigen::MatrixXd::Random(30, 3);
  PoseFeatures f;
  f.positions = Eigen::MatrixXd::Zero(30, n);
  for (int i = 0; i < n; ++i) {
    Eigen::VectorXd phase(3);
    for (int j = 0; j < 3; ++j) phase(j) = std::sin(i * (0.1 + 0.037 * j) + j);
    f.positions.col(i) = mix * phase + 0.003 * Eigen::VectorXd::Random(30);
  }
  f.velocities = Eigen::MatrixXd::Zero(30, n);
  for (int i = 1; i < n; ++i) f.velocities.col(i) = f.positions.col(i) - f.positions.col(i - 1);
  f.velocities.col(0) = f.velocities.col(1);
  return f;
}

// K_l by definition: every allowed r with d(l, r) <= theta_l, sorted by (d, r), the first k.
std::vector<std::vector<int>> brute_candidates(const PoseFeatures& f, const std::vector<double>& theta,
                                               const GraphParams& p) {
  const int n = f.frame_count();
  const std::size_t k = static_cast<std::size_t>(p.max_transitions * p.candidates_per_transition);
  std::vector<std::vector<int>> out(static_cast<std::size_t>(n));
  for (int l = 0; l < n; ++l) {
    std::vector<std::pair<double, int>> c;
    for (int r = 0; r < n; ++r) {
      if (r == l || r == l + 1 || (p.exclude_near && std::abs(r - l) <= p.l_pn)) continue;
      const double d = pose_distance(f, l, r, p);
      if (d <= theta[static_cast<std::size_t>(l)]) c.emplace_back(d, r);
    }
    std::sort(c.begin(), c.end());
    if (k > 0 && c.size() > k) c.resize(k);
    for (const auto& [d, r] : c) out[static_cast<std::size_t>(l)].push_back(r);
    std::sort(out[static_cast<std::size_t>(l)].begin(), out[static_cast<std::size_t>(l)].end());
  }
  return out;
}

// The bounded analysis by definition: pruning 1 on K_l, pruning 2 against the edges kept so far,
// the max_transitions nearest survivors (by weight, then target).
std::vector<Transition> brute_analysis(const PoseFeatures& f, const std::vector<int>& run_end, const GraphParams& p) {
  const std::vector<double> theta = continuity_thresholds(f, run_end, p);
  const std::vector<std::vector<int>> k = brute_candidates(f, theta, p);
  std::vector<Transition> edges;
  std::vector<std::pair<int, int>> kept;  // all edges so far
  for (int l = 0; l < f.frame_count(); ++l) {
    std::vector<std::pair<double, int>> survivors;
    for (const int r : prune_runs(k[static_cast<std::size_t>(l)], p.l_pn)) {
      bool covered = false;
      for (const auto& [a, b] : kept)
        covered = covered || (std::abs(a - l) <= p.l_pn && std::abs(b - r) <= p.l_pn) ||
                  (std::abs(a - r) <= p.l_pn && std::abs(b - l) <= p.l_pn);
      if (!covered) survivors.emplace_back(pose_distance(f, l, r, p), r);
    }
    std::sort(survivors.begin(), survivors.end());
    if (p.max_transitions > 0 && survivors.size() > static_cast<std::size_t>(p.max_transitions))
      survivors.resize(static_cast<std::size_t>(p.max_transitions));
    std::sort(survivors.begin(), survivors.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
    for (const auto& [d, r] : survivors) {
      edges.push_back({l, r, d});
      kept.emplace_back(l, r);
    }
  }
  return edges;
}

std::vector<std::tuple<int, int, double>> as_tuples(const std::vector<Transition>& edges) {
  std::vector<std::tuple<int, int, double>> out;
  out.reserve(edges.size());
  for (const Transition& t : edges) out.emplace_back(t.from, t.to, t.weight);
  return out;
}

// How many of the n frames have exactly `degree` of the edges (from, to, weight).
long frames_with_out_degree(const std::vector<std::tuple<int, int, double>>& edges, int n, int degree) {
  std::vector<int> out_degree(static_cast<std::size_t>(n), 0);
  for (const auto& [from, to, w] : edges) ++out_degree[static_cast<std::size_t>(from)];
  return static_cast<long>(std::count(out_degree.begin(), out_degree.end(), degree));
}

TEST(Neighbours, BothSearchesFindTheCandidatesByDefinition) {
  const PoseFeatures f = looping_motion(500, 11);
  GraphParams p;
  p.l_pn = 2;
  p.max_transitions = 3;
  p.candidates_per_transition = 4;  // k = 12: binds on most frames of a random walk
  p.ann_checks = 0;                 // the tree searched to the end is exact
  const std::vector<double> theta = continuity_thresholds(f, one_run(500), p);
  const auto expected = brute_candidates(f, theta, p);
  std::size_t bound = 0;
  for (const auto& k : expected) bound += k.size() == 12 ? 1 : 0;
  ASSERT_GT(bound, 100u) << "the bound must bind for the test to mean anything";
  EXPECT_EQ(candidate_sets(f, theta, p, NeighbourSearch::Exact), expected);
  EXPECT_EQ(candidate_sets(f, theta, p, NeighbourSearch::Approximate), expected);
  p.max_transitions = 0;  // unbounded: every candidate under the threshold
  const auto all = brute_candidates(f, theta, p);
  EXPECT_EQ(candidate_sets(f, theta, p, NeighbourSearch::Exact), all);
  EXPECT_EQ(candidate_sets(f, theta, p, NeighbourSearch::Approximate), all);
}

TEST(Neighbours, NoFrameHasMoreThanMaxTransitionsAndTheyAreTheNearest) {
  const PoseFeatures f = looping_motion(400, 5);
  GraphParams p;
  p.l_pn = 1;
  p.max_transitions = 2;
  const std::vector<Transition> edges = continuity_analysis(f, one_run(400), p);
  std::vector<int> out_degree(400, 0);
  for (const Transition& t : edges) ++out_degree[static_cast<std::size_t>(t.from)];
  EXPECT_LE(*std::max_element(out_degree.begin(), out_degree.end()), 2);
  EXPECT_GT(std::count(out_degree.begin(), out_degree.end(), 2), 20) << "the bound must bind";
  EXPECT_EQ(as_tuples(edges), as_tuples(brute_analysis(f, one_run(400), p)));
}

TEST(Neighbours, ApproximateSearchedExhaustivelyGivesTheExactEdgeSet) {
  const PoseFeatures f = looping_motion(600, 3);
  GraphParams p;
  p.l_pn = 2;
  p.max_transitions = 4;
  p.ann_checks = 0;
  p.neighbours = NeighbourSearch::Exact;
  const std::vector<Transition> exact = continuity_analysis(f, one_run(600), p);
  p.neighbours = NeighbourSearch::Approximate;
  const std::vector<Transition> approximate = continuity_analysis(f, one_run(600), p);
  ASSERT_GT(exact.size(), 100u);
  EXPECT_EQ(as_tuples(approximate), as_tuples(exact));
  // With a small budget the search gives up early on some frames: fewer candidates, never others.
  p.ann_checks = 24;
  const std::vector<double> theta = continuity_thresholds(f, one_run(600), p);
  const auto found = candidate_sets(f, theta, p, NeighbourSearch::Approximate);
  const auto truth = candidate_sets(f, theta, p, NeighbourSearch::Exact);
  const double recall = candidate_recall(found, truth);
  EXPECT_LT(recall, 1.0);
  EXPECT_GT(recall, 0.0);
}

// With a budget the frames of each leaf of the tree share one walk of kLeafWalkChecks times the
// per-frame budget: a budget of a sixth of the frames (kLeafWalkChecks 6) lets that walk examine
// every frame, so every frame finds its exact candidates, where a walk of the per-frame budget
// alone would stop after a sixth of them.
TEST(Neighbours, ALeafsFramesShareAWalkOfSixTimesTheirBudget) {
  static_assert(kLeafWalkChecks == 6, "the test's budgets are a sixth of the frames");
  const PoseFeatures f = looping_motion(600, 3);
  GraphParams p;
  p.l_pn = 2;
  const std::vector<double> theta = continuity_thresholds(f, one_run(600), p);
  const auto truth = candidate_sets(f, theta, p, NeighbourSearch::Exact);
  p.ann_checks = 100;  // 6 x 100 = 600 frames: the whole reference
  EXPECT_EQ(candidate_sets(f, theta, p, NeighbourSearch::Approximate), truth);
  // A walk of 100 frames (what a budget of 100 examined alone) stops early on some leaves.
  p.ann_checks = 17;  // 6 x 17 = 102 frames: the walk stops after 7 leaves
  const double recall = candidate_recall(candidate_sets(f, theta, p, NeighbourSearch::Approximate), truth);
  EXPECT_LT(recall, 1.0) << "a walk of 100 frames must miss members";
  EXPECT_GT(recall, 0.0);
}

TEST(Neighbours, UnboundedIsThePapersAnalysis) {
  // max_transitions 0: every candidate under the threshold goes through both prunings (the
  // definition of brute_analysis with no bound), whichever search finds them.
  const PoseFeatures f = looping_motion(300, 9);
  GraphParams p;
  p.l_pn = 3;
  p.max_transitions = 0;
  const auto expected = as_tuples(brute_analysis(f, one_run(300), p));
  p.neighbours = NeighbourSearch::Exact;
  EXPECT_EQ(as_tuples(continuity_analysis(f, one_run(300), p)), expected);
  p.neighbours = NeighbourSearch::Approximate;
  p.ann_checks = 0;
  EXPECT_EQ(as_tuples(continuity_analysis(f, one_run(300), p)), expected);
}

TEST(Neighbours, CandidateRecallCountsSharedPairs) {
  // exact {1, 2} {3} {} against found {1} {3, 4} {5}: 2 of 3 exact pairs found.
  EXPECT_DOUBLE_EQ(candidate_recall({{1}, {3, 4}, {5}}, {{1, 2}, {3}, {}}), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(candidate_recall({{}}, {{}}), 1.0);
}

TEST(Neighbours, AutoSearchesExactlyUpToExactFrames) {
  GraphParams p;
  p.exact_frames = 100;
  EXPECT_EQ(neighbour_search_for(p, 100), NeighbourSearch::Exact);
  EXPECT_EQ(neighbour_search_for(p, 101), NeighbourSearch::Approximate);
  p.neighbours = NeighbourSearch::Exact;
  EXPECT_EQ(neighbour_search_for(p, 101), NeighbourSearch::Exact);
  EXPECT_EQ(candidate_limit(p), p.max_transitions * p.candidates_per_transition);
  p.max_transitions = 0;
  EXPECT_EQ(candidate_limit(p), 0);
}

TEST(Neighbours, AutosBudgetGrowsAQuarterPerDoublingPastAnHour) {
  GraphParams p;  // ann_checks 2000, exact_frames 15000, kAnnChecksFrames 108000
  EXPECT_EQ(search_checks(p, 15000, NeighbourSearch::Auto), 0);  // searched to the end
  EXPECT_EQ(search_checks(p, 15001, NeighbourSearch::Auto), 2000);
  EXPECT_EQ(search_checks(p, 108000, NeighbourSearch::Auto), 2000);
  EXPECT_EQ(search_checks(p, 216000, NeighbourSearch::Auto), 2500);   // 2000 * (1 + 1/4)
  EXPECT_EQ(search_checks(p, 432000, NeighbourSearch::Auto), 3000);   // two doublings
  EXPECT_EQ(search_checks(p, 1728000, NeighbourSearch::Auto), 4000);  // four: 16 h
  // Asked for by name, the budget is ann_checks at every length.
  EXPECT_EQ(search_checks(p, 1728000, NeighbourSearch::Approximate), 2000);
  EXPECT_EQ(search_checks(p, 1728000, NeighbourSearch::Exact), 0);
  p.ann_checks = 0;  // 0 stays "to the end"
  EXPECT_EQ(search_checks(p, 1728000, NeighbourSearch::Auto), 0);
}

// One rule at every length: the bound applies below exact_frames as above it, and the two
// searches Auto switches between give the same edges, so a reference just under exact_frames
// and one just over get the same analysis.
TEST(Neighbours, TheSameBoundedEdgesOnBothSidesOfExactFrames) {
  const PoseFeatures f = looping_motion(400, 5);
  GraphParams p;
  p.l_pn = 1;
  p.max_transitions = 2;
  p.ann_checks = 0;
  const auto expected = as_tuples(brute_analysis(f, one_run(400), p));
  ASSERT_GT(frames_with_out_degree(expected, 400, 2), 20) << "the bound must bind";
  p.exact_frames = 400;  // Auto: the tree searched to the end
  EXPECT_EQ(as_tuples(continuity_analysis(f, one_run(400), p)), expected);
  p.exact_frames = 399;  // Auto: the tree within ann_checks (0 here: also to the end)
  EXPECT_EQ(as_tuples(continuity_analysis(f, one_run(400), p)), expected);
  GraphParams unbounded = p;
  unbounded.max_transitions = 0;
  EXPECT_GT(continuity_analysis(f, one_run(400), unbounded).size(), expected.size());
}

// Every frame's K_l from find_run over runs of 37 frames of the tree's order (across the groups of
// 16 the exact search takes together) against find's of the frame alone; returns the members seen.
std::size_t expect_runs_find_what_frames_alone_find(const CandidateSearch& finder) {
  const std::vector<int>& order = finder.query_order();
  const int n = finder.frames();
  CandidateScratch alone;
  std::vector<Candidate> expected;
  std::vector<CandidateScratch> scratch;
  std::vector<std::vector<Candidate>> together;
  std::size_t members = 0;
  for (int first = 0; first < n; first += 37) {
    const int count = std::min(37, n - first);
    finder.find_run(first, count, scratch, together);
    for (int i = 0; i < count; ++i) {
      const int l = order[static_cast<std::size_t>(first + i)];
      finder.find(l, alone, expected);
      const std::vector<Candidate>& got = together[static_cast<std::size_t>(i)];
      EXPECT_EQ(got.size(), expected.size()) << "frame " << l;
      for (std::size_t j = 0; j < std::min(got.size(), expected.size()); ++j) {
        EXPECT_EQ(got[j].r, expected[j].r) << "frame " << l;
        EXPECT_EQ(got[j].d, expected[j].d) << "frame " << l;
      }
      members += got.size();
    }
  }
  return members;
}

// The exact search of several neighbouring frames together (find_run) finds for each what its own
// search finds, for runs that start and end anywhere in the tree's order; so does the budgeted one,
// which searches each frame with the other frames of its leaf however the runs cut the leaves.
TEST(Neighbours, FramesSearchedTogetherFindWhatEachFindsAlone) {
  const PoseFeatures f = looping_motion(700, 7);
  for (const NeighbourSearch search : {NeighbourSearch::Exact, NeighbourSearch::Approximate}) {
    for (const int max_transitions : {4, 0}) {
      SCOPED_TRACE(std::to_string(static_cast<int>(search)) + " " + std::to_string(max_transitions));
      GraphParams p;
      p.l_pn = 2;
      p.max_transitions = max_transitions;
      p.candidates_per_transition = 5;
      p.ann_checks = 64;
      const std::vector<double> theta = continuity_thresholds(f, one_run(700), p);
      const CandidateSearch finder(f, theta, p, search);
      EXPECT_GT(expect_runs_find_what_frames_alone_find(finder), 700u * 3)
          << "frames must have candidates for the test to mean anything";
    }
  }
}

// The parallel search keeps a frame's first survivors for pruning 2 and searches a frame again when
// they run out before its bound is settled: the edges are the same however few it keeps (1 makes
// nearly every frame with two or more edges search again).
TEST(Neighbours, TheEdgesDoNotDependOnHowManySurvivorsAreKept) {
  const PoseFeatures f = looping_motion(400, 5);
  GraphParams p;
  p.l_pn = 1;
  p.max_transitions = 2;
  const auto expected = as_tuples(brute_analysis(f, one_run(400), p));
  ASSERT_GT(frames_with_out_degree(expected, 400, 2), 20) << "frames must need a second survivor";
  for (const std::size_t kept : {std::size_t{1}, std::size_t{2}, std::size_t{16}, std::size_t{0}}) {
    SCOPED_TRACE(kept);
    EXPECT_EQ(as_tuples(continuity_analysis(f, one_run(400), p, {}, kept)), expected);
  }
}

TEST(Neighbours, SurvivorsKeptAreAllOfThemWithin512MiBAndAtLeast16) {
  GraphParams p;  // max_transitions 4, candidates_per_transition 32: K_l holds at most 128
  EXPECT_EQ(kept_survivors(12810, p), 128u);
  EXPECT_EQ(kept_survivors(524288, p), 128u);  // 512 MiB of 8-byte survivors: 128 a frame
  EXPECT_EQ(kept_survivors(524289, p), 127u);
  // 512 MiB over 838,860 frames: 80.00004 a frame.
  EXPECT_EQ(kept_survivors(838860, p), 80u);
  EXPECT_EQ(kept_survivors(2052000, p), 32u);  // 32.7
  EXPECT_EQ(kept_survivors(100000000, p), 16u);
  p.max_transitions = 10;  // K_l up to 320: a frame's count is one byte
  EXPECT_EQ(kept_survivors(1000, p), 255u);
  p.max_transitions = 1;
  p.candidates_per_transition = 12;
  EXPECT_EQ(kept_survivors(1000, p), 12u);
  p.max_transitions = 0;  // no bound: every survivor, in a list
  EXPECT_EQ(kept_survivors(1000, p), 0u);
}

// A budgeted search that cannot see every frame still finds >= 95% of the exact candidate pairs.
// The default budget (2,000 a frame, a leaf's walk 6 x that) covers nearly the whole of these short
// references and would give 1, so each test sets one that binds: a leaf's walk over a fifth of
// the 427 s speaker's 12,810 frames (400 a frame, 2,400 a leaf) and a third of the BEAT2 clip's
// 1,906 (100, 600). At 4 h the default's walk covers 4 % of the frames, with recall 0.99
// (docs/performance.md); a small tree is the harder case for a given share, since its 128
// candidates are a larger part of it.
void expect_recall(const Motion& m, int ann_checks) {
  const PoseFeatures f = pose_features(m);
  GraphParams p;
  p.ann_checks = ann_checks;
  const std::vector<double> theta = continuity_thresholds(f, one_run(f.frame_count()), p);
  const double recall = candidate_recall(candidate_sets(f, theta, p, NeighbourSearch::Approximate),
                                         candidate_sets(f, theta, p, NeighbourSearch::Exact));
  std::cout << "recall of the exact candidate set: " << recall << " (" << f.frame_count() << " frames, " << ann_checks
            << " checks a frame)\n";
  EXPECT_LT(recall, 1.0) << "the budget must bind";
  EXPECT_GE(recall, 0.95);
}

TEST(NeighboursRealData, ApproximateRecallOnBeat2AtLeast95Percent) {
  GMG_REQUIRE_SHARED_DATA();
  expect_recall(bvh_read(shared_data_dir() + "/beat2_scott/2_scott_0_1_1.bvh"), 100);
}

TEST(Neighbours, ApproximateRecallOnA427sSyntheticSpeakerAtLeast95Percent) {
  SynthSpec spec;
  spec.duration_s = 427.0;  // the paper's longest reference
  spec.seed = 3;
  spec.joint_count_hint = 25;
  expect_recall(synth_speaker(spec).motion, 400);
}

}  // namespace
}  // namespace gmg
