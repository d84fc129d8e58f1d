// GraphViz DOT and GraphML exports of a frame range (graph/graph_export.cpp).
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <new>
#include <regex>
#include <tuple>
#include <utility>

#include <unistd.h>

#include <gtest/gtest.h>

#include "engine/core/checksum.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "graph/build.h"
#include "graph/graph_check.h"
#include "graph/graph_io.h"
#include "graph/key_poses.h"
#include "graph/reference_facts.h"
#include "graph/stats.h"
#include "tests/core/helpers.h"
#include "tests/graph/fixtures.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(GraphIo, ExportsDotAndGraphml) {
  const MotionGraph g = two_clip_graph();
  gmg::testing::TempDir dir;
  constexpr int kFrom = 10, kTo = 50;
  graph_write_dot(dir.file("g.dot"), g, kFrom, kTo);
  graph_write_graphml(dir.file("g.graphml"), g, kFrom, kTo);
  const std::string dot = read_file_bytes(dir.file("g.dot"));
  const std::string xml = read_file_bytes(dir.file("g.graphml"));
  EXPECT_NE(dot.find("digraph"), std::string::npos);
  EXPECT_NE(dot.find("big"), std::string::npos);
  EXPECT_NE(xml.find("<graphml"), std::string::npos);
  EXPECT_NE(xml.find("keyword"), std::string::npos);

  // Every edge with both ends in the range, and no other, with its flag and weight: (source,
  // target) as the files number them (vertex i = frame kFrom + i) to (natural, weight).
  std::map<std::pair<int, int>, std::pair<bool, double>> want;
  int transitions = 0;
  for (int f = kFrom; f < kTo; ++f)
    for (const GraphEdge e : g.graph.out_edges(static_cast<GraphVertex>(f))) {
      const int b = static_cast<int>(g.graph.target(e));
      if (b < kFrom || b >= kTo) continue;
      const bool natural = b == f + 1;
      want[{f - kFrom, b - kFrom}] = {natural, g.weight(e)};
      transitions += natural ? 0 : 1;
    }
  ASSERT_GT(transitions, 0) << "the range should hold transitions";
  // The weights are declared numbers, so that readers (networkx, yEd, Gephi) parse them.
  EXPECT_NE(xml.find(R"(<key id="key4" for="edge" attr.name="weight" attr.type="double" />)"), std::string::npos);
  const std::regex edge(R"re(<edge id="e\d+" source="n(\d+)" target="n(\d+)">\s*)re"
                        R"re(<data key="key3">(\d)</data>\s*<data key="key4">([^<]+)</data>)re");
  std::map<std::pair<int, int>, std::pair<bool, double>> got;
  for (std::sregex_iterator it(xml.begin(), xml.end(), edge), end; it != end; ++it)
    got[{std::stoi((*it)[1]), std::stoi((*it)[2])}] = {(*it)[3] == "1", std::stod((*it)[4])};
  ASSERT_EQ(got.size(), want.size());
  for (const auto& [ends, value] : want) {
    ASSERT_EQ(got.count(ends), 1u) << ends.first << " -> " << ends.second;
    EXPECT_EQ(got[ends].first, value.first) << ends.first << " -> " << ends.second;
    // Each weight reads back as the same double.
    EXPECT_EQ(got[ends].second, value.second) << ends.first << " -> " << ends.second;
  }
  // The DOT file draws each transition in orange with its weight, each natural edge in gray.
  std::size_t orange = 0, gray = 0;
  for (std::size_t at = dot.find("color=orange"); at != std::string::npos; at = dot.find("color=orange", at + 1))
    ++orange;
  for (std::size_t at = dot.find("[color=gray]"); at != std::string::npos; at = dot.find("[color=gray]", at + 1))
    ++gray;
  EXPECT_EQ(orange, static_cast<std::size_t>(transitions));
  EXPECT_EQ(gray, want.size() - static_cast<std::size_t>(transitions));

  EXPECT_THROW(graph_write_dot(dir.file("x.dot"), g, 50, 500), Error);
}

}  // namespace
}  // namespace gmg
