// Marking onset, keyword and break nodes of a clip placed inside a larger graph.
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "graph/key_nodes.h"
#include "tests/graph/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(KeyNodes, MarksEventsAtTheClipsOffset) {
  std::vector<NodeInfo> g(20);
  ClipEvents clip{"c.bvh", line_motion(wave(10, 0.0)), {0, 3}, {{3, "big"}, {3, "this"}, {7, "not"}}};
  mark_key_nodes(g, 5, clip, {4});
  EXPECT_EQ(g[5].kinds, kOnsetNode);
  EXPECT_EQ(g[8].kinds, kOnsetNode | kKeywordNode);
  EXPECT_EQ(g[8].keyword, "big");  // the first keyword of a frame wins
  EXPECT_EQ(g[12].kinds, kKeywordNode);
  EXPECT_EQ(g[12].keyword, "not");
  EXPECT_EQ(g[9].kinds, kBreakNode);   // the capture jump at clip frame 4
  EXPECT_EQ(g[14].kinds, kBreakNode);  // the clip's last frame
  int marked = 0;
  for (std::size_t f = 0; f < 20; ++f) marked += g[f].kinds != 0;
  EXPECT_EQ(marked, 5);
}

TEST(KeyNodes, EventOutsideTheClipNamesIt) {
  std::vector<NodeInfo> g(20);
  ClipEvents clip{"c.bvh", line_motion(wave(10, 0.0)), {10}, {}};
  try {
    mark_key_nodes(g, 0, clip, {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "c.bvh: onset frame 10 outside the clip");
  }
}

}  // namespace
}  // namespace gmg
