// The speech analysis written out for users: the same events the planner uses.
#include <algorithm>
#include <filesystem>

#include <gtest/gtest.h>

#include "audio/audio_file.h"
#include "engine/core/csv.h"
#include "engine/core/error.h"
#include "engine/pipeline/speech_report.h"
#include "engine/synth/synth.h"
#include "tests/cli/cli_run.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

TEST(SpeechReport, HoldsTheEventsAndFeaturesThePlannerUses) {
  gmg::testing::TempDir dir;
  SynthSpec spec;
  spec.duration_s = 12.0;
  spec.seed = 5;
  synth_write(synth_speaker(spec), dir.path().string(), "s");
  const SpeechFiles files{dir.file("s.wav"), dir.file("s.tsv")};
  const Config cfg;
  const nlohmann::ordered_json r = speech_report_json(files, 30.0, cfg);
  // The planner's events of the same speech on the same grid.
  const SpeechEvents ev = speech_analyse(files, 30.0, -1, cfg.graph, lexicon_for(cfg.graph));
  EXPECT_EQ(r["frames"].get<int>(), ev.total_frames);
  std::vector<int> frames;
  for (const auto& o : r["onsets"]) {
    frames.push_back(o["frame"].get<int>());
    EXPECT_GE(o["strength"].get<double>(), cfg.graph.min_onset_strength);
    EXPECT_NEAR(o["time_s"].get<double>() * 30.0, o["frame"].get<double>(), 0.5);
  }
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  EXPECT_EQ(frames, ev.onset_frames);
  ASSERT_FALSE(ev.keyword_frames.empty()) << "the synthetic transcript has keywords";
  std::size_t k = 0;
  for (const auto& kw : r["keywords"])
    if (k < ev.keyword_frames.size() && kw["frame"].get<int>() == ev.keyword_frames[k].first) {
      EXPECT_EQ(kw["keyword"].get<std::string>(), ev.keyword_frames[k].second);
      ++k;
    }
  EXPECT_EQ(k, ev.keyword_frames.size());
  const auto& loud = r["features"]["loudness"];
  ASSERT_EQ(static_cast<int>(loud.size()), ev.total_frames);
  for (int f = 0; f < ev.total_frames; ++f)
    EXPECT_FLOAT_EQ(loud[static_cast<std::size_t>(f)].get<float>(),
                    ev.features.values[2 * static_cast<std::size_t>(f)]);
  double paused = 0.0;
  for (const auto& p : r["features"]["pause"]) paused += p.get<double>();
  EXPECT_GT(paused, 0.0) << "the synthetic speaker pauses between phrases";
  // CSV: a header, then one line per onset and keyword.
  const std::vector<CsvRow> rows = csv_parse(speech_report_csv(r), "report.csv");
  ASSERT_EQ(rows.size(), 1 + r["onsets"].size() + r["keywords"].size());
  EXPECT_EQ(rows[1].fields[0], "onset");
  EXPECT_EQ(rows.back().fields[0], "keyword");
}

// The phones the face track plays: a TextGrid's phones tier, symbols without their stress digits,
// each with its viseme; none for a transcript without phones.
TEST(SpeechReport, ListsThePhonesOfATextGridsPhonesTier) {
  gmg::testing::TempDir dir;
  SynthSpec spec;
  spec.duration_s = 4.0;
  spec.seed = 3;
  synth_write(synth_speaker(spec), dir.path().string(), "s");
  const std::string grid = R"(File type = "ooTextFile"
Object class = "TextGrid"

xmin = 0
xmax = 4
tiers? <exists>
size = 2
item []:
    item [1]:
        class = "IntervalTier"
        name = "words"
        xmin = 0
        xmax = 4
        intervals: size = 2
        intervals [1]:
            xmin = 0
            xmax = 1.2
            text = ""
        intervals [2]:
            xmin = 1.2
            xmax = 1.5
            text = "map"
    item [2]:
        class = "IntervalTier"
        name = "phones"
        xmin = 0
        xmax = 4
        intervals: size = 4
        intervals [1]:
            xmin = 0
            xmax = 1.2
            text = ""
        intervals [2]:
            xmin = 1.2
            xmax = 1.3
            text = "M"
        intervals [3]:
            xmin = 1.3
            xmax = 1.42
            text = "AE1"
        intervals [4]:
            xmin = 1.42
            xmax = 1.5
            text = "P"
)";
  gmg::testing::write_text(dir.file("s.TextGrid"), grid);
  const Config cfg;
  const nlohmann::ordered_json r = speech_report_json({dir.file("s.wav"), dir.file("s.TextGrid")}, 30.0, cfg);
  ASSERT_EQ(r["phones"].size(), 3u) << r["phones"].dump();
  EXPECT_EQ(r["phones"][0]["phone"], "M");
  EXPECT_EQ(r["phones"][0]["viseme"], "bilabial");
  EXPECT_DOUBLE_EQ(r["phones"][0]["start_s"].get<double>(), 1.2);
  EXPECT_EQ(r["phones"][1]["phone"], "AE");
  EXPECT_EQ(r["phones"][1]["viseme"], "open vowel");
  EXPECT_DOUBLE_EQ(r["phones"][2]["end_s"].get<double>(), 1.5);
  EXPECT_TRUE(speech_report_json({dir.file("s.wav"), dir.file("s.tsv")}, 30.0, cfg)["phones"].empty());
  // A phones tier past the audio's end is refused, as a transcript's words are, naming the file.
  std::string past = grid;
  past.replace(past.rfind("xmax = 1.5"), 10, "xmax = 9.5");
  gmg::testing::write_text(dir.file("past.TextGrid"), past);
  try {
    speech_report_json({dir.file("s.wav"), dir.file("past.TextGrid")}, 30.0, cfg);
    ADD_FAILURE() << "accepted a phone ending at 9.5 s in 4 s of audio";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("past.TextGrid: the phones tier runs past the end of the audio: phone \"P\""),
              std::string::npos)
        << e.what();
  }
}

TEST(SpeechReport, TheCommandWritesJsonOrCsvAndRefusesOtherNames) {
  gmg::testing::TempDir dir;
  SynthSpec spec;
  spec.duration_s = 6.0;
  synth_write(synth_speaker(spec), dir.path().string(), "s");
  EXPECT_EQ(gmg::testing::run_gmg({"analyse", "--audio", dir.file("s.wav"), "-o", dir.file("a.csv")}).code, 0);
  EXPECT_EQ(gmg::testing::run_gmg(
                {"analyse", "--audio", dir.file("s.wav"), "--transcript", dir.file("s.tsv"), "-o", dir.file("a.json")})
                .code,
            0);
  EXPECT_TRUE(std::filesystem::exists(dir.file("a.csv")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("a.json")));
  const auto bad = gmg::testing::run_gmg({"analyse", "--audio", dir.file("s.wav"), "-o", dir.file("a.txt")});
  EXPECT_EQ(bad.code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir.file("a.txt")));
}

}  // namespace
}  // namespace gmg
