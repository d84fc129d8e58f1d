// Planning a whole reenactment: continuation, retries, determinism.
#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "search/planner.h"
#include "tests/search/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(Planner, ContinuesFromThePreviousPathsSuccessors) {
  // The last onset is far from the clip end, so every accepted first path ends on an onset
  // with successors.
  const MotionGraph g = chain_graph(150, {10, 20, 30, 40, 50, 60, 70, 80, 90, 100}, {}, {});
  const Plan plan = plan_one(g, {{0, 10, Termination::Rhythm, ""}, {10, 10, Termination::Rhythm, ""}}, true);
  ASSERT_TRUE(plan.segments[1].accepted);
  EXPECT_TRUE(plan.segments[1].continued);
  EXPECT_EQ(plan.segments[1].path.front(), plan.segments[0].path.back() + 1);
}

// Three start nodes make equally good first paths (20->30, 30->40, 100->110, each 11 frames); only
// the first one's stop node (30) continues naturally into the second subsequence (the next onset,
// 40, lies 10 frames on; after 40 and 110 the next ones are 60 and 30 frames away). The natural
// planner looks one subsequence ahead among near-equal candidates, whatever the seed.
TEST(Planner, PrefersThePathTheNextSubsequenceCanContinue) {
  const MotionGraph g = chain_graph(200, {20, 30, 40, 100, 110, 140}, {}, {});
  SearchParams p;
  p.l_npaths = 3;
  p.l_feat = 1;
  p.w_full = {1.0};
  p.merge_below = 0;
  p.variety = 0.0;  // every start node available to every seed
  const std::vector<Subsequence> subs = {{0, 10, Termination::Rhythm, ""}, {10, 10, Termination::Rhythm, ""}};
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    std::mt19937_64 rng(seed);
    const Plan plan = plan_reenactment(g, subs, p, rng);
    ASSERT_EQ(plan.segments.size(), 2u);
    EXPECT_EQ(plan.segments[0].path.front(), 20) << "seed " << seed;
    EXPECT_TRUE(plan.segments[1].continued) << "seed " << seed;
  }
}

}  // namespace
}  // namespace gmg

namespace gmg {
namespace {

using namespace gmg::testing;

// Speech features (loudness, onsets) for every frame of a graph or a test: `loud(f)`, onsets 0.
template <typename F>
std::vector<float> features(int frames, const F& loud) {
  std::vector<float> v;
  for (int f = 0; f < frames; ++f) {
    v.push_back(static_cast<float>(loud(f)));
    v.push_back(0.0f);
  }
  return v;
}

SearchParams speech_params() {
  SearchParams p;
  p.variety = 0.0;  // every start node available
  p.merge_below = 0;
  return p;
}

// Two stretches fit equally (every pose is the same, so no junction costs anything, and both end
// on an onset after 20 frames): one was captured while the speaker was loud, the other in a pause.
// The planner plays the one whose speech is like the test's, for loud and for quiet test speech.
TEST(PlannerSpeech, PlaysTheStretchWhoseSpeechMatches) {
  MotionGraph g = chain_graph(200, {10, 30, 110, 130}, {}, {});
  g.speech_dims = 2;
  g.speech = features(200, [](int f) { return f >= 10 && f < 30 ? 0.0 : (f >= 110 && f < 130 ? -4.0 : -2.0); });
  const std::vector<Subsequence> subs = {{0, 20, Termination::Rhythm, ""}};
  for (const double test_loudness : {0.0, -4.0}) {
    std::mt19937_64 rng(1);
    const Plan plan = plan_reenactment(g, subs, speech_params(), rng, features(20, [&](int) { return test_loudness; }));
    ASSERT_EQ(plan.segments.size(), 1u);
    EXPECT_EQ(plan.segments[0].path.front(), test_loudness == 0.0 ? 10 : 110) << "test loudness " << test_loudness;
  }
}

// The natural continuation of a loud stretch loses to an equally fitting jump when the test speech
// falls silent: continuing is not free when what it plays no longer suits the speech.
TEST(PlannerSpeech, AContinuationWhoseSpeechNoLongerFitsLosesToAJump) {
  MotionGraph g = chain_graph(200, {10, 30, 50, 110, 130}, {}, {});
  g.speech_dims = 2;
  g.speech = features(200, [](int f) { return f < 60 ? 0.0 : (f >= 110 && f < 130 ? -4.0 : -2.0); });
  const std::vector<Subsequence> subs = {{0, 20, Termination::Rhythm, ""}, {20, 20, Termination::Rhythm, ""}};
  const std::vector<float> test = features(40, [](int t) { return t < 20 ? 0.0 : -4.0; });
  std::mt19937_64 rng(1);
  const Plan plan = plan_reenactment(g, subs, speech_params(), rng, test);
  ASSERT_EQ(plan.segments.size(), 2u);
  EXPECT_EQ(plan.segments[0].path.front(), 10);
  EXPECT_FALSE(plan.segments[1].continued);
  EXPECT_EQ(plan.segments[1].path.front(), 110);
  // Without the speech cost the continuation (30 -> 50) is taken.
  SearchParams deaf = speech_params();
  deaf.speech_weight = 0.0;
  std::mt19937_64 rng2(1);
  EXPECT_TRUE(plan_reenactment(g, subs, deaf, rng2, test).segments[1].continued);
}

// A 3 s pause in the test speech over a reference with a pause where the speaker rests: the output
// plays the reference's rest there.
TEST(PlannerSpeech, RestsWhereTheSpeechPauses) {
  // Reference: speaking (frames 0-149 and 240-399, onsets every 15 frames, moving), a pause at
  // 150-239 (at rest), and an onset where speech resumes.
  std::vector<int> onsets;
  for (int f = 15; f < 150; f += 15) onsets.push_back(f);
  for (int f = 150; f < 400; f += 15) onsets.push_back(f < 240 ? 150 : f);
  onsets.push_back(240);
  std::sort(onsets.begin(), onsets.end());
  onsets.erase(std::unique(onsets.begin(), onsets.end()), onsets.end());
  MotionGraph g = chain_graph(400, onsets, {}, {});
  auto pause = [](int f) { return f >= 150 && f < 240; };
  g.speech_dims = 2;
  g.speech = features(400, [&](int f) { return pause(f) ? -4.0 : 0.0; });
  for (int f = 0; f < 400; ++f) g.activity.push_back(pause(f) ? 0.05f : 1.5f);
  // Test: speech with onsets at 15, 30, 45, a pause from 60 to 150 (3 s), speech again to 210.
  const std::vector<Subsequence> subs = segment_speech(210, {15, 30, 45, 60, 150, 165, 180, 195}, {});
  const std::vector<float> test = features(210, [](int t) { return t >= 60 && t < 150 ? -4.0 : 0.0; });
  std::mt19937_64 rng(1);
  const Plan plan = plan_reenactment(g, subs, speech_params(), rng, test);
  int resting = 0, paused = 0;
  for (const PlannedSegment& s : plan.segments)
    if (s.sub.start >= 60 && s.sub.start < 150)
      for (int f : s.path) {
        ++paused;
        resting += g.activity[static_cast<std::size_t>(f)] < 0.3f;
      }
  ASSERT_GT(paused, 60);
  EXPECT_GE(resting, 0.9 * paused) << resting << " of " << paused << " frames at rest";
}

// One very attractive stretch (its speech alone matches the test's): it is not replayed over and
// over. 70 s of new speech from a 60 s reference: no frame more than 3 times; without the reuse
// cost the stretch would be played at most subsequences.
TEST(PlannerSpeech, AnAttractiveStretchIsNotReplayedBeyondTheBound) {
  const int n = 1800;
  std::vector<int> onsets;
  for (int f = 30; f < n; f += 30) onsets.push_back(f);
  MotionGraph g = chain_graph(n, onsets, {}, {});
  g.speech_dims = 2;
  g.speech = features(n, [](int f) { return f >= 600 && f < 630 ? 0.0 : -1.5; });
  std::vector<int> test_onsets;
  for (int t = 30; t < 2100; t += 30) test_onsets.push_back(t);
  const std::vector<Subsequence> subs = segment_speech(2100, test_onsets, {});
  const std::vector<float> test = features(2100, [](int) { return 0.0; });
  auto most_plays = [&](const SearchParams& p) {
    std::mt19937_64 rng(1);
    const Plan plan = plan_reenactment(g, subs, p, rng, test);
    std::vector<int> plays(static_cast<std::size_t>(n), 0);
    int previous = -1;
    for (const PlannedSegment& s : plan.segments)
      for (int f : s.path) {
        if (f != previous) ++plays[static_cast<std::size_t>(f)];
        previous = f;
      }
    return *std::max_element(plays.begin(), plays.end());
  };
  EXPECT_LE(most_plays(speech_params()), 3);
  SearchParams no_reuse = speech_params();
  no_reuse.reuse_weight = 0.0;
  EXPECT_GT(most_plays(no_reuse), 10) << "the test needs a stretch the planner would otherwise replay";
}

// A graph with more key nodes than start_candidates ranks a sample of them for each subsequence:
// the plan is still the same for the same seed. At a cap of exactly the key count nothing is
// sampled and no draw is made, so the plan is that of no cap at all.
TEST(Planner, AboveTheCapPlansWithASampleDeterministically) {
  std::vector<int> onsets;
  for (int f = 7; f < 1200; f += 9 + (f / 7) % 5) onsets.push_back(f);
  const MotionGraph g = chain_graph(1200, onsets, {}, {{50, 600, 1.0}, {300, 900, 2.0}, {700, 100, 1.5}});
  const std::size_t keys = onsets.size() + 1;  // and the clip's end
  std::vector<Subsequence> subs;
  for (int t = 0, k = 0; t < 300; t += 12 + k % 9, ++k) subs.push_back({t, 12 + k % 9, Termination::Rhythm, ""});
  auto plan = [&](int cap, std::uint64_t seed) {
    SearchParams p;
    p.start_candidates = cap;
    std::mt19937_64 rng(seed);
    std::vector<std::vector<int>> paths;
    for (const PlannedSegment& s : plan_reenactment(g, subs, p, rng).segments) paths.push_back(s.path);
    return paths;
  };
  const auto sampled = plan(20, 1);
  EXPECT_EQ(plan(20, 1), sampled);
  EXPECT_EQ(sampled.size(), subs.size());
  EXPECT_EQ(plan(static_cast<int>(keys), 1), plan(0, 1));
  EXPECT_EQ(plan(static_cast<int>(keys), 2), plan(0, 2));
}
}  // namespace
}  // namespace gmg
