// The natural planner's junction cost: start nodes near the pose the output would continue into.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "graph/graph_builder.h"
#include "graph/graph_io.h"
#include "graph/key_poses.h"
#include "search/junction.h"
#include "search/planner.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

// A root and a hand 10 units away; the root turns about Z by angle[f], so the hand's pose depends
// on the frame. Natural edges everywhere except out of the break nodes; no unnatural edges.
MotionGraph posed_graph(const std::vector<double>& angle, const std::vector<int>& onsets,
                        const std::vector<int>& breaks, const std::vector<Transition>& jumps = {}) {
  Skeleton sk;
  Joint root;
  root.name = "root";
  root.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  Joint hand;
  hand.name = "hand";
  hand.parent = 0;
  hand.offset = glm::dvec3(10, 0, 0);
  sk.joints = {root, hand};
  const int n = static_cast<int>(angle.size());
  MotionGraph g;
  g.motion = motion_rest(sk, 30.0, n);
  for (int f = 0; f < n; ++f)
    g.motion.rotations[g.motion.index(f, 0)] = glm::angleAxis(angle[static_cast<std::size_t>(f)], glm::dvec3(0, 0, 1));
  g.clips = {{"posed", 0, n}};
  GraphBuilder b(n);
  for (int f : onsets) b.node(f).kinds |= kOnsetNode;
  for (int f : breaks) b.node(f).kinds |= kBreakNode;
  for (int f = 0; f + 1 < n; ++f)
    if (!(b.node(f).kinds & kBreakNode)) b.add_edge(f, f + 1, EdgeInfo{0.0});
  for (const Transition& t : jumps) b.add_edge(t.from, t.to, EdgeInfo{t.weight});
  b.finish(g);
  return g;
}

// Frames 0..19 hold the pose of angle 0 and end in a break; frames 20..59 hold angle pi (far), frames
// 60..99 angle 0 again (near). Onsets 30, 40 and 70, 80 give the two candidates 30 and 70 the same
// rhythm (l_feat 1: the next key 10 frames on). The first subsequence is one frame long and takes
// key 18 (its next key, 19, is one frame on); the second (10 frames) cannot continue past the break
// at 19, so it starts afresh: from 30 or from 70, equally good but for the pose.
TEST(Junction, PlannerPicksTheStartNearThePreviousEnd) {
  std::vector<double> angle(100, 0.0);
  for (int f = 20; f < 60; ++f) angle[static_cast<std::size_t>(f)] = 3.14159;
  const MotionGraph g = posed_graph(angle, {18, 30, 40, 70, 80}, {19, 99});
  SearchParams p;
  p.l_npaths = 2;  // the two best key nodes only: no random frames join the beam
  p.l_feat = 1;
  p.w_full = {1.0};
  p.merge_below = 0;
  p.variety = 0.0;
  const std::vector<Subsequence> subs = {{0, 1, Termination::Rhythm, ""}, {1, 10, Termination::Rhythm, ""}};
  std::mt19937_64 rng(1);
  const Plan natural = plan_reenactment(g, subs, p, rng);
  ASSERT_EQ(natural.segments.size(), 2u);
  EXPECT_EQ(natural.segments[0].path, std::vector<int>{18});
  ASSERT_TRUE(natural.segments[1].accepted);
  EXPECT_EQ(natural.segments[1].path.front(), 70);
  EXPECT_EQ(natural.segments[1].junction_from, 19);
  EXPECT_NEAR(natural.segments[1].junction_gap, 0.0, 1e-9);
  // Without the junction cost (the paper's planner) the tie goes to the earlier key node: 30.
  p.planner = PlannerMode::Paper;
  const Plan paper = plan_reenactment(g, subs, p, rng);
  EXPECT_EQ(paper.segments[1].path.front(), 30);
  EXPECT_NEAR(paper.segments[1].junction_gap, 20.0, 1e-4);  // the hand on the other side
}

TEST(Junction, CostIsThePoseDistanceOverTheMeanTransitionWeight) {
  std::vector<double> angle(40, 0.0);
  for (int f = 0; f < 40; ++f) angle[static_cast<std::size_t>(f)] = 0.05 * f;
  const MotionGraph g = posed_graph(angle, {}, {39}, {{5, 30, 2.0}, {6, 20, 4.0}});
  JunctionCost j(g);
  EXPECT_DOUBLE_EQ(j.normaliser(), 3.0);
  // Frames 10 and 20: the hand 10 away at angles 0.5 and 1.0 (chord 2 * 10 * sin(0.25)), both moving
  // at 0.05 rad per frame (velocities of equal length 2 * 10 * sin(0.025), 0.5 rad apart).
  const double chord = 20.0 * std::sin(0.25);
  const double speed = 20.0 * std::sin(0.025);
  const double velocity_gap = 2.0 * speed * std::sin(0.25);
  EXPECT_NEAR(j.cost(10, 20), (chord + velocity_gap) / 3.0, 1e-9);
  EXPECT_EQ(j.cost(10, 10), 0.0);
  std::vector<double> costs;
  j.costs(10, {10, 20, 30}, costs);
  EXPECT_EQ(costs[0], 0.0);
  EXPECT_NEAR(costs[1], j.cost(10, 20), 1e-12);
  EXPECT_NEAR(j.largest_joint_gap(10, 20), chord, 1e-9);
}

// With the key poses in the graph, the key nodes' costs are read in place, for all of them or for
// some of them, and each equals what the copied batch of `costs` gives, bit for bit.
TEST(Junction, KeyCostsReadInPlaceEqualTheBatch) {
  std::vector<double> angle(120);
  for (int f = 0; f < 120; ++f) angle[static_cast<std::size_t>(f)] = 0.03 * f + 0.4 * std::sin(0.2 * f);
  MotionGraph g = posed_graph(angle, {5, 17, 30, 44, 58, 61, 80, 95, 101}, {119}, {{5, 80, 2.0}});
  g.key_poses = key_junction_poses(g);
  JunctionCost j(g);
  ASSERT_TRUE(j.has_key_poses());
  const std::vector<int> keys = g.key_frames();
  for (int c : {17, 33}) {  // a key node and a frame that is not one
    std::vector<double> batch, in_place, strided;
    JunctionCost fresh(g);
    fresh.costs(c, keys, batch);
    std::vector<std::size_t> all(keys.size());
    for (std::size_t m = 0; m < all.size(); ++m) all[m] = m;
    j.key_costs(c, all, in_place);
    EXPECT_EQ(in_place, batch);
    const std::vector<std::size_t> some = {1, 2, 3, 6, 8, 9};  // runs 1-3, 6, 8-9
    j.key_costs(c, some, strided);
    ASSERT_EQ(strided.size(), some.size());
    for (std::size_t m = 0; m < some.size(); ++m) EXPECT_EQ(strided[m], batch[some[m]]) << "key " << some[m];
  }
}
// The key poses of a graph served from its file (format 9, MotionCheck::OnUse) are checked as they
// are read: key_costs checks the keys it is asked for and no other, a key node's own pose is checked
// when it is the frame the output is at, and a pose whose bytes changed in the file throws, naming
// the file and the key, where it is read.
TEST(Junction, KeyCostsOfAServedGraphCheckTheKeysTheyRead) {
  std::vector<double> angle(120);
  for (int f = 0; f < 120; ++f) angle[static_cast<std::size_t>(f)] = 0.03 * f + 0.4 * std::sin(0.2 * f);
  MotionGraph g = posed_graph(angle, {5, 17, 30, 44, 58, 61, 80, 95, 101}, {119}, {{5, 80, 2.0}});
  g.key_poses = key_junction_poses(g);
  const std::size_t keys = g.key_frames().size(), dims = g.key_poses.size() / keys;
  gmg::testing::TempDir dir;
  const std::string path = dir.file("posed.gmg");
  graph_save(path, g);
  {
    const MotionGraph h = graph_load(path, MotionCheck::OnUse);
    ASSERT_NE(h.unchecked_key_poses, nullptr);
    JunctionCost j(h);
    std::vector<double> out;
    j.key_costs(33, {1, 2, 3, 6}, out);  // 33 is not a key node
    EXPECT_EQ(h.unchecked_key_poses->checked, std::vector<std::uint8_t>({0, 1, 1, 1, 0, 0, 1, 0, 0, 0}));
    j.key_costs(17, {8}, out);  // 17 is key node 1; 101 key node 8
    EXPECT_EQ(h.unchecked_key_poses->checked, std::vector<std::uint8_t>({0, 1, 1, 1, 0, 0, 1, 0, 1, 0}));
    EXPECT_GT(j.cost(58, 33), 0.0);  // 58 is key node 4
    EXPECT_EQ(h.unchecked_key_poses->checked, std::vector<std::uint8_t>({0, 1, 1, 1, 1, 0, 1, 0, 1, 0}));
    ASSERT_EQ(keys, 10u);
  }
  std::string bytes = read_file_bytes(path);
  const std::string pose(reinterpret_cast<const char*>(g.key_poses.data() + 7 * dims), dims * sizeof(double));
  const std::size_t at = bytes.find(pose);
  ASSERT_NE(at, std::string::npos);
  bytes[at] = static_cast<char>(bytes[at] ^ 0x10);
  gmg::testing::write_text(path, bytes);
  const MotionGraph h = graph_load(path, MotionCheck::OnUse);
  JunctionCost j(h);
  std::vector<double> out;
  j.key_costs(33, {5, 6, 8, 9}, out);
  try {
    j.key_costs(33, {6, 7, 8}, out);
    ADD_FAILURE() << "a damaged key pose was read";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": graph file is damaged (checksum mismatch in the junction pose of key node 7 (frame 95))");
  }
}

// A chain of six joints whose every joint turns about two axes with its own slow waves: poses of
// 36 values (18 positions, 18 velocities), more than the sketch's 8 axes per part. Onsets every
// `every` frames, one break at the end, a few transitions.
MotionGraph waving_graph(int n, int every) {
  Skeleton sk;
  for (int j = 0; j < 6; ++j) {
    Joint joint;
    joint.name = "j" + std::to_string(j);
    joint.parent = j - 1;
    joint.offset = j == 0 ? glm::dvec3(0) : glm::dvec3(0, 8, 1);
    joint.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
    sk.joints.push_back(joint);
  }
  MotionGraph g;
  g.motion = motion_rest(sk, 30.0, n);
  for (int f = 0; f < n; ++f)
    for (int j = 0; j < 6; ++j)
      g.motion.rotations[g.motion.index(f, j)] =
          glm::angleAxis(0.6 * std::sin(0.037 * (j + 1) * f + j), glm::dvec3(0, 0, 1)) *
          glm::angleAxis(0.4 * std::cos(0.051 * (7 - j) * f), glm::dvec3(1, 0, 0));
  g.clips = {{"waving", 0, n}};
  GraphBuilder b(n);
  for (int f = every / 2; f < n; f += every) b.node(f).kinds |= kOnsetNode;
  b.node(n - 1).kinds |= kBreakNode;
  for (int f = 0; f + 1 < n; ++f)
    if (!(b.node(f).kinds & kBreakNode)) b.add_edge(f, f + 1, EdgeInfo{0.0});
  for (int f = 7; f + 40 < n; f += 37) b.add_edge(f, f + 40, EdgeInfo{1.0 + 0.01 * f});
  b.finish(g);
  g.key_poses = key_junction_poses(g);
  g.key_sketch = key_pose_sketch(g.key_poses, junction_pose_dims(sk));
  return g;
}

// The sketch's bound is never above the key's cost as key_costs gives it, for any key and any
// frame the output is at, and is most of it; a graph without a sketch bounds every key by 0.
TEST(Junction, KeyLowerBoundsNeverExceedTheKeyCosts) {
  MotionGraph g = waving_graph(600, 5);
  ASSERT_EQ(g.key_sketch.axes, kSketchAxes);
  ASSERT_LT(kSketchAxes, junction_pose_dims(g.motion.skeleton) / 2);
  JunctionCost j(g);
  std::vector<std::size_t> all(g.key_frames().size());
  for (std::size_t m = 0; m < all.size(); ++m) all[m] = m;
  double bounded = 0.0, total = 0.0;
  for (int c : {2, 77, 302, 599}) {  // a key node (302) and frames that are not
    std::vector<double> costs, bounds;
    j.key_costs(c, all, costs);
    j.key_lower_bounds(c, all, bounds);
    ASSERT_EQ(bounds.size(), costs.size());
    for (std::size_t m = 0; m < all.size(); ++m) {
      EXPECT_LE(bounds[m], costs[m]) << "frame " << c << ", key " << m;
      EXPECT_GE(bounds[m], 0.0);
      bounded += bounds[m];
      total += costs[m];
    }
  }
  EXPECT_GT(bounded, 0.8 * total) << "the poses vary in few directions: the sketch holds most of each distance";
  g.key_sketch = KeyPoseSketch();
  JunctionCost none(g);
  std::vector<double> zeros;
  none.key_lower_bounds(77, all, zeros);
  EXPECT_EQ(zeros, std::vector<double>(all.size(), 0.0));
}

// Ranking with the bound skips keys, never a plan's choice: the plans of a graph with and without
// its sketch are the same, segment by segment.
TEST(Junction, TheSketchChangesNoPlan) {
  const MotionGraph with = waving_graph(900, 3);
  MotionGraph without = waving_graph(900, 3);
  without.key_sketch = KeyPoseSketch();
  std::vector<Subsequence> subs;
  for (int start = 0, k = 0; start < 400; ++k) {
    const int length = 6 + (k * 7) % 17;
    subs.push_back({start, length, Termination::Rhythm, ""});
    start += length;
  }
  SearchParams p;
  p.l_npaths = 4;  // the ranking's first 4 x 8 candidates are complete without bounds: the rest are bounded
  p.retries = 1;
  p.variety = 0.0;  // no stretch withheld: every key node competes on its pose
  for (int seed : {1, 2, 3}) {
    std::mt19937_64 a(static_cast<unsigned>(seed)), b(static_cast<unsigned>(seed));
    const Plan x = plan_reenactment(with, subs, p, a);
    const Plan y = plan_reenactment(without, subs, p, b);
    ASSERT_EQ(x.segments.size(), y.segments.size());
    int jumps = 0;
    for (std::size_t s = 0; s < x.segments.size(); ++s) {
      EXPECT_EQ(x.segments[s].path, y.segments[s].path) << "seed " << seed << ", segment " << s;
      EXPECT_EQ(x.segments[s].junction_cost, y.segments[s].junction_cost);
      jumps += x.segments[s].junction_from >= 0 && x.segments[s].junction_from + 1 != x.segments[s].path.front();
    }
    EXPECT_GT(jumps, 3) << "the plans start afresh often enough for the ranking to matter";
  }
}

}  // namespace
}  // namespace gmg
