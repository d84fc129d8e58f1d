// Graph files: save/load round trip, rejection of damaged files, DOT/GraphML export.
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <new>
#include <tuple>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "graph/build.h"
#include "graph/graph_io.h"
#include "graph/stats.h"
#include "tests/graph/fixtures.h"
#include "tests/test_support.h"

// Bytes allocated while counting is on (this test executable's global operator new, on malloc;
// GCC takes the replacement's free for a mismatch with operator new).
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
std::atomic<bool> g_counting{false};
std::atomic<std::size_t> g_allocated{0};

void* operator new(std::size_t size) {
  if (g_counting) g_allocated += size;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace gmg {
namespace {

using namespace gmg::testing;

// A graph of a few thousand frames: its arrays dwarf the small allocations of a load.
MotionGraph long_graph() {
  std::vector<double> x;
  x.reserve(3000);
  for (int i = 0; i < 3000; ++i) x.push_back(0.8 * std::sin(i * 0.07) + 0.3 * std::sin(i * 0.23));
  return graph_build({{"long.bvh", line_motion(x), {10, 400}, {{20, "big"}}}}, GraphParams{});
}

// The bytes of a graph's arrays: what one copy of it costs.
std::size_t array_bytes(const MotionGraph& g) {
  return g.motion.rotations.size() * sizeof(glm::dquat) + g.motion.translations.size() * sizeof(glm::dvec3) +
         g.graph.m_forward.m_rowstart.size() * sizeof(std::uint32_t) +
         g.graph.m_forward.m_column.size() * sizeof(std::size_t) +
         g.graph.m_forward.m_edge_properties.size() * sizeof(EdgeInfo) +
         g.graph.m_vertex_properties.size() * sizeof(NodeInfo);
}

TEST(GraphIo, LoadingDoesNotCopyTheGraph) {
  const MotionGraph g = long_graph();
  gmg::testing::TempDir dir;
  graph_save(dir.file("g.gmg"), g);
  const std::size_t one_copy = array_bytes(g);
  ASSERT_GT(one_copy, 300000u);
  // As the command line does it: a graph declared first, then assigned the loaded one.
  MotionGraph h;
  g_allocated = 0;
  g_counting = true;
  h = graph_load(dir.file("g.gmg"));
  g_counting = false;
  EXPECT_EQ(h.frame_count(), g.frame_count());
  EXPECT_EQ(boost::num_edges(h.graph), boost::num_edges(g.graph));
  // One copy of the arrays plus small change (names, skeleton); a second copy would double it.
  EXPECT_LT(g_allocated.load(), one_copy + one_copy / 4) << "one copy is " << one_copy << " bytes";
  EXPECT_GE(g_allocated.load(), one_copy);
}

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
  for (int f = 0; f < g.frame_count(); ++f) {
    EXPECT_EQ(h.node(f).kinds, g.node(f).kinds);
    EXPECT_EQ(h.node(f).keyword, g.node(f).keyword);
    std::vector<std::tuple<std::size_t, double, bool>> a, b;
    for (auto [it, end] = boost::out_edges(static_cast<std::size_t>(f), g.graph); it != end; ++it)
      a.emplace_back(boost::target(*it, g.graph), g.graph[*it].weight, g.graph[*it].natural);
    for (auto [it, end] = boost::out_edges(static_cast<std::size_t>(f), h.graph); it != end; ++it)
      b.emplace_back(boost::target(*it, h.graph), h.graph[*it].weight, h.graph[*it].natural);
    EXPECT_EQ(a, b) << "frame " << f;
  }
  EXPECT_EQ(h.params.max_transitions, g.params.max_transitions);
  const GraphStats a = graph_stats(g), b = graph_stats(h);
  EXPECT_EQ(a.unnatural_edges, b.unnatural_edges);
  EXPECT_EQ(a.onset_nodes, b.onset_nodes);
}

// The SMPL-X body (shape and per-frame face) is the file's one optional section: a graph with one
// is written as version 4 and loads with it exactly; one without stays version 3, byte for byte
// the layout before the section existed.
TEST(GraphIo, TheBodyIsAnOptionalSectionOfVersion4) {
  MotionGraph g = two_clip_graph();
  gmg::testing::TempDir dir;
  graph_save(dir.file("plain.gmg"), g);
  const std::string plain = read_file_bytes(dir.file("plain.gmg"));
  EXPECT_EQ(plain[8], 3);
  EXPECT_FALSE(graph_load(dir.file("plain.gmg")).body.has_face());

  g.body.expression_dims = 2;
  for (int f = 0; f < g.frame_count(); ++f)
    g.body.expressions.insert(g.body.expressions.end(), {0.5 * f, -1.0 / (f + 1)});
  g.body.betas = {1.25, -0.75, 3.0};
  g.body.gender = "female";
  g.body.model = "smplx2020";
  graph_save(dir.file("body.gmg"), g);
  const std::string bytes = read_file_bytes(dir.file("body.gmg"));
  EXPECT_EQ(bytes[8], 4);
  const MotionGraph h = graph_load(dir.file("body.gmg"));
  EXPECT_EQ(h.body.expression_dims, 2);
  EXPECT_EQ(h.body.expressions, g.body.expressions);
  EXPECT_EQ(h.body.betas, g.body.betas);
  EXPECT_EQ(h.body.gender, "female");
  EXPECT_EQ(h.body.model, "smplx2020");
  // The section follows the version 3 payload: the rest of the file is the same bytes.
  EXPECT_EQ(bytes.compare(20, plain.size() - 28, plain, 20, plain.size() - 28), 0);

  // A face that does not cover the frames is refused, even behind a valid checksum.
  MotionGraph bad = g;
  bad.body.expressions.pop_back();
  graph_save(dir.file("bad.gmg"), bad);
  try {
    graph_load(dir.file("bad.gmg"));
    ADD_FAILURE() << "a face shorter than the frames was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the face disagrees with frames x coefficients"), std::string::npos)
        << e.what();
  }
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
  expect_refused("keyword label on a frame that is not a keyword node",
                 [](MotionGraph& g) { g.graph[5].keyword = "stray"; });
  expect_refused("a node has unknown kinds", [](MotionGraph& g) { g.graph[5].kinds |= 0x80; });
  expect_refused("an edge weight is negative or not finite", [](MotionGraph& g) {
    g.graph = with_edge(g.graph, 3, 90, EdgeInfo{-1.0, false});
  });
  expect_refused("an edge weight is negative or not finite", [](MotionGraph& g) {
    g.graph = with_edge(g.graph, 3, 90, EdgeInfo{std::numeric_limits<double>::quiet_NaN(), false});
  });
  expect_refused("is not a step to the next frame of weight 0", [](MotionGraph& g) {
    g.graph = with_edge(g.graph, 3, 90, EdgeInfo{0.0, true});
  });
  expect_refused("unknown or repeated channel", [](MotionGraph& g) {
    g.motion.skeleton.joints[1].channels.push_back(g.motion.skeleton.joints[1].channels.back());
  });
  expect_refused("build parameters are out of range", [](MotionGraph& g) { g.params.l_pn = 0; });
  EXPECT_EQ(error_after([](MotionGraph&) {}), "accepted");  // the control
}

}  // namespace
}  // namespace gmg
