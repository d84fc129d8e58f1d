// Sync metrics with a control: circular shifts, BC and speech correlation lifts.
#include <cmath>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/metrics/evaluate.h"
#include "engine/metrics/sync.h"
#include "engine/motion/bvh.h"
#include "engine/synth/synth.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

TEST(Sync, ShiftsAreSpreadAndFarFromAlignment) {
  const std::vector<double> s = control_shifts(20.0, 8, 2.0);
  ASSERT_EQ(s.size(), 8u);
  EXPECT_DOUBLE_EQ(s.front(), 2.0);
  EXPECT_DOUBLE_EQ(s.back(), 18.0);  // 2 s from a full turn
  for (std::size_t i = 1; i < s.size(); ++i) EXPECT_NEAR(s[i] - s[i - 1], 16.0 / 7, 1e-12);
  EXPECT_THROW(control_shifts(4.9, 8, 2.0), Error);
  EXPECT_THROW(control_shifts(20.0, 1, 2.0), Error);
}

TEST(Sync, CircularShiftRotatesSamples) {
  audio::Audio a{10, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}};
  EXPECT_EQ(circular_shift(a, 0.3).samples, (std::vector<float>{3, 4, 5, 6, 7, 8, 9, 0, 1, 2}));
  EXPECT_EQ(circular_shift(a, 1.0).samples, a.samples);
  EXPECT_EQ(circular_shift(a, -0.2).samples, (std::vector<float>{8, 9, 0, 1, 2, 3, 4, 5, 6, 7}));
}

// The synthetic speaker beats on its stressed syllables: its own motion has a clearly positive BC
// lift, while a speaker of other speech against the same audio stays within the shifted spread.
TEST(Sync, TruthHasLiftAndUnrelatedMotionDoesNot) {
  SynthSpec spec;
  spec.duration_s = 30;
  spec.seed = 21;
  const SynthClip own = synth_speaker(spec);
  spec.seed = 22;
  const SynthClip other = synth_speaker(spec);
  const SyncControl control = sync_control(own.audio);
  const double scale = length_unit_to_cm(own.motion.skeleton);
  const ControlledScore truth = bc_controlled(motion_forward_kinematics(own.motion) * scale, 30.0, control, {});
  const ControlledScore unrelated = bc_controlled(motion_forward_kinematics(other.motion) * scale, 30.0, control, {});
  EXPECT_GT(truth.lift(), 3.0 * truth.shifted_sd()) << truth.aligned << " vs " << truth.shifted_mean();
  EXPECT_LT(std::abs(unrelated.lift()), 2.0 * unrelated.shifted_sd())
      << unrelated.aligned << " vs " << unrelated.shifted_mean();
}

TEST(Sync, SpeechCorrelationSeesZeggsOwnSpeech) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string d = gmg::testing::shared_data_dir() + "/zeggs/067_Speech_2_x_1_0";
  const Motion m = bvh_read(d + ".bvh");
  const SyncControl control = sync_control(audio::read_wav(d + ".wav"));
  const ControlledScore s =
      speech_correlation_controlled(motion_forward_kinematics(m) * length_unit_to_cm(m.skeleton), m.fps, control);
  EXPECT_GT(s.lift(), 3.0 * s.shifted_sd()) << s.aligned << " vs " << s.shifted_mean();
}

TEST(Sync, SpeechCorrelationOfMatchingSignalsIsOne) {
  // A one-joint "motion" whose speed is the envelope itself (onset strength at envelope frames,
  // one motion frame per envelope frame) correlates perfectly at lag 0.
  const double fps = 22050.0 / 512;
  std::vector<float> env(200);
  Eigen::MatrixXd pos = Eigen::MatrixXd::Zero(200, 6);
  double x = 0;
  for (int t = 0; t < 200; ++t) {
    env[static_cast<std::size_t>(t)] = static_cast<float>(std::expm1(1.0 + std::sin(0.3 * t)));
    x += 1.0 + std::sin(0.3 * t);  // speed = log1p(envelope)
    pos(t, 3) = x;
  }
  // Speed at t is the step from t-1 to t, so it leads the envelope by one frame: lag 1 matches.
  EXPECT_GT(metric_speech_correlation(pos, fps, env), 0.99);
}

}  // namespace
}  // namespace gmg
