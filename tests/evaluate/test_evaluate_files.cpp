// gmg evaluate over files: inputs, skipped metrics, naturalness, trimming, plots, mismatch errors.
#include <filesystem>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/evaluate/evaluate_files.h"
#include "engine/motion/bvh.h"
#include "engine/synth/synth.h"
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
  EXPECT_EQ(k["notes"].size(), 3u);  // no audio, no truth, no truth or reference for naturalness
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
