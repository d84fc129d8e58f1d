// The reenactment report: every subsequence and total taken from the plan.
#include <gtest/gtest.h>

#include "engine/pipeline/report.h"

namespace gmg {
namespace {

PlannedSegment segment(int start, int length, Fallback fallback, bool accepted, bool failure) {
  PlannedSegment s;
  s.sub = {start, length, Termination::Rhythm, ""};
  s.path = {100 + start, 101 + start, 102 + start, 500};
  s.fallback = fallback;
  s.accepted = accepted;
  s.failure = failure;
  return s;
}

TEST(Report, FallbackNamesAndTotalsFollowThePlan) {
  Plan plan;
  plan.segments = {segment(0, 10, Fallback::None, true, false), segment(10, 5, Fallback::KeywordToRhythm, true, false),
                   segment(15, 8, Fallback::IgnoreStops, true, false),
                   segment(23, 7, Fallback::HoldLastFrame, false, false), segment(30, 4, Fallback::None, false, true)};
  plan.segments[1].sub.kind = Termination::Keyword;
  plan.segments[1].sub.keyword = "big";
  SpeechEvents ev;
  ev.total_frames = 34;
  ev.duration_s = 34 / 30.0;
  const nlohmann::ordered_json r = reenactment_report(plan, ev, Config{}, 30.0, 1.0);
  const char* expected[] = {"none", "keyword_to_rhythm", "ignore_stops", "hold_last_frame", "none"};
  ASSERT_EQ(r["subsequences"].size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(r["subsequences"][i]["fallback"], expected[i]) << i;
    EXPECT_EQ(r["subsequences"][i]["start_frame"].get<int>(), plan.segments[i].sub.start);
    EXPECT_EQ(r["subsequences"][i]["path_length"].get<int>(), 4);
  }
  EXPECT_EQ(r["subsequences"][1]["termination"], "keyword");
  EXPECT_EQ(r["subsequences"][1]["keyword"], "big");
  EXPECT_FALSE(r["subsequences"][0].contains("keyword"));
  // Path 100, 101, 102, 500: two runs.
  EXPECT_EQ(r["subsequences"][0]["graph_ranges"].dump(), "[[100,102],[500,500]]");
  EXPECT_EQ(r["totals"]["subsequences"].get<int>(), 5);
  EXPECT_EQ(r["totals"]["accepted"].get<int>(), 3);
  EXPECT_EQ(r["totals"]["failures"].get<int>(), 1);
  EXPECT_EQ(r["totals"]["fallbacks"]["keyword_to_rhythm"].get<int>(), 1);
  EXPECT_EQ(r["totals"]["fallbacks"]["ignore_stops"].get<int>(), 1);
  EXPECT_EQ(r["totals"]["fallbacks"]["hold_last_frame"].get<int>(), 1);
  EXPECT_EQ(r["frames"].get<int>(), 34);
}

}  // namespace
}  // namespace gmg
