// The face's metrics: jaw-energy correlation, viseme contrast, expressions out of range.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "engine/core/error.h"
#include "engine/metrics/face_metrics.h"

namespace gmg {
namespace {

TEST(FaceMetrics, JawAnglesOfTheJointNamedJaw) {
  Skeleton sk;
  Joint root, jaw;
  root.name = "pelvis";
  jaw.name = "jaw";
  jaw.parent = 0;
  sk.joints = {root, jaw};
  Motion m = motion_rest(sk, 30.0, 3);
  m.rotations[m.index(1, 1)] = glm::angleAxis(0.3, glm::dvec3(1, 0, 0));
  m.rotations[m.index(2, 1)] = glm::angleAxis(0.5, glm::dvec3(0, 0.6, 0.8));
  const std::vector<double> a = jaw_angles(m);
  ASSERT_EQ(a.size(), 3u);
  EXPECT_NEAR(a[0], 0.0, 1e-12);
  EXPECT_NEAR(a[1], 0.3, 1e-12);
  EXPECT_NEAR(a[2], 0.5, 1e-12);
  m.skeleton.joints[1].name = "head";
  EXPECT_TRUE(jaw_angles(m).empty());
}

TEST(FaceMetrics, FrameRmsOverEachFrame) {
  audio::Audio sound;
  sound.sample_rate = 300;  // 10 samples a frame at 30 fps
  sound.samples.assign(30, 0.0f);
  for (int i = 5; i < 15; ++i) sound.samples[static_cast<std::size_t>(i)] = (i % 2) ? 0.5f : -0.5f;
  const std::vector<double> r = frame_rms(sound, 30.0, 4);
  ASSERT_EQ(r.size(), 4u);
  EXPECT_DOUBLE_EQ(r[0], 0.0);  // samples 0-4 (from -0.5 frames)
  EXPECT_DOUBLE_EQ(r[1], 0.5);  // samples 5-14
  EXPECT_DOUBLE_EQ(r[2], 0.0);  // samples 15-24
  EXPECT_DOUBLE_EQ(r[3], 0.0);  // samples 25-29, then past the end
}

TEST(FaceMetrics, CorrelationOfTheSmoothedTracks) {
  // Smoothed over 3 frames, [0, 3, 0, 3, 0] is [1.5, 1, 2, 1, 1.5] and [1, 2, 1, 2, 1] is
  // [1.5, 4/3, 5/3, 4/3, 1.5]: proportional about their means, so a correlation of 1.
  const std::vector<double> jaw = {0, 3, 0, 3, 0}, energy = {1, 2, 1, 2, 1};
  EXPECT_NEAR(*jaw_energy_correlation(jaw, energy), 1.0, 1e-12);
  const std::vector<double> inverse = {2, 1, 2, 1, 2};
  EXPECT_NEAR(*jaw_energy_correlation(jaw, inverse), -1.0, 1e-12);
  EXPECT_FALSE(jaw_energy_correlation(jaw, {1, 1, 1, 1, 1}).has_value());
  EXPECT_FALSE(jaw_energy_correlation({1, 2}, {1, 2}).has_value());
}

TEST(FaceMetrics, VisemeContrastIsOpenOverClosed) {
  // 8 fps (times exact in binary): frames 0-2 open (0.4 each), frames 3-4 closed (0.1 and 0.3).
  const std::vector<double> jaw = {0.4, 0.4, 0.4, 0.1, 0.3, 9.0};
  const std::vector<MouthSpan> spans = {{0.0, 0.375, true}, {0.375, 0.625, false}};
  EXPECT_NEAR(*viseme_contrast(jaw, spans, 8.0), 0.4 / 0.2, 1e-12);
  EXPECT_FALSE(viseme_contrast(jaw, {{0.0, 0.375, true}}, 8.0).has_value());
}

TEST(FaceMetrics, ShareOfFramesOutOfTheReferencesRange) {
  const std::vector<double> reference = {0.0, 1.0, 1.0, 2.0};  // 2 frames of 2: [0, 1] and [1, 2]
  const std::vector<double> frames = {0.5, 1.5, -0.04, 2.04, -0.06, 1.0, 0.5, 2.2};
  EXPECT_DOUBLE_EQ(expressions_out_of_range(frames, reference, 2, 0.05), 0.5);
  EXPECT_DOUBLE_EQ(expressions_out_of_range(frames, reference, 2, 0.25), 0.0);
  EXPECT_THROW(expressions_out_of_range(frames, {}, 2, 0.05), Error);
}

}  // namespace
}  // namespace gmg
