// engine/pipeline/report_facts: junction times and source frames read back from a reenactment report.
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/pipeline/report_facts.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

TEST(ReportFacts, JunctionsAreWhereTheSourceJumpsAtTheResampledOutputTime) {
  gmg::testing::TempDir dir;
  // Subsequence 1: path 5..9 then 20..24 (10 path frames) stretched onto 19 output frames: the
  // jump is at path index 5, output 0 + 5 * 18 / 9 = 10. Subsequence 2 continues (25 follows 24):
  // no junction. Subsequence 3 starts elsewhere: a junction at its start frame, 24.
  gmg::testing::write_text(dir.file("r.json"), R"({"frames": 30, "parameters": {"min_onset_strength": 3},
    "totals": {"failures": 1},
    "subsequences": [{"start_frame": 0, "target_length": 19, "graph_ranges": [[5, 9], [20, 24]]},
                     {"start_frame": 19, "target_length": 5, "graph_ranges": [[25, 26]]},
                     {"start_frame": 24, "target_length": 6, "graph_ranges": [[60, 62]]}]})");
  const ReportFacts f = read_report_facts(dir.file("r.json"), 20.0);
  ASSERT_EQ(f.junctions_s.size(), 2u);
  EXPECT_DOUBLE_EQ(f.junctions_s[0], 10.0 / 20.0);
  EXPECT_DOUBLE_EQ(f.junctions_s[1], 24.0 / 20.0);
  const std::vector<int> source = {5, 6, 7, 8, 9, 20, 21, 22, 23, 24, 25, 26, 60, 61, 62};
  EXPECT_EQ(f.source_frames, source);
  EXPECT_EQ(f.frames, 30);
  EXPECT_EQ(f.totals["failures"], 1);
  EXPECT_EQ(f.parameters["min_onset_strength"], 3);
}

TEST(ReportFacts, SomethingElseIsAnErrorNamingTheFile) {
  gmg::testing::TempDir dir;
  gmg::testing::write_text(dir.file("x.json"), R"({"subsequences": []})");
  try {
    read_report_facts(dir.file("x.json"), 30);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(dir.file("x.json") + ": not a gmg reenactment report"), std::string::npos);
  }
  gmg::testing::write_text(dir.file("y.json"), R"({"totals": {"failures": 0},
    "subsequences": [{"start_frame": 0, "target_length": 3, "graph_ranges": [[4, 2]]}]})");
  EXPECT_THROW(read_report_facts(dir.file("y.json"), 30), Error);
}

// The report's control (`gmg reenact --keep --range --pin`) read back as stretches of seconds.
TEST(ReportFacts, ControlStretchesInSeconds) {
  gmg::testing::TempDir dir;
  gmg::testing::write_text(dir.file("c.json"), R"({"totals": {"failures": 0},
    "subsequences": [{"start_frame": 0, "target_length": 60, "graph_ranges": [[0, 59]]}],
    "control": {"kept": [[0, 20], [50, 60]], "planned": [[20, 50]],
                "pinned": [{"start_frame": 30, "frames": 10, "graph_frame": 7}]}})");
  const ReportFacts f = read_report_facts(dir.file("c.json"), 10.0);
  using Spans = std::vector<std::pair<double, double>>;
  EXPECT_EQ(f.kept_s, (Spans{{0.0, 2.0}, {5.0, 6.0}}));
  EXPECT_EQ(f.planned_s, (Spans{{2.0, 5.0}}));
  EXPECT_EQ(f.pinned_s, (Spans{{3.0, 4.0}}));
  gmg::testing::write_text(dir.file("bad.json"), R"({"totals": {"failures": 0}, "subsequences": [],
    "control": {"kept": [[5, 2]], "planned": [], "pinned": []}})");
  EXPECT_THROW(read_report_facts(dir.file("bad.json"), 10.0), Error);
}

}  // namespace
}  // namespace gmg
