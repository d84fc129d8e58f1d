// The ablation run on a synthetic recording: five setups, the paper's rows, sane metrics.
#include <gtest/gtest.h>

#include "engine/app/ablation.h"
#include "engine/core/error.h"
#include "engine/app/synth/synth.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

TEST(Ablation, FiveSetupsScoredOverSeeds) {
  gmg::testing::TempDir dir;
  SynthSpec spec;
  spec.duration_s = 45;
  spec.seed = 21;
  synth_write(synth_speaker(spec), dir.path().string(), "clip");
  const auto rows = ablation_run(dir.file("clip.bvh"), dir.file("clip.wav"), dir.file("clip.tsv"), 2.0 / 3.0, {1, 2}, Config{});
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0].setup, "Weak Detection");
  EXPECT_EQ(rows[4].setup, "Full");
  for (const AblationRow& r : rows) {
    ASSERT_EQ(r.syn.size(), 2u);
    for (double v : r.syn) EXPECT_GT(v, 0.0);
    for (double v : r.div) {
      EXPECT_GE(v, 0.0);
      EXPECT_LE(v, 1.0);
    }
    for (double v : r.bc) {
      EXPECT_GE(v, 0.0);
      EXPECT_LE(v, 1.0);
    }
  }
  for (int f : rows[4].failures) EXPECT_EQ(f, 0);  // the full system never fails
  const std::string md = ablation_markdown(rows);
  EXPECT_NE(md.find("| No Term. Fallback |"), std::string::npos);
  EXPECT_NE(ablation_csv(rows).find("setup,syn_mean"), std::string::npos);
  // Each weakened setup must change the result: the same numbers as the full row would mean the
  // ablation silently ran the full setup.
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    EXPECT_TRUE(rows[i].syn != rows[4].syn || rows[i].failures != rows[4].failures) << rows[i].setup;
  }
  EXPECT_GT(rows[3].failures[0] + rows[3].failures[1], 0) << "without fallbacks some subsequence fails";
  EXPECT_THROW(ablation_run(dir.file("clip.bvh"), dir.file("clip.wav"), "", 0.95, {1}, Config{}), Error);
}

}  // namespace
}  // namespace gmg
