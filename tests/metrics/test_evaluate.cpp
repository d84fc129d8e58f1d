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
