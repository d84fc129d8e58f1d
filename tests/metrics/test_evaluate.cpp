// gmg evaluate over files: inputs, skipped metrics, mismatch errors.
#include <gtest/gtest.h>

#include "engine/motion/bvh.h"
#include "engine/core/error.h"
#include "engine/metrics/evaluate.h"
#include "engine/app/synth/synth.h"
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
  const auto j = evaluate_files(in, MetricParams{});
  EXPECT_EQ(j["syn"].get<double>(), 0.0);
  EXPECT_EQ(j["hellinger_speed_all"].get<double>(), 0.0);
  EXPECT_TRUE(j.contains("bc"));
  EXPECT_TRUE(j.contains("hellinger_speed_wrists"));  // the synthetic skeleton has hands
  EvaluateInputs alone;
  alone.generated = dir.file("b.bvh");
  const auto k = evaluate_files(alone, MetricParams{});
  EXPECT_FALSE(k.contains("syn"));
  EXPECT_FALSE(k.contains("bc"));
  EXPECT_EQ(k["notes"].size(), 2u);
  EXPECT_GT(k["generated"]["jerk_cm_s3"].get<double>(), 0.0);
}

// Syn compares the generated motion with the truth it is given: against another recording it is
// the mean speed difference of the two, computed here independently of evaluate_files.
TEST_F(Evaluate, SynIsMeasuredAgainstTheGivenTruth) {
  EvaluateInputs in;
  in.generated = dir.file("a.bvh");
  in.truth = dir.file("b.bvh");
  const auto j = evaluate_files(in, MetricParams{});
  const Motion a = bvh_read(dir.file("a.bvh")), b = bvh_read(dir.file("b.bvh"));
  const Eigen::MatrixXd pa = motion_forward_kinematics(a), pb = motion_forward_kinematics(b);  // synth is in cm
  double sum = 0.0;
  for (Eigen::Index t = 1; t < pa.rows(); ++t)
    for (Eigen::Index k = 0; k < pa.cols() / 3; ++k)
      sum += std::abs((pa.block<1, 3>(t, 3 * k) - pa.block<1, 3>(t - 1, 3 * k)).norm() -
                      (pb.block<1, 3>(t, 3 * k) - pb.block<1, 3>(t - 1, 3 * k)).norm());
  const double expected = sum / static_cast<double>((pa.rows() - 1) * (pa.cols() / 3)) * a.fps;
  EXPECT_GT(expected, 1.0);
  EXPECT_NEAR(j["syn"].get<double>(), expected, 1e-9 * expected);
}

TEST_F(Evaluate, SkeletonAndLengthMismatchAreClearErrors) {
  // Length: a shorter clip of the same skeleton.
  Motion a = bvh_read(dir.file("a.bvh"));
  bvh_write(dir.file("short.bvh"), motion_slice(a, 0, 100));
  EvaluateInputs in;
  in.generated = dir.file("a.bvh");
  in.truth = dir.file("short.bvh");
  try {
    evaluate_files(in, MetricParams{});
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
    evaluate_files(in, MetricParams{});
    FAIL();
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("different skeletons"), std::string::npos) << what;
    EXPECT_NE(what.find("Elsewhere"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace gmg
