// Feature-based initialisation: key features, d_feat ranking, occurrences, random fallback.
#include <gtest/gtest.h>

#include "search/initialisation.h"
#include "tests/search/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(Initialisation, KeyFeatureHasTrailingZeros) {
  const std::vector<double> f = key_feature({0, 5, 12, 20}, 1, 4);
  EXPECT_EQ(f, (std::vector<double>{7, 8, 0, 0}));
}

}  // namespace
}  // namespace gmg
