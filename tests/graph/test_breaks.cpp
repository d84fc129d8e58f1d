// Break nodes from capture jumps.
#include <gtest/gtest.h>

#include "graph/breaks.h"
#include "tests/graph/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(Breaks, CaptureJumpBecomesABreak) {
  std::vector<double> x;
  x.reserve(50);
  for (int i = 0; i < 50; ++i) x.push_back(0.01 * i + (i >= 25 ? 5.0 : 0.0));
  const PoseFeatures f = line_features(x);
  const std::vector<int> jumps = capture_jump_frames(f, GraphParams{});
  EXPECT_EQ(jumps, (std::vector<int>{24}));
}

}  // namespace
}  // namespace gmg
