// The ablation: time folds, seven setups, baselines that are what they claim.
#include <algorithm>
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "engine/ablation/ablation.h"
#include "engine/core/error.h"
#include "engine/metrics/evaluate.h"
#include "engine/metrics/naturalness.h"
#include "engine/motion/bvh.h"
#include "engine/synth/synth.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

TEST(Ablation, FoldsCoverEveryFrameOnce) {
  for (int k : {2, 3, 5, 7}) {
    const std::vector<TimeFold> folds = time_folds(1001, k, 10);
    ASSERT_EQ(static_cast<int>(folds.size()), k);
    std::vector<int> tested(1001, 0);
    for (const TimeFold& f : folds) {
      for (int i = f.test_first; i < f.test_end; ++i) ++tested[static_cast<std::size_t>(i)];
      // The reference is everything else, in at most two pieces.
      int reference = 0;
      for (const auto& [a, b] : f.reference) {
        EXPECT_TRUE(b <= f.test_first || a >= f.test_end);
        reference += b - a;
      }
      EXPECT_EQ(reference + f.test_end - f.test_first, 1001);
      EXPECT_LE(f.reference.size(), 2u);
    }
    for (int c : tested) EXPECT_EQ(c, 1);
  }
  EXPECT_THROW(time_folds(1000, 1, 10), Error);
  EXPECT_THROW(time_folds(1000, 0, 10), Error);
  EXPECT_THROW(time_folds(100, 3, 40), Error);  // parts of 33 frames are too short
}

class AblationRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new gmg::testing::TempDir();
    SynthSpec spec;
    spec.duration_s = 45;
    spec.seed = 21;
    synth_write(synth_speaker(spec), dir_->path().string(), "clip");
    AblationOptions o;
    o.folds = 3;
    o.seeds = {1, 2};
    result_ = new AblationResult(
        ablation_run({dir_->file("clip.bvh"), dir_->file("clip.wav"), dir_->file("clip.tsv")}, o, Config{}));
  }
  static void TearDownTestSuite() {
    delete result_;
    delete dir_;
  }
  static const AblationRow& row(AblationSetup s) {
    return *std::find_if(result_->rows.begin(), result_->rows.end(),
                         [s](const AblationRow& r) { return r.setup == s; });
  }
  static gmg::testing::TempDir* dir_;
  static AblationResult* result_;
};
gmg::testing::TempDir* AblationRun::dir_ = nullptr;
AblationResult* AblationRun::result_ = nullptr;

TEST_F(AblationRun, SevenSetupsOverFoldsAndSeeds) {
  ASSERT_EQ(result_->rows.size(), 7u);
  const char* names[] = {"weak_detection", "weak_pruning", "weak_initialization", "no_fallback",
                         "full",           "contiguous",   "random_chunks"};
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(enum_name(kAblationSetupNames, result_->rows[i].setup), std::string(names[i]));
    ASSERT_EQ(result_->rows[i].scores.size(), 6u);  // 3 folds x 2 seeds
    for (const AblationScore& s : result_->rows[i].scores) {
      EXPECT_GT(s.syn, 0.0);
      EXPECT_GE(s.sync.bc, 0.0);
      EXPECT_LE(s.sync.bc, 1.0);
      EXPECT_GT(s.jerk_ratio, 0.0);
      EXPECT_GE(s.hellinger, 0.0);
      EXPECT_LE(s.hellinger, 1.0);
    }
  }
  EXPECT_EQ(result_->truth.size(), 3u);
}

// Each weakened setup must change its row: the same numbers as the full row would mean the
// ablation silently ran the full setup.
TEST_F(AblationRun, EverySetupChangesWhatItShould) {
  const AblationRow& full = row(AblationSetup::Full);
  auto syn = [](const AblationRow& r) {
    std::vector<double> v;
    for (const AblationScore& s : r.scores) v.push_back(s.syn);
    return v;
  };
  for (AblationSetup s : {AblationSetup::WeakDetection, AblationSetup::WeakPruning, AblationSetup::WeakInitialization,
                          AblationSetup::NoFallback, AblationSetup::Contiguous, AblationSetup::RandomChunks})
    EXPECT_NE(syn(row(s)), syn(full)) << enum_name(kAblationSetupNames, s);
  int failures = 0;
  for (const AblationScore& s : row(AblationSetup::NoFallback).scores) failures += s.failures;
  EXPECT_GT(failures, 0) << "without fallbacks some subsequence fails";
  for (const AblationScore& s : full.scores) EXPECT_EQ(s.failures, 0);
  // Weak detection keeps every onset peak: at least as many test onsets in every fold (the
  // synthetic voice's peaks are mostly strong, so only some folds gain).
  int weak = 0, strong = 0;
  for (std::size_t i = 0; i < full.scores.size(); ++i) {
    EXPECT_GE(row(AblationSetup::WeakDetection).scores[i].test_onsets, full.scores[i].test_onsets) << i;
    weak += row(AblationSetup::WeakDetection).scores[i].test_onsets;
    strong += full.scores[i].test_onsets;
  }
  EXPECT_GT(weak, strong);
}

TEST_F(AblationRun, BaselinesAreWhatTheyClaim) {
  // Contiguous: a stretch of the reference part, so no transition and no step beyond the
  // reference part's own largest (relative to its 99.9th percentile).
  const Motion whole = bvh_read(dir_->file("clip.bvh"));
  const double scale = length_unit_to_cm(whole.skeleton);
  const std::vector<TimeFold> folds = time_folds(whole.frame_count, 3, 1);
  const AblationRow& contiguous = row(AblationSetup::Contiguous);
  const AblationRow& chunks = row(AblationSetup::RandomChunks);
  for (std::size_t f = 0; f < folds.size(); ++f) {
    std::vector<double> steps;
    for (const auto& [a, b] : folds[f].reference) {
      const std::vector<double> s = frame_steps(motion_forward_kinematics(motion_slice(whole, a, b)) * scale);
      steps.insert(steps.end(), s.begin(), s.end());
    }
    const double own = *std::max_element(steps.begin(), steps.end()) / percentile(steps, 99.9);
    for (std::size_t k = 0; k < 2; ++k) {
      const AblationScore& c = contiguous.scores[f * 2 + k];
      if (c.transitions_per_s == 0.0) {
        EXPECT_LE(c.jump_ratio, own + 1e-9) << "fold " << f;
        // One stretch played once: no junction, no frame played twice, nothing to jump back to;
        // the legs follow the same path.
        EXPECT_EQ(c.paths.junctions, 0) << "fold " << f;
        EXPECT_EQ(c.paths.max_plays_upper, 1) << "fold " << f;
        EXPECT_EQ(c.paths.max_plays_lower, 1) << "fold " << f;
        EXPECT_EQ(c.paths.back_jumps_upper, 0) << "fold " << f;
        EXPECT_EQ(c.paths.stance_changes_per_min, 0.0) << "fold " << f;
        EXPECT_TRUE(std::isnan(c.paths.junction_gap_median_cm)) << "fold " << f;
      }
      // Random chunks join pieces that do not follow each other: junctions, each with a pose gap.
      const AblationScore& r = chunks.scores[f * 2 + k];
      EXPECT_GT(r.paths.junctions_per_min, 0.0) << "fold " << f;
      EXPECT_GT(r.paths.junction_gap_median_cm, 0.0) << "fold " << f;
      EXPECT_GT(chunks.scores[f * 2 + k].transitions_per_s, c.transitions_per_s) << "fold " << f;
    }
  }
  // Contiguous playback is natural motion: far smoother than random chunks.
  double cj = 0, rj = 0;
  for (const AblationScore& s : contiguous.scores) cj += s.jerk_ratio;
  for (const AblationScore& s : chunks.scores) rj += s.jerk_ratio;
  EXPECT_LT(cj, rj);
}

TEST_F(AblationRun, TablesHaveTheColumnsAndRows) {
  const std::string csv = ablation_csv(*result_);
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_EQ(header.rfind("setup,syn,syn_sd,bc,bc_sd,bc_lift,bc_lift_sd,div,div_sd,jerk_ratio,jerk_ratio_sd,acc_ratio,"
                         "acc_ratio_sd,hellinger,hellinger_sd,hellinger_wrists,hellinger_wrists_sd,root_speed_ratio,"
                         "root_speed_ratio_sd,jump_ratio,jump_ratio_sd,transitions_per_s,transitions_per_s_sd,failures,"
                         "failures_sd",
                         0),
            0u)
      << header;
  for (const char* name :
       {"knee_share_ratio", "knee_p90_deg", "body_jerk_ratio", "body_jerk_p99_ratio", "still_longest_ratio",
        "still_longest_s", "foot_slide_ratio", "foot_slide_share", "junctions_per_min", "junction_gap_median_cm",
        "stance_changes_per_min", "max_plays_upper", "max_plays_lower", "back_jumps_upper", "back_jumps_lower"}) {
    EXPECT_NE(header.find("," + std::string(name) + "," + name + "_sd"), std::string::npos) << name;
  }
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 8);  // header + 7 setups
  const std::string md = ablation_markdown(*result_);
  for (const char* name : {"| weak_detection |", "| no_fallback |", "| contiguous |", "| random_chunks |"})
    EXPECT_NE(md.find(name), std::string::npos) << name;
  EXPECT_NE(md.find("overflow bin"), std::string::npos);
  // The lifelike table and the per-fold table's truth and full columns.
  for (const char* head : {"| knee share × |", "| junctions/min |", "| back-jumps low |", "| truth knee share × |",
                           "| full foot slide × |"})
    EXPECT_NE(md.find(head), std::string::npos) << head;
}

TEST(Ablation, OneFoldIsAClearError) {
  gmg::testing::TempDir dir;
  SynthSpec spec;
  spec.duration_s = 20;
  synth_write(synth_speaker(spec), dir.path().string(), "clip");
  AblationOptions o;
  o.folds = 1;
  try {
    ablation_run({dir.file("clip.bvh"), dir.file("clip.wav"), ""}, o, Config{});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--folds must be at least 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gmg

namespace gmg {
namespace {

// On the shared ZEGGS recording (6 time folds, each fold's speech new to its graph): the motion
// follows its own speech more than other folds' speech, and more so than the paper's planner
// manages, which cuts at every onset.
TEST(AblationRealData, ZeggsFoldsFollowTheirSpeechBetterThanThePaperPlanner) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string z = gmg::testing::shared_data_dir() + "/zeggs/067_Speech_2_x_1_0";
  AblationOptions o;
  o.folds = 6;
  o.seeds = {1, 2, 3, 4, 5};
  auto lift = [&](const Config& cfg) {
    const AblationResult r = ablation_run({z + ".bvh", z + ".wav", ""}, o, cfg);
    for (const AblationRow& row : r.rows)
      if (row.setup == AblationSetup::Full) {
        double sum = 0.0;
        for (const AblationScore& s : row.scores) sum += s.sync.energy_corr_lift;
        return sum / static_cast<double>(row.scores.size());
      }
    return 0.0;
  };
  Config paper;
  paper.search.planner = PlannerMode::Paper;
  const double ours = lift(Config{}), theirs = lift(paper);
  EXPECT_GT(ours, theirs) << "speech-correlation lift over mismatched speech: ours " << ours << ", paper " << theirs;
  EXPECT_GT(ours, 0.3);
}

}  // namespace
}  // namespace gmg
