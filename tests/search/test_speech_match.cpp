// The speech distance of the speech-driven planner: values worked out by hand.
#include <cmath>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "search/speech_match.h"
#include "tests/search/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

// A 4-frame graph whose speech features are (loudness, onsets) = (f, 0): frame f is f loud.
MotionGraph four_frames() {
  MotionGraph g = chain_graph(4, {}, {}, {});
  g.speech_dims = 2;
  g.speech = std::vector<float>{0, 0, 1, 0, 2, 0, 3, 0};
  return g;
}

TEST(SpeechMatch, CostsAreSquaredDistancesOverTheRandomPairMean) {
  const MotionGraph g = four_frames();
  // Test frames of loudness 0 and 2, onsets 1 (onsets weigh half).
  const std::vector<float> test = {0, 1, 2, 1};
  const SpeechMatch m(g, test, 2);
  ASSERT_TRUE(m.active());
  // Unscaled: (t=0, f=0) = 0 + 0.5 * 1 = 0.5; (t=1, f=3) = 1 + 0.5 = 1.5. The scale is the mean
  // over 4096 pairs t = i * 1 / 4095 (0 for i < 4095, 1 for the last), f = 7919 i mod 4: the first
  // 4095 pairs cycle through f = 0, 3, 2, 1 (7919 = 3 mod 4) against t = 0 (0.5, 9.5, 4.5, 1.5).
  double sum = 0.0;
  for (int i = 0; i < 4096; ++i) {
    const int t = i == 4095 ? 1 : 0;
    const int f = static_cast<int>((static_cast<long long>(i) * 7919) % 4);
    const double loud = (t == 0 ? 0.0 : 2.0) - f;
    sum += loud * loud + 0.5;
  }
  const double scale = 4096.0 / sum;
  EXPECT_NEAR(m.frame_cost(0, 0), 0.5 * scale, 1e-12);
  EXPECT_NEAR(m.frame_cost(1, 3), 1.5 * scale, 1e-12);
  EXPECT_NEAR(m.frame_cost(7, 2), 0.5 * scale, 1e-12) << "test frames are clamped to the last";
}

TEST(SpeechMatch, PathCostFollowsTheTimeWarp) {
  const MotionGraph g = four_frames();
  const std::vector<float> test = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const SpeechMatch m(g, test, 5);
  // Two path frames stretched over 5 test frames: i = 0..4 reads path[round(i / 4)] = 0, 0, 1, 1,
  // 1 (round half away from zero: 0.5 -> 1), i.e. graph frames 2, 2, 3, 3, 3 with costs 4, 4, 9, 9, 9.
  const double scale = m.frame_cost(0, 1);  // loudness 1 off: 1 x scale
  EXPECT_NEAR(m.path_cost({2, 3}, 0, 5), (4 + 4 + 9 + 9 + 9) / 5.0 * scale, 1e-12);
  // The window from frame 2 plays 2, 3, then holds 3 (the run's last frame).
  std::vector<double> w;
  m.window_costs(0, 4, {2}, w);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NEAR(w[0], (4 + 9 + 9 + 9) / 4.0 * scale, 1e-12);
}

TEST(SpeechMatch, InactiveWithoutFeaturesAndSizesAreChecked) {
  const MotionGraph plain = chain_graph(4, {}, {}, {});
  const SpeechMatch none(plain, {0, 0}, 1);
  EXPECT_FALSE(none.active());
  EXPECT_EQ(none.frame_cost(0, 2), 0.0);
  EXPECT_EQ(none.path_cost({1, 2}, 0, 2), 0.0);
  EXPECT_THROW(SpeechMatch(four_frames(), {0, 0, 0}, 2), Error);
}

TEST(SpeechMatch, RestCostsInPausesOnly) {
  MotionGraph g = four_frames();
  g.speech = std::vector<float>{0, 0, 0, 0, 0, 0, 0, 0};  // all alike: only the rest term differs
  g.activity = std::vector<float>{0.0f, 1.0f, 2.0f, 0.5f};
  // Test frame 0 speaks (loudness 0), frame 1 is a full pause (-4: 40 dB below speech), frame 2
  // half one (-2.75).
  const std::vector<float> test = {0, 0, -4, 0, -2.75f, 0};
  const SpeechMatch m(g, test, 3, 2.0);
  const double base0 = m.frame_cost(0, 0);
  EXPECT_NEAR(m.frame_cost(0, 2), base0, 1e-12) << "speech: activity does not count";
  EXPECT_NEAR(m.frame_cost(1, 2) - m.frame_cost(1, 0), 2.0 * 1.0 * 2.0, 1e-12);
  EXPECT_NEAR(m.frame_cost(2, 1) - m.frame_cost(2, 0), 2.0 * 0.5 * 1.0, 1e-6);
}

TEST(SpeechMatch, EndingOnAKinematicBeatCostsNothing) {
  // Activity falls to a minimum at frame 10 (above the 0.3 floor) and rises again.
  MotionGraph g = chain_graph(21, {}, {}, {});
  g.speech_dims = 2;
  g.speech.assign(std::size_t{2} * 21, 0.0f);
  for (int f = 0; f < 21; ++f) g.activity.push_back(1.0f + 0.05f * static_cast<float>(std::abs(f - 10)));
  const SpeechMatch m(g, std::vector<float>(2, 0.0f), 1);
  EXPECT_NEAR(m.end_cost(10), 0.0, 1e-12);
  // 3 frames (0.1 s at 30 fps) away: 1 - exp(-1/2).
  EXPECT_NEAR(m.end_cost(13), 1.0 - std::exp(-0.5), 1e-6);
  EXPECT_NEAR(m.end_cost(7), 1.0 - std::exp(-0.5), 1e-6);
}

// A graph that keeps its beat end costs (MotionGraph::beat_cost) is read, not recomputed; one made
// without them has them computed from its activity (graph/beats.h).
TEST(SpeechMatch, EndCostsComeFromTheGraph) {
  MotionGraph g = chain_graph(21, {}, {}, {});
  g.speech_dims = 2;
  g.speech.assign(std::size_t{2} * 21, 0.0f);
  for (int f = 0; f < 21; ++f) g.activity.push_back(1.0f + 0.05f * static_cast<float>(std::abs(f - 10)));
  const SpeechMatch computed(g, std::vector<float>(2, 0.0f), 1);
  std::vector<float> kept(21);
  for (int f = 0; f < 21; ++f) kept[static_cast<std::size_t>(f)] = 0.01f * static_cast<float>(f);
  g.beat_cost = kept;
  const SpeechMatch stored(g, std::vector<float>(2, 0.0f), 1);
  EXPECT_NEAR(computed.end_cost(10), 0.0, 1e-12);
  EXPECT_EQ(stored.end_cost(10), static_cast<double>(kept[10]));
  EXPECT_EQ(stored.end_cost(3), static_cast<double>(kept[3]));
}
}  // namespace
}  // namespace gmg
