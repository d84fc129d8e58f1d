// Graph construction: features, break detection, continuity analysis and pruning, storage.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/app/pipeline.h"
#include "graph/motion_graph.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

// Features of a "motion" given directly as 1-D positions (one joint coordinate per frame), so
// distances can be worked out by hand: d(l, r) = |x_l - x_r| + |v_l - v_r|.
PoseFeatures line_features(const std::vector<double>& x) {
  PoseFeatures f;
  const int n = static_cast<int>(x.size());
  f.positions = Eigen::MatrixXd::Zero(n, 3);
  f.velocities = Eigen::MatrixXd::Zero(n, 3);
  for (int i = 0; i < n; ++i) f.positions(i, 0) = x[static_cast<std::size_t>(i)];
  for (int i = 1; i < n; ++i) f.velocities(i, 0) = x[static_cast<std::size_t>(i)] - x[static_cast<std::size_t>(i - 1)];
  if (n > 1) f.velocities(0, 0) = f.velocities(1, 0);
  return f;
}

std::vector<int> one_run(int n) { return std::vector<int>(static_cast<std::size_t>(n), n - 1); }

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
  const std::vector<Transition> edges = continuity_analysis(f, one_run(10), p);
  ASSERT_FALSE(edges.empty());
  EXPECT_EQ(edges[0].from, 0);
  EXPECT_EQ(edges[0].to, 6);
  EXPECT_DOUBLE_EQ(edges[0].weight, 1.0);
  for (const Transition& t : edges) {
    EXPECT_NE(t.from, 1) << "pruning 2 must drop 1->6 and 1->7 next to 0->6";
    EXPECT_GT(std::abs(t.to - t.from), 1) << "no stutter jumps";
    // Every surviving edge satisfies its threshold: recompute by hand.
    const double d = std::abs(f.positions(t.from, 0) - f.positions(t.to, 0)) +
                     std::abs(f.velocities(t.from, 0) - f.velocities(t.to, 0));
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
      const bool near_reverse = std::abs(edges[j].from - edges[i].to) <= 10 && std::abs(edges[j].to - edges[i].from) <= 10;
      EXPECT_FALSE(near || near_reverse) << edges[j].from << "->" << edges[j].to << " vs " << edges[i].from << "->" << edges[i].to;
    }
}

TEST(Continuity, WeakPruningKeepsMoreEdges) {
  std::vector<double> x;
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
  f.positions = Eigen::MatrixXd::Zero(n, 30);
  for (int i = 1; i < n; ++i)
    f.positions.row(i) = f.positions.row(i - 1) + 0.1 * Eigen::RowVectorXd::Random(30);
  f.velocities = Eigen::MatrixXd::Zero(n, 30);
  for (int i = 1; i < n; ++i) f.velocities.row(i) = f.positions.row(i) - f.positions.row(i - 1);
  f.velocities.row(0) = f.velocities.row(1);
  GraphParams p;
  p.l_pn = 1;
  p.exclude_near = true;
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

TEST(Continuity, CaptureJumpBecomesABreak) {
  std::vector<double> x;
  for (int i = 0; i < 50; ++i) x.push_back(0.01 * i + (i >= 25 ? 5.0 : 0.0));
  const PoseFeatures f = line_features(x);
  const std::vector<int> jumps = capture_jump_frames(f, GraphParams{});
  EXPECT_EQ(jumps, (std::vector<int>{24}));
}

// A tiny skeleton motion: the root turns about Z by x radians, swinging the hand around it.
Motion line_motion(const std::vector<double>& x) {
  Skeleton sk;
  Joint root;
  root.name = "root";
  root.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition, Channel::Zrotation, Channel::Xrotation,
                   Channel::Yrotation};
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

std::vector<double> wave(int n, double phase) {
  std::vector<double> x;
  for (int i = 0; i < n; ++i) x.push_back(0.8 * std::sin(i * 0.2 + phase));
  return x;
}

MotionGraph two_clip_graph() {
  ClipEvents a{"a.bvh", line_motion(wave(100, 0.0)), {10, 40, 70}, {{20, "big"}, {60, "this"}}};
  ClipEvents b{"b.bvh", line_motion(wave(80, 1.0)), {5, 30}, {{50, "big"}}};
  return graph_build({a, b}, GraphParams{});
}

TEST(Graph, BuildJoinsClipsWithBreaksAndNoNaturalEdgeAcross) {
  const MotionGraph g = two_clip_graph();
  ASSERT_EQ(g.frame_count(), 180);
  ASSERT_EQ(g.clips.size(), 2u);
  EXPECT_TRUE(g.node(99).kinds & kBreakNode);
  EXPECT_TRUE(g.node(179).kinds & kBreakNode);
  EXPECT_TRUE(g.node(105).kinds & kOnsetNode);  // clip b's onset 5, offset 100
  EXPECT_EQ(g.node(150).keyword, "big");
  EXPECT_TRUE(g.node(20).kinds & kKeywordNode);
  for (auto [it, end] = boost::out_edges(99, g.graph); it != end; ++it) EXPECT_FALSE(g.graph[*it].natural);
  const GraphStats s = graph_stats(g);
  EXPECT_EQ(s.onset_nodes, 5);
  EXPECT_EQ(s.keyword_nodes, 3);
  EXPECT_EQ(s.break_nodes, 2);
  EXPECT_EQ(s.natural_edges, 178);
  EXPECT_GT(s.unnatural_edges, 0);
}

TEST(Graph, SkeletonMismatchIsAnError) {
  Motion other = line_motion(wave(30, 0));
  other.skeleton.joints[1].name = "wrist";
  ClipEvents a{"a.bvh", line_motion(wave(30, 0)), {}, {}};
  ClipEvents b{"b.bvh", other, {}, {}};
  try {
    graph_build({a, b}, GraphParams{});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("b.bvh"), std::string::npos);
  }
}

TEST(Graph, SaveLoadRoundTrip) {
  const MotionGraph g = two_clip_graph();
  gmg::testing::TempDir dir;
  const std::string path = dir.file("g.gmg");
  graph_save(path, g);
  const MotionGraph h = graph_load(path);
  EXPECT_EQ(h.frame_count(), g.frame_count());
  EXPECT_EQ(boost::num_edges(h.graph), boost::num_edges(g.graph));
  EXPECT_EQ(h.node(150).keyword, "big");
  EXPECT_EQ(h.clips[1].name, "b.bvh");
  EXPECT_EQ(h.params.l_pn, g.params.l_pn);
  EXPECT_EQ(h.motion.rotations, g.motion.rotations);
  const GraphStats a = graph_stats(g), b = graph_stats(h);
  EXPECT_EQ(a.unnatural_edges, b.unnatural_edges);
  EXPECT_EQ(a.onset_nodes, b.onset_nodes);
}

TEST(Graph, LoadRejectsWrongDamagedAndTruncatedFiles) {
  const MotionGraph g = two_clip_graph();
  gmg::testing::TempDir dir;
  const std::string path = dir.file("g.gmg");
  graph_save(path, g);
  const std::string bytes = read_file_bytes(path);
  auto expect_error = [&](const std::string& content, const std::string& fragment) {
    const std::string p = dir.file("bad.gmg");
    gmg::testing::write_text(p, content);
    try {
      graph_load(p);
      ADD_FAILURE() << "accepted: " << fragment;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("bad.gmg"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_error("HIERARCHY\nROOT x", "not a gmg graph file");
  expect_error(bytes.substr(0, bytes.size() / 2), "truncated");
  std::string flipped = bytes;
  flipped[bytes.size() / 2] = static_cast<char>(flipped[bytes.size() / 2] ^ 0x40);
  expect_error(flipped, "checksum");
  std::string version = bytes;
  version[8] = 9;
  expect_error(version, "version 9");
}

TEST(Graph, ExportsDotAndGraphml) {
  const MotionGraph g = two_clip_graph();
  gmg::testing::TempDir dir;
  graph_write_dot(dir.file("g.dot"), g, 0, 50);
  graph_write_graphml(dir.file("g.graphml"), g, 0, 50);
  const std::string dot = read_file_bytes(dir.file("g.dot"));
  const std::string xml = read_file_bytes(dir.file("g.graphml"));
  EXPECT_NE(dot.find("digraph"), std::string::npos);
  EXPECT_NE(dot.find("big"), std::string::npos);
  EXPECT_NE(xml.find("<graphml"), std::string::npos);
  EXPECT_NE(xml.find("keyword"), std::string::npos);
  EXPECT_THROW(graph_write_dot(dir.file("x.dot"), g, 50, 500), Error);
}

}  // namespace
}  // namespace gmg

namespace gmg {
namespace {

TEST(GraphRealData, ScottHasOnsetAndKeywordNodesZeggsOnsetAndBreakOnly) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string d = gmg::testing::shared_data_dir();
  Config cfg;
  const MotionGraph scott = graph_build_from_files(
      {{d + "/beat2_scott/2_scott_0_1_1.bvh", {d + "/beat2_scott/2_scott_0_1_1.wav", d + "/beat2_scott/2_scott_0_1_1.TextGrid"}}},
      cfg);
  const GraphStats s = graph_stats(scott);
  EXPECT_EQ(s.frames, 1906);
  EXPECT_EQ(s.onset_nodes, 115);  // librosa's count for this recording (reference_onsets)
  EXPECT_GT(s.keyword_nodes, 20);
  EXPECT_GE(s.break_nodes, 1);
  EXPECT_GT(s.unnatural_edges, 0);
  const MotionGraph zeggs = graph_build_from_files(
      {{d + "/zeggs/067_Speech_2_x_1_0.bvh", {d + "/zeggs/067_Speech_2_x_1_0.wav", ""}}}, cfg);
  const GraphStats z = graph_stats(zeggs);
  EXPECT_EQ(z.frames, 2065);
  EXPECT_EQ(z.keyword_nodes, 0);
  EXPECT_GT(z.onset_nodes, 120);  // librosa finds 130, a few fall past the last motion frame
  EXPECT_LE(z.onset_nodes, 130);
  EXPECT_GE(z.break_nodes, 1);
  EXPECT_TRUE(zeggs.node(2064).kinds & kBreakNode);
  // Two clips with different skeletons cannot share a graph.
  EXPECT_THROW(graph_build_from_files({{d + "/beat2_scott/2_scott_0_1_1.bvh", {d + "/beat2_scott/2_scott_0_1_1.wav", ""}},
                                       {d + "/zeggs/067_Speech_2_x_1_0.bvh", {d + "/zeggs/067_Speech_2_x_1_0.wav", ""}}},
                                      cfg),
               Error);
}

}  // namespace
}  // namespace gmg
