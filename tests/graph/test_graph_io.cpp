// Graph files: save/load round trip, rejection of damaged files, DOT/GraphML export.
#include <fstream>
#include <functional>
#include <limits>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "graph/graph_io.h"
#include "graph/stats.h"
#include "tests/graph/fixtures.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(GraphIo, SaveLoadRoundTrip) {
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

TEST(GraphIo, LoadRejectsWrongDamagedAndTruncatedFiles) {
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

TEST(GraphIo, ExportsDotAndGraphml) {
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

// A file with a valid checksum can still be hostile (made by hand or by another tool): each
// field is checked. graph_save writes whatever it is given, so these files have valid checksums.
TEST(GraphIo, LoadChecksEveryFieldBehindTheChecksum) {
  gmg::testing::TempDir dir;
  auto error_after = [&](const std::function<void(MotionGraph&)>& damage) {
    MotionGraph g = two_clip_graph();
    damage(g);
    const std::string path = dir.file("hand.gmg");
    graph_save(path, g);
    try {
      graph_load(path);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  auto expect_refused = [&](const std::string& fragment, const std::function<void(MotionGraph&)>& damage) {
    const std::string what = error_after(damage);
    EXPECT_NE(what.find("hand.gmg: byte "), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  };
  expect_refused("frame rate inf is outside 1 to 1000 fps",
                 [](MotionGraph& g) { g.motion.fps = std::numeric_limits<double>::infinity(); });
  expect_refused("frame rate 1e+06 is outside", [](MotionGraph& g) { g.motion.fps = 1e6; });
  expect_refused("frame rate 0.5 is outside", [](MotionGraph& g) { g.motion.fps = 0.5; });
  expect_refused("clip table inconsistent", [](MotionGraph& g) { g.clips[1].frame_count = 2147483647; });
  expect_refused("clips do not cover the motion", [](MotionGraph& g) { g.clips.pop_back(); });
  expect_refused("not finite or not a unit rotation", [](MotionGraph& g) { g.motion.rotations[7].w = 2.0; });
  expect_refused("not finite or not a unit rotation",
                 [](MotionGraph& g) { g.motion.translations[3].y = std::numeric_limits<double>::quiet_NaN(); });
  expect_refused("a keyword without its kind", [](MotionGraph& g) { g.graph[5].keyword = "stray"; });
  expect_refused("edge with an invalid weight", [](MotionGraph& g) {
    boost::add_edge(3, 90, EdgeInfo{-1.0, false}, g.graph);
  });
  expect_refused("edge with an invalid weight", [](MotionGraph& g) {
    boost::add_edge(3, 90, EdgeInfo{0.0, true}, g.graph);
  });
  expect_refused("unknown or repeated channel", [](MotionGraph& g) {
    g.motion.skeleton.joints[1].channels.push_back(g.motion.skeleton.joints[1].channels.back());
  });
  expect_refused("build parameters are out of range", [](MotionGraph& g) { g.params.l_pn = 0; });
  EXPECT_EQ(error_after([](MotionGraph&) {}), "accepted");  // the control
}

}  // namespace
}  // namespace gmg
