// gmg evaluate over files: inputs, skipped metrics, naturalness, lifelike metrics, trimming, plots,
// mismatch errors.
#include <filesystem>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/evaluate/evaluate_files.h"
#include "engine/motion/bvh.h"
#include "engine/synth/synth.h"
#include "tests/cli/cli_run.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

class Evaluate : public ::testing::Test {
 protected:
  void SetUp() override {
    SynthSpec spec;
    spec.duration_s = 10;
    spec.seed = 5;
    synth_write(synth_speaker(spec), dir.path().string(), "a");
    spec.seed = 6;
    synth_write(synth_speaker(spec), dir.path().string(), "b");
  }
  gmg::testing::TempDir dir;
};

TEST_F(Evaluate, AgainstItselfSynIsZeroAndSkipsAreNoted) {
  EvaluateInputs in;
  in.generated = dir.file("a.bvh");
  in.truth = dir.file("a.bvh");
  in.audio = dir.file("a.wav");
  const auto j = evaluate_files(in, EvaluateOptions{}).json;
  EXPECT_EQ(j["syn"].get<double>(), 0.0);
  EXPECT_EQ(j["hellinger_speed_all"].get<double>(), 0.0);
  EXPECT_TRUE(j.contains("bc"));
  EXPECT_TRUE(j.contains("hellinger_speed_wrists"));  // the synthetic skeleton has hands
  EvaluateInputs alone;
  alone.generated = dir.file("b.bvh");
  const auto k = evaluate_files(alone, EvaluateOptions{}).json;
  EXPECT_FALSE(k.contains("syn"));
  EXPECT_FALSE(k.contains("bc"));
  // No audio, no truth, no truth or reference for naturalness nor the lifelike ratios, no report.
  EXPECT_EQ(k["notes"].size(), 5u);
  EXPECT_GT(k["generated"]["jerk_cm_s3"].get<double>(), 0.0);
}

// Syn compares the generated motion with the truth it is given: against another recording it is
// the mean speed difference of the two, computed here independently of evaluate_files.
TEST_F(Evaluate, SynIsMeasuredAgainstTheGivenTruth) {
  EvaluateInputs in;
  in.generated = dir.file("a.bvh");
  in.truth = dir.file("b.bvh");
  const auto j = evaluate_files(in, EvaluateOptions{}).json;
  const Motion a = bvh_read(dir.file("a.bvh")), b = bvh_read(dir.file("b.bvh"));
  const Eigen::MatrixXd pa = motion_forward_kinematics(a), pb = motion_forward_kinematics(b);  // synth is in cm
  double sum = 0.0;
  for (Eigen::Index t = 1; t < pa.rows(); ++t)
    for (Eigen::Index k = 0; k < pa.cols() / 3; ++k)
      sum += std::abs((pa.block<1, 3>(t, 3 * k) - pa.block<1, 3>(t - 1, 3 * k)).norm() -
                      (pb.block<1, 3>(t, 3 * k) - pb.block<1, 3>(t - 1, 3 * k)).norm());
  const Eigen::Index joints = pa.cols() / 3;  // whole: three columns per joint
  const double expected = sum / static_cast<double>((pa.rows() - 1) * joints) * a.fps;
  EXPECT_GT(expected, 1.0);
  EXPECT_NEAR(j["syn"].get<double>(), expected, 1e-9 * expected);
}

TEST_F(Evaluate, NaturalnessAgainstTruthOrReference) {
  EvaluateInputs in;
  in.generated = dir.file("a.bvh");
  in.truth = dir.file("a.bvh");
  const auto self = evaluate_files(in, EvaluateOptions{}).json;
  EXPECT_EQ(self["naturalness"]["ratios_against"], "truth");
  EXPECT_NEAR(self["naturalness"]["jerk_ratio"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(self["naturalness"]["root_speed_ratio"].get<double>(), 1.0, 1e-12);
  // Against another speaker's capture as the reference, without truth.
  EvaluateInputs ref;
  ref.generated = dir.file("a.bvh");
  ref.reference = dir.file("b.bvh");
  const auto j = evaluate_files(ref, EvaluateOptions{}).json;
  EXPECT_EQ(j["naturalness"]["ratios_against"], "reference");
  EXPECT_EQ(j["naturalness"]["steps_against"], "reference");
  EXPECT_GT(j["naturalness"]["jerk_ratio"].get<double>(), 0.0);
  EXPECT_NE(j["naturalness"]["jerk_ratio"].get<double>(), 1.0);
}

// The motion against itself as the truth: every lifelike ratio of a motion is 1; the path metrics
// of a hand-written report: 0..149 played twice (frames 0-149 and 150-299 of 10 s).
TEST_F(Evaluate, LifelikeAgainstItselfAndFromTheReport) {
  gmg::testing::write_text(dir.file("r.json"), R"({"totals": {"failures": 0}, "subsequences": [
    {"start_frame": 0, "target_length": 150, "continued": false, "junction_gap_cm": 0,
     "transitions_inside": 0, "graph_ranges": [[0, 149]]},
    {"start_frame": 150, "target_length": 150, "continued": false, "junction_gap_cm": 20.5,
     "transitions_inside": 0, "graph_ranges": [[0, 149]]}]})");
  EvaluateInputs in;
  in.generated = dir.file("a.bvh");
  in.truth = dir.file("a.bvh");
  in.report = dir.file("r.json");
  const auto j = evaluate_files(in, EvaluateOptions{}).json;
  ASSERT_TRUE(j.contains("lifelike")) << j.dump();
  const auto& l = j["lifelike"];
  EXPECT_EQ(l["against"], "truth");
  EXPECT_DOUBLE_EQ(l["body_jerk_ratio"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(l["body_jerk_p99_ratio"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(l["still_longest_ratio"].get<double>(), 1.0);
  EXPECT_EQ(l["still_longest_s"], l["reference_still_longest_s"]);
  EXPECT_EQ(l["knee_p90_deg"], l["reference_knee_p90_deg"]);
  // One junction in 10 s: 6 a minute, its gap 20.5 cm; every frame played twice, and the second
  // subsequence jumps back to frame 0, played 5 s before. No lower body: the legs follow.
  EXPECT_DOUBLE_EQ(l["junctions_per_min"].get<double>(), 6.0);
  EXPECT_DOUBLE_EQ(l["junction_gap_median_cm"].get<double>(), 20.5);
  EXPECT_DOUBLE_EQ(l["stance_changes_per_min"].get<double>(), 6.0);
  EXPECT_EQ(l["max_plays_upper"], 2);
  EXPECT_EQ(l["max_plays_lower"], 2);
  EXPECT_EQ(l["back_jumps_upper"], 1);
  EXPECT_EQ(l["back_jumps_lower"], 1);
  EXPECT_FALSE(l.contains("coverage"));  // no --reference
  EXPECT_FALSE(j.contains("behaviour"));
}

// End to end: `gmg evaluate --json` of a reenactment against its graph prints every lifelike field.
TEST_F(Evaluate, CommandLineJsonHasTheLifelikeFields) {
  using gmg::testing::run_gmg;
  ASSERT_EQ(run_gmg({"build", "--motion", dir.file("a.bvh"), "--audio", dir.file("a.wav"), "--transcript",
                     dir.file("a.tsv"), "-o", dir.file("a.gmg")})
                .code,
            0);
  ASSERT_EQ(run_gmg({"reenact", "--graph", dir.file("a.gmg"), "--audio", dir.file("b.wav"), "--transcript",
                     dir.file("b.tsv"), "-o", dir.file("out.bvh"), "--report", dir.file("out.json"), "--seed", "1"})
                .code,
            0);
  const gmg::testing::CliRun e = run_gmg({"evaluate", "--generated", dir.file("out.bvh"), "--report",
                                          dir.file("out.json"), "--reference", dir.file("a.gmg"), "--json"});
  ASSERT_EQ(e.code, 0) << e.err;
  const nlohmann::json j = nlohmann::json::parse(e.out);
  const nlohmann::json& l = j.at("lifelike");
  EXPECT_EQ(l["against"], "reference");
  for (const char* key :
       {"knee_share_ratio", "knee_p90_deg", "reference_knee_p90_deg", "body_jerk_ratio", "body_jerk_p99_ratio",
        "still_longest_ratio", "still_longest_s", "reference_still_longest_s", "foot_slide_ratio", "foot_slide_share",
        "reference_foot_slide_share", "junctions_per_min", "junction_gap_median_cm", "stance_changes_per_min",
        "max_plays_upper", "max_plays_lower", "back_jumps_upper", "back_jumps_lower", "coverage"}) {
    ASSERT_TRUE(l.contains(key)) << key << " missing from " << l.dump();
    // A ratio over a reference value of 0 is null; everything else is a number.
    if (std::string(key) != "foot_slide_ratio") {
      EXPECT_TRUE(l[key].is_number()) << key << ": " << l[key];
    }
  }
  EXPECT_GE(l["max_plays_upper"].get<int>(), 1);
  EXPECT_GT(l["junctions_per_min"].get<double>(), 0.0);
  EXPECT_GT(l["coverage"].get<double>(), 0.0);
}

TEST_F(Evaluate, TrimCutsTheLongerClipAndSaysBy) {
  const Motion a = bvh_read(dir.file("a.bvh"));
  bvh_write(dir.file("short.bvh"), motion_slice(a, 0, 298));
  EvaluateInputs in;
  in.generated = dir.file("a.bvh");
  in.truth = dir.file("short.bvh");
  in.trim = true;
  const EvaluateResult r = evaluate_files(in, EvaluateOptions{});
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("cut 2 frame(s)"), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("a.bvh"), std::string::npos) << r.warnings[0];
  EXPECT_EQ(r.json["frames"].get<int>(), 298);
  EXPECT_EQ(r.json["syn"].get<double>(), 0.0);  // the same motion once cut
}

TEST_F(Evaluate, PlotsPngAndSvg) {
  EvaluateInputs in;
  in.generated = dir.file("a.bvh");
  in.truth = dir.file("b.bvh");
  in.audio = dir.file("a.wav");
  in.plot = dir.file("p.png");
  evaluate_files(in, EvaluateOptions{});
  const std::string png = read_file_bytes(dir.file("p.png"));
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  in.plot = dir.file("p.svg");
  evaluate_files(in, EvaluateOptions{});
  EXPECT_NE(read_file_bytes(dir.file("p.svg")).find("<svg"), std::string::npos);
  in.plot = dir.file("p.jpg");
  EXPECT_THROW(evaluate_files(in, EvaluateOptions{}), Error);
  EXPECT_FALSE(std::filesystem::exists(dir.file("p.jpg")));
}

TEST_F(Evaluate, SkeletonAndLengthMismatchAreClearErrors) {
  // Length: a shorter clip of the same skeleton.
  Motion a = bvh_read(dir.file("a.bvh"));
  bvh_write(dir.file("short.bvh"), motion_slice(a, 0, 100));
  EvaluateInputs in;
  in.generated = dir.file("a.bvh");
  in.truth = dir.file("short.bvh");
  try {
    (void)evaluate_files(in, EvaluateOptions{});
    FAIL();
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("300 frames"), std::string::npos) << what;
    EXPECT_NE(what.find("100"), std::string::npos) << what;
  }
  // Skeleton: rename a joint.
  a.skeleton.joints[3].name = "Elsewhere";
  bvh_write(dir.file("other.bvh"), a);
  in.truth = dir.file("other.bvh");
  try {
    (void)evaluate_files(in, EvaluateOptions{});
    FAIL();
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("different skeletons"), std::string::npos) << what;
    EXPECT_NE(what.find("Elsewhere"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace gmg
