// Feature-based initialisation: key features, d_feat ranking, occurrences, random fallback.
#include <algorithm>
#include <cmath>
#include <random>

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

// Graph keys 0 10 20 40 70 and the clip end 79 (a break node); features with l_feat 2:
// [10 10] [10 20] [20 30] [30 9] [9 0] [0 0]. Test keys 0 20 40 70: subsequence 0's feature is
// [20 20]. With w_full [1 1], lambda_first 1 and no occurrences yet:
//   key 0:  |(10,10)-(20,20)| = 14.14 + |1 - 10/20| = 0.5   -> 14.64
//   key 10: |(10,20)-(20,20)| = 10    + 0.5                 -> 10.5
//   key 20: |(20,30)-(20,20)| = 10    + 0                   -> 10
//   key 40: |(30,9)-(20,20)|  = 14.87 + 0.5                 -> 15.37
//   key 70: |(9,0)-(20,20)|   = 22.83 + 0.55                -> 23.38
//   key 79: |(0,0)-(20,20)|   = 28.28 + 1                   -> 29.28
// so the ranking is 20, 10, 0, 40, 70, 79.
TEST(Initialisation, RanksKeyNodesByFeatureDistance) {
  const MotionGraph g = chain_graph(80, {0, 10, 20, 40, 70}, {}, {});
  SearchParams p;
  p.l_feat = 2;
  p.w_full = {1, 1};
  p.l_npaths = 3;
  const std::vector<Subsequence> subs = {
      {0, 20, Termination::Rhythm, ""}, {20, 20, Termination::Rhythm, ""}, {40, 30, Termination::Rhythm, ""}};
  StartNodeIndex index = initialisation_prepare(g, subs, p);
  EXPECT_EQ(index.keys, (std::vector<int>{0, 10, 20, 40, 70, 79}));  // 79: the clip end (break)
  EXPECT_NEAR(feature_distance(index, 0, 0, p), std::sqrt(200.0) + 0.5, 1e-12);
  std::mt19937_64 rng(1);
  EXPECT_EQ(initialisation_start_nodes(g, index, 0, 0, p, rng), (std::vector<int>{20, 10, 0}));
  // The next round takes the next ranks; the occurrence count pushes a used node back.
  const std::vector<int> second = initialisation_start_nodes(g, index, 0, 1, p, rng);
  EXPECT_EQ(second.size(), 3u);
  EXPECT_EQ(second[0], 40);
  initialisation_count_use(index, 20);
  p.lambda_occ = 100.0;
  EXPECT_EQ(initialisation_start_nodes(g, index, 0, 0, p, rng), (std::vector<int>{10, 0, 40}));
}

TEST(Initialisation, RandomNodesAreSeededAndInRange) {
  const MotionGraph g = chain_graph(50, {10, 20}, {}, {});
  SearchParams p;
  p.init = InitMode::Random;
  const std::vector<Subsequence> subs = {{0, 10, Termination::Rhythm, ""}};
  const StartNodeIndex index = initialisation_prepare(g, subs, p);
  std::mt19937_64 a(7), b(7), c(8);
  const std::vector<int> na = initialisation_start_nodes(g, index, 0, 0, p, a);
  EXPECT_EQ(na.size(), 20u);
  for (int f : na) {
    EXPECT_GE(f, 0);
    EXPECT_LT(f, 50);
  }
  EXPECT_EQ(na, initialisation_start_nodes(g, index, 0, 0, p, b));
  EXPECT_NE(na, initialisation_start_nodes(g, index, 0, 0, p, c));
}

// At or below the cap every key node is a candidate; above it a sample of at most cap of them in
// blocks of consecutive key nodes, every stride-th block from an offset the seed and the
// subsequence decide.
TEST(Initialisation, AboveTheCapEachSubsequenceRanksAnEvenSample) {
  for (int cap : {0, 1000, 5000}) {
    const std::vector<std::size_t> all = start_candidate_sample(1000, cap, 7, 3);
    ASSERT_EQ(all.size(), 1000u);
    for (std::size_t m = 0; m < all.size(); ++m) EXPECT_EQ(all[m], m);
  }
  // 1000 keys, cap 200: 16 blocks of 64 (the last of 40), 3 wanted, every 6th block from an offset
  // in [0, 6): blocks o, o + 6 and (when o < 4) o + 12.
  std::vector<std::size_t> offsets;
  for (std::size_t k = 0; k < 40; ++k) {
    const std::vector<std::size_t> s = start_candidate_sample(1000, 200, 7, k);
    ASSERT_FALSE(s.empty());
    EXPECT_LE(s.size(), 200u);
    const std::size_t o = s.front() / 64;
    EXPECT_LT(o, 6u);
    EXPECT_EQ(s.front(), 64 * o);
    std::vector<std::size_t> expected;
    for (std::size_t b = o; b < 16; b += 6)
      for (std::size_t i = 64 * b; i < std::min<std::size_t>(1000, 64 * b + 64); ++i) expected.push_back(i);
    EXPECT_EQ(s, expected);
    EXPECT_EQ(start_candidate_sample(1000, 200, 7, k), s);
    offsets.push_back(o);
  }
  std::sort(offsets.begin(), offsets.end());
  EXPECT_EQ(std::unique(offsets.begin(), offsets.end()) - offsets.begin(), 6) << "subsequences see different samples";
  // A cap below a block: blocks of the cap's size.
  const std::vector<std::size_t> small = start_candidate_sample(100, 10, 7, 0);
  EXPECT_EQ(small.size(), 10u);
  EXPECT_EQ(small.back() - small.front(), 9u);
}

// A ranking made once serves every attempt: its rounds are those initialisation_start_nodes gives.
TEST(Initialisation, ARankingServesEveryRound) {
  const MotionGraph g = chain_graph(200, {0, 10, 20, 40, 70, 75, 90, 120, 150, 151, 170}, {}, {});
  SearchParams p;
  p.l_feat = 2;
  p.w_full = {1, 1};
  p.l_npaths = 3;
  const std::vector<Subsequence> subs = {{0, 20, Termination::Rhythm, ""}, {20, 20, Termination::Rhythm, ""}};
  const StartNodeIndex index = initialisation_prepare(g, subs, p);
  std::vector<std::size_t> all(index.keys.size());
  for (std::size_t m = 0; m < all.size(); ++m) all[m] = m;
  StartRanking ranking(index, 0, all, nullptr, p);
  for (int round = 0; round < 6; ++round) {  // the last rounds run out of key nodes: random frames
    std::mt19937_64 a(5), b(5);
    EXPECT_EQ(ranking.start_nodes(g, index, round, p, a), initialisation_start_nodes(g, index, 0, round, p, b))
        << "round " << round;
  }
}
}  // namespace
}  // namespace gmg
