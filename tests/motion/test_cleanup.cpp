// Tests of engine/motion/cleanup: Savitzky-Golay smoothing and the wrist lock clean-up.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/motion/cleanup.h"
#include "engine/pipeline/pipeline.h"
#include "engine/synth/synth.h"
#include "tests/core/helpers.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

TEST(SavitzkyGolay, FivePointQuadraticWeightsAreTheClassicTable) {
  // Savitzky & Golay (1964): window 5, order 2 smooths with (-3, 12, 17, 12, -3) / 35.
  std::vector<double> impulse(11, 0.0);
  impulse[5] = 1.0;
  const std::vector<double> y = savgol_filter(impulse, 5, 2);
  const double expected[5] = {-3, 12, 17, 12, -3};
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(y[static_cast<std::size_t>(3 + k)], expected[4 - k] / 35.0, 1e-12);
  EXPECT_NEAR(y[0], 0.0, 1e-12);
}

TEST(SavitzkyGolay, PreservesCubicsEverywhereIncludingEdges) {
  std::vector<double> x;
  x.reserve(40);
  for (int i = 0; i < 40; ++i) x.push_back(0.002 * i * i * i - 0.1 * i * i + i - 3.0);
  const std::vector<double> y = savgol_filter(x, 15, 3);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(y[i], x[i], 1e-8) << i;
}

TEST(SavitzkyGolay, ReducesNoise) {
  std::mt19937 rng(4);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<double> x(500);
  for (double& v : x) v = n(rng);
  const std::vector<double> y = savgol_filter(x, 15, 3);
  double vx = 0.0, vy = 0.0;
  for (std::size_t i = 20; i < 480; ++i) vx += x[i] * x[i], vy += y[i] * y[i];
  EXPECT_LT(vy, 0.4 * vx);  // the 15/3 filter passes about 0.3 of white noise power
  EXPECT_THROW(savgol_filter(x, 14, 3), Error);
  EXPECT_EQ(savgol_filter({1.0, 2.0, 4.0}, 15, 3), (std::vector<double>{1.0, 2.0, 4.0}));  // too short: unchanged
}

TEST(Cleanup, LocksSwingAndSmoothsTwistOfNamedJointsOnly) {
  SynthSpec spec;
  spec.duration_s = 3;
  Motion m = synth_speaker(spec).motion;
  const int wrist = m.skeleton.find("RightHand");
  ASSERT_GE(wrist, 0);
  const int other = m.skeleton.find("LeftHand");
  const glm::dvec3 axis = bone_axis(m.skeleton, wrist);
  // Give the wrist a known rotation: a swing about an axis normal to the bone, then a twist
  // following a cubic (which the smoothing must keep).
  const glm::dvec3 normal = glm::normalize(glm::cross(axis, glm::dvec3(0.3, 0.9, 0.1)));
  std::vector<double> twist;
  for (int f = 0; f < m.frame_count; ++f) {
    const double t = f / 30.0;
    twist.push_back(0.4 * t * t * t - 0.9 * t * t + 0.5 * t + 0.2);
    m.rotations[m.index(f, wrist)] =
        glm::angleAxis(0.5 * std::sin(f * 0.3), normal) * glm::angleAxis(twist.back(), axis);
  }
  const Motion before = m;
  motion_lock_and_smooth(m, {"RightHand"}, 15, 3, "clip.bvh");
  for (int f = 0; f < m.frame_count; ++f) {
    const glm::dquat expected = glm::angleAxis(twist[static_cast<std::size_t>(f)], axis);
    EXPECT_LT(rotation_angle_between(m.rotation(f, wrist), expected), 1e-6) << f;
    // The bone keeps pointing along its rest direction: the swing is gone.
    EXPECT_NEAR(glm::length(m.rotation(f, wrist) * axis - axis), 0.0, 1e-9);
    EXPECT_EQ(m.rotation(f, other), before.rotation(f, other));
  }
  try {
    motion_lock_and_smooth(m, {"NoSuchWrist"}, 15, 3, "clip.bvh");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("clip.bvh"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("NoSuchWrist"), std::string::npos);
  }
}

TEST(Cleanup, AppliedToReferencesWhenConfigured) {
  gmg::testing::TempDir dir;
  SynthSpec spec;
  spec.duration_s = 10;
  synth_write(synth_speaker(spec), dir.path().string(), "ref");
  Config cfg;
  config_set(cfg, "lock_joints", "RightHand,LeftHand");
  const MotionGraph g =
      graph_build_from_files({{dir.file("ref.bvh"), {dir.file("ref.wav"), dir.file("ref.tsv")}}}, cfg);
  for (const char* name : {"RightHand", "LeftHand"}) {
    const int j = g.motion.skeleton.find(name);
    const glm::dvec3 axis = bone_axis(g.motion.skeleton, j);
    for (int f = 0; f < g.frame_count(); f += 17)
      EXPECT_NEAR(glm::length(g.motion.rotation(f, j) * axis - axis), 0.0, 1e-9);
  }
  config_set(cfg, "lock_joints", "Nope");
  EXPECT_EQ(testing::error_of([&] {
              graph_build_from_files({{dir.file("ref.bvh"), {dir.file("ref.wav"), ""}}}, cfg);
            }),
            dir.file("ref.bvh") + ": clean-up joint 'Nope' (lock_joints) is not in the skeleton");
}

}  // namespace
}  // namespace gmg
