// What a report says was played: junctions, stance changes, plays, back-jumps, counted by hand.
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/metrics/played_paths.h"

namespace gmg {
namespace {

// 85 output frames at 30 fps. Upper body:
//   0: frames 0-29 play 100..129 (the first: no junction)
//   1: frames 30-49 play 130..139 then 200..209: continued, one transition inside
//   2: frames 50-59 play 50..59: a junction, gap 12.5 cm
//   3: frames 60-69 play 105..114: a junction, gap 30 cm, back to frames played at output 5-14
//   4: frames 70-79 play 115..124: continued (115 follows 114), although 115 was played before
//   5: frames 80-84 hold 124: a junction of gap 0, and a held frame read again
// Lower body: 0-49 plays 0..49, then 50-84 plays 10..44 (a change to rest, back to frames played
// 40 output frames before).
const char* kReport = R"({
  "fps": 30, "frames": 85,
  "subsequences": [
    {"start_frame": 0, "target_length": 30, "continued": false, "junction_gap_cm": 0.0,
     "transitions_inside": 0, "graph_ranges": [[100, 129]]},
    {"start_frame": 30, "target_length": 20, "continued": true, "junction_gap_cm": 0.0,
     "transitions_inside": 1, "graph_ranges": [[130, 139], [200, 209]]},
    {"start_frame": 50, "target_length": 10, "continued": false, "junction_gap_cm": 12.5,
     "transitions_inside": 0, "graph_ranges": [[50, 59]]},
    {"start_frame": 60, "target_length": 10, "continued": false, "junction_gap_cm": 30.0,
     "transitions_inside": 0, "graph_ranges": [[105, 114]]},
    {"start_frame": 70, "target_length": 10, "continued": true, "junction_gap_cm": 0.0,
     "transitions_inside": 0, "graph_ranges": [[115, 124]]},
    {"start_frame": 80, "target_length": 5, "continued": false, "junction_gap_cm": 0.0,
     "transitions_inside": 0, "graph_ranges": [[124, 124]]}],
  "lower_body": {"stretches": [
    {"start_frame": 0, "length": 50, "change": "start", "graph_ranges": [[0, 49]]},
    {"start_frame": 50, "length": 35, "change": "rest", "graph_ranges": [[10, 44]]}]}
})";

TEST(PlayedPaths, ReadsTheReportsLayers) {
  const PlayedPaths p = played_paths_of(nlohmann::json::parse(kReport), "r.json");
  ASSERT_EQ(p.upper.size(), 6u);
  EXPECT_EQ(p.upper[1].path.size(), 20u);
  EXPECT_EQ(p.upper[1].path[10], 200);
  EXPECT_TRUE(p.upper[1].continued);
  EXPECT_EQ(p.upper[1].transitions_inside, 1);
  EXPECT_EQ(p.upper[2].junction_gap_cm, 12.5);
  ASSERT_EQ(p.lower.size(), 2u);
  EXPECT_EQ(p.lower[1].start_frame, 50);
  EXPECT_EQ(p.lower[1].path.front(), 10);
  EXPECT_EQ(p.stance_changes, 1);
  EXPECT_EQ(played_frames(p.upper).size(), 30u + 20 + 10 + 10 + 10 + 1);
}

TEST(PlayedPaths, JunctionsPlaysAndBackJumps) {
  const PlayedPaths p = played_paths_of(nlohmann::json::parse(kReport), "r.json");
  const LifelikePaths m = lifelike_paths(p, 30.0, 85 / 30.0, LifelikeParams{});
  // Junctions: the transition inside 1, and subsequences 2, 3 and 5; 4 per 85/30 s.
  EXPECT_EQ(m.junctions, 4);
  EXPECT_NEAR(m.junctions_per_min, 4 / (85 / 30.0 / 60.0), 1e-9);
  // Gaps of the subsequence junctions: 12.5, 30, 0: the median 12.5.
  EXPECT_NEAR(m.junction_gap_median_cm, 12.5, 1e-12);
  EXPECT_NEAR(m.stance_changes_per_min, 1 / (85 / 30.0 / 60.0), 1e-9);
  // 105..124 are read twice each (124 held: still one play), 10..44 twice by the lower body.
  EXPECT_EQ(m.max_plays_upper, 2);
  EXPECT_EQ(m.max_plays_lower, 2);
  // Upper: 3 starts at 105, played at output frame 5 (55 frames = 1.83 s before), and 5 holds
  // 124, read at output frame 79. Piece 4 is 3's natural continuation. Lower: 10, 40 frames before.
  EXPECT_EQ(m.back_jumps_upper, 2);
  EXPECT_EQ(m.back_jumps_lower, 1);
}

TEST(PlayedPaths, BackJumpsLookBackOverTheWindowInOutputTime) {
  const PlayedPaths p = played_paths_of(nlohmann::json::parse(kReport), "r.json");
  // Window 1 s = 30 frames: the jump to 105 (55 frames back) no longer counts, the hold (1 frame
  // back) does; 2 s = 60 frames: both.
  EXPECT_EQ(back_jumps(p.upper, 30.0, 1.0), 1);
  EXPECT_EQ(back_jumps(p.upper, 30.0, 2.0), 2);
  EXPECT_EQ(back_jumps(p.lower, 30.0, 1.0), 0);  // 40 frames back
  // A path resampled onto more output frames: 10 graph frames over 19 output frames land 2 apart,
  // so frame 9 of the path is at output frame 18; a jump back to it from output frame 47 is 29
  // frames later (within 1 s), from output frame 48 it is 30 (not).
  std::vector<int> run(28);
  std::iota(run.begin(), run.end(), 100);
  std::vector<PlayedSegment> s = {{0, 19, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, false, 0, 0.0},
                                  {19, 28, run, false, 0, 0.0},
                                  {47, 1, {9}, false, 0, 0.0}};
  EXPECT_EQ(back_jumps(s, 30.0, 1.0), 1);
  s[2].start_frame = 48;
  EXPECT_EQ(back_jumps(s, 30.0, 1.0), 0);
}

TEST(PlayedPaths, WithoutALayeredBodyTheLegsFollowTheUpperPath) {
  nlohmann::json r = nlohmann::json::parse(kReport);
  r.erase("lower_body");
  const LifelikePaths m = lifelike_paths(played_paths_of(r, "r.json"), 30.0, 85 / 30.0, LifelikeParams{});
  EXPECT_EQ(m.stance_changes_per_min, m.junctions_per_min);
  EXPECT_EQ(m.max_plays_lower, m.max_plays_upper);
  EXPECT_EQ(m.back_jumps_lower, m.back_jumps_upper);
  r["lower_body"] = nullptr;  // as a report of an unlayered body may say
  EXPECT_TRUE(played_paths_of(r, "r.json").lower.empty());
}

TEST(PlayedPaths, ReuseCountsPlaysNotHeldFrames) {
  // 3 4 5 | 3 3 3 | 4: frame 3 is played twice (the hold is one play), 4 twice, 5 once.
  const Reuse r = reference_reuse({3, 4, 5, 3, 3, 3, 4}, 10);
  EXPECT_EQ(r.max_plays, 2);
  EXPECT_NEAR(r.coverage, 0.3, 1e-12);
  EXPECT_EQ(reference_reuse({3, 4, 5, 3}, 0).max_plays, 2);  // without a reference: plays only
  EXPECT_EQ(reference_reuse({3, 4, 5, 3}, 0).coverage, 0.0);
  EXPECT_THROW(reference_reuse({3, 12}, 10), Error);
}

std::string error_of(const nlohmann::json& r) {
  try {
    played_paths_of(r, "r.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(PlayedPaths, AMalformedReportNamesTheFileAndTheField) {
  nlohmann::json r = nlohmann::json::parse(kReport);
  r["subsequences"][2].erase("continued");
  EXPECT_EQ(error_of(r), "r.json: subsequence 2 lacks continued");
  r = nlohmann::json::parse(kReport);
  r["subsequences"][1]["graph_ranges"][0] = {139, 130};
  EXPECT_EQ(error_of(r), "r.json: subsequence 1: a graph range is not [first, last] with 0 <= first <= last");
  r = nlohmann::json::parse(kReport);
  r["subsequences"][0]["junction_gap_cm"] = -1;
  EXPECT_EQ(error_of(r), "r.json: subsequence 0: junction_gap_cm is not a number >= 0");
  r = nlohmann::json::parse(kReport);
  r["lower_body"]["stretches"][1].erase("change");
  EXPECT_EQ(error_of(r), "r.json: lower_body stretch 1 lacks change");
  r = nlohmann::json::parse(kReport);
  r["subsequences"][0]["graph_ranges"] = {{0, 2000000000}};
  EXPECT_NE(error_of(r).find("r.json: subsequence 0: a graph range"), std::string::npos);
  EXPECT_EQ(error_of(nlohmann::json::parse("{\"frames\": 3}")),
            "r.json: not a gmg reenactment report (no subsequences)");
}

}  // namespace
}  // namespace gmg
