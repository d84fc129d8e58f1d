// The whole graph construction: clips joined, breaks, natural and unnatural edges.
#include <cmath>
#include <filesystem>
#include <tuple>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/pipeline/pipeline.h"
#include "graph/build.h"
#include "graph/continuity.h"
#include "graph/graph_io.h"
#include "graph/stats.h"
#include "tests/graph/fixtures.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(Graph, BuildJoinsClipsWithBreaksAndNoNaturalEdgeAcross) {
  const MotionGraph g = two_clip_graph();
  ASSERT_EQ(g.frame_count(), 180);
  ASSERT_EQ(g.clips.size(), 2u);
  EXPECT_TRUE(g.node(99).kinds & kBreakNode);
  EXPECT_TRUE(g.node(179).kinds & kBreakNode);
  EXPECT_TRUE(g.node(105).kinds & kOnsetNode);  // clip b's onset 5, offset 100
  EXPECT_EQ(g.node(150).keyword, "big");
  EXPECT_TRUE(g.node(20).kinds & kKeywordNode);
  // Frame 99 ends clip a: no natural edge out of it, no step to frame 100.
  for (const GraphEdge e : g.graph.out_edges(99)) EXPECT_NE(g.graph.target(e), 100u);
  const GraphStats s = graph_stats(g);
  EXPECT_EQ(s.onset_nodes, 5);
  EXPECT_EQ(s.keyword_nodes, 3);
  EXPECT_EQ(s.break_nodes, 2);
  EXPECT_EQ(s.natural_edges, 178);
  EXPECT_GT(s.unnatural_edges, 0);
}

TEST(Graph, LongClipsGetTheFeaturesOfOnePoseFeaturesCall) {
  // graph_build computes features a few thousand frames at a time; the transitions (and so the
  // features they come from) must be those of the whole clip's pose_features.
  std::vector<double> x;
  x.reserve(9000);
  for (int i = 0; i < 9000; ++i) x.push_back(0.8 * std::sin(i * 0.21) + 0.3 * std::sin(i * 0.057));
  const Motion m = line_motion(x);
  GraphParams p;
  p.max_transitions = 3;
  const MotionGraph g = graph_build({{"long.bvh", m, {}, {}}}, p);
  std::vector<std::tuple<int, int, double>> built, direct;
  for (int f = 0; f < g.frame_count(); ++f)
    for (const GraphEdge e : g.graph.out_edges(static_cast<GraphVertex>(f)))
      if (g.graph.target(e) != static_cast<GraphVertex>(f + 1))
        built.emplace_back(f, static_cast<int>(g.graph.target(e)), g.weight(e));
  for (const Transition& t : continuity_analysis(pose_features(m), one_run(9000), p))
    direct.emplace_back(t.from, t.to, t.weight);
  ASSERT_GT(direct.size(), 1000u);
  EXPECT_EQ(built, direct);
}

TEST(Graph, ASpilledBuildWritesTheSameFileAndLeavesNoTemporaryFile) {
  // Every array spilled (a limit of 0 bytes): the motion, the key poses and the positions are read
  // back from temporary files, and the graph is the one built in memory.
  std::vector<ClipEvents> clips = {{"a.bvh", line_motion(wave(300, 0.0)), {10, 40, 70, 200}, {{20, "big"}}},
                                   {"b.bvh", line_motion(wave(250, 1.0)), {5, 30, 180}, {{50, "big"}}},
                                   {"c.bvh", line_motion(wave(200, 2.0)), {7, 90}, {}}};
  const std::string folder = ::testing::TempDir() + "/spilled_build";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  auto files = [&] {
    int n = 0;
    for (const auto& e : std::filesystem::directory_iterator(folder)) n += e.is_regular_file() ? 1 : 0;
    return n;
  };
  const MotionGraph in_memory = graph_build(clips, GraphParams{});
  GraphBuild build(GraphParams{}, folder, 0);
  for (const ClipEvents& c : clips) build.add(c);
  // rotations, translations, key poses, positions
  EXPECT_EQ(files(), 4) << "every array is in a temporary file";
  const MotionGraph spilled = build.finish();
  graph_save(folder + "/memory.gmg", in_memory);
  graph_save(folder + "/spilled.gmg", spilled);
  EXPECT_EQ(read_file_bytes(folder + "/memory.gmg"), read_file_bytes(folder + "/spilled.gmg"));
  EXPECT_EQ(files(), 2) << "the temporary files are unlinked once mapped";
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

}  // namespace
}  // namespace gmg

namespace gmg {
namespace {

TEST(GraphRealData, ScottHasOnsetAndKeywordNodesZeggsOnsetAndBreakOnly) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string d = gmg::testing::shared_data_dir();
  Config cfg;
  const MotionGraph scott =
      graph_build_from_files({{d + "/beat2_scott/2_scott_0_1_1.bvh",
                               {d + "/beat2_scott/2_scott_0_1_1.wav", d + "/beat2_scott/2_scott_0_1_1.TextGrid"}}},
                             cfg);
  const GraphStats s = graph_stats(scott);
  EXPECT_EQ(s.frames, 1906);
  EXPECT_EQ(s.onset_nodes, 115);  // librosa's count for this recording (reference_onsets)
  EXPECT_GT(s.keyword_nodes, 20);
  EXPECT_GE(s.break_nodes, 1);
  EXPECT_GT(s.unnatural_edges, 0);
  const MotionGraph zeggs =
      graph_build_from_files({{d + "/zeggs/067_Speech_2_x_1_0.bvh", {d + "/zeggs/067_Speech_2_x_1_0.wav", ""}}}, cfg);
  const GraphStats z = graph_stats(zeggs);
  EXPECT_EQ(z.frames, 2065);
  EXPECT_EQ(z.keyword_nodes, 0);
  EXPECT_GT(z.onset_nodes, 120);  // librosa finds 130, a few fall past the last motion frame
  EXPECT_LE(z.onset_nodes, 130);
  EXPECT_GE(z.break_nodes, 1);
  EXPECT_TRUE(zeggs.node(2064).kinds & kBreakNode);
  // Two clips with different skeletons cannot share a graph.
  EXPECT_THROW(
      graph_build_from_files({{d + "/beat2_scott/2_scott_0_1_1.bvh", {d + "/beat2_scott/2_scott_0_1_1.wav", ""}},
                              {d + "/zeggs/067_Speech_2_x_1_0.bvh", {d + "/zeggs/067_Speech_2_x_1_0.wav", ""}}},
                             cfg),
      Error);
}

}  // namespace
}  // namespace gmg
