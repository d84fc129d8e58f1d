// Naturalness ratios: root-relative steps, percentiles, ratios to a reference.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/metrics/metrics.h"
#include "engine/metrics/naturalness.h"

namespace gmg {
namespace {

// Two joints: a root walking along x at `root_speed` cm/frame and a hand circling it.
Eigen::MatrixXd walker(int frames, double root_speed, double hand_radius, double phase = 0.0) {
  Eigen::MatrixXd p(frames, 6);
  for (int t = 0; t < frames; ++t) {
    const double a = 0.2 * t + phase;
    p.row(t) << root_speed * t, 100, 0, root_speed * t + hand_radius * std::cos(a), 100 + hand_radius * std::sin(a), 0;
  }
  return p;
}

TEST(Naturalness, StepsAreRootRelative) {
  // The hand moves on a circle of radius 10 at 0.2 rad/frame: chord 2 * 10 * sin(0.1) per frame,
  // whatever the root's walk adds.
  const std::vector<double> steps = frame_steps(walker(50, 7.0, 10.0));
  ASSERT_EQ(steps.size(), 49u);
  for (double s : steps) EXPECT_NEAR(s, 20.0 * std::sin(0.1), 1e-9);
  EXPECT_NEAR(root_speed(walker(50, 7.0, 10.0), 30.0), 7.0 * 30.0, 1e-9);
}

TEST(Naturalness, PercentileInterpolatesLikeNumpy) {
  // numpy.percentile([1, 2, 3, 4], 50) = 2.5; 99.9 of 0..1000 = 999.
  EXPECT_DOUBLE_EQ(percentile({4, 1, 3, 2}, 50), 2.5);
  std::vector<double> v;
  for (int i = 0; i <= 1000; ++i) v.push_back(i);
  EXPECT_NEAR(percentile(v, 99.9), 999.0, 1e-9);
  EXPECT_DOUBLE_EQ(percentile({5}, 99.9), 5.0);
  EXPECT_THROW(percentile({}, 50), Error);
}

TEST(Naturalness, ContiguousPlaybackAgainstItselfIsOne) {
  // A stretch of the reference scored against the reference: jerk, acceleration and root speed
  // ratios are 1 for the whole clip, and no stretch can jump further than the clip's largest step.
  Eigen::MatrixXd ref = walker(300, 1.5, 12.0);
  for (int t = 0; t < 300; ++t) ref(t, 4) += 3.0 * std::sin(0.05 * t * t / 30.0);  // uneven speed
  const NaturalnessReference r = naturalness_reference(ref, 30.0);
  const Naturalness self = naturalness(ref, 30.0, r);
  EXPECT_NEAR(self.jerk_ratio, 1.0, 1e-9);
  EXPECT_NEAR(self.acc_ratio, 1.0, 1e-9);
  EXPECT_NEAR(self.root_speed_ratio, 1.0, 1e-9);
  const Naturalness stretch = naturalness(ref.middleRows(40, 120), 30.0, r);
  EXPECT_LE(stretch.jump_ratio, self.jump_ratio + 1e-12);
  EXPECT_GE(self.jump_ratio, 1.0);
  // The share above the 99.9th percentile of 299 steps is at most one step: 1 / 299.
  EXPECT_LE(self.step_share, 1.0 / 299 + 1e-12);
}

TEST(Naturalness, AJumpAndAGlideShow) {
  // The reference's hand circles a little wider, so every ordinary step of the test motion is
  // strictly below the reference's 99.9th percentile and only the jump counts.
  const Eigen::MatrixXd ref = walker(200, 0.0, 10.2);
  const NaturalnessReference r = naturalness_reference(ref, 30.0);
  Eigen::MatrixXd jumpy = walker(200, 3.0, 10.0);       // the root glides at 90 cm/s against a still one
  for (int t = 100; t < 200; ++t) jumpy(t, 3) += 15.0;  // the hand jumps 15 cm at frame 100
  const Naturalness n = naturalness(jumpy, 30.0, r);
  EXPECT_NEAR(
      n.jump_ratio,
      (Eigen::Vector3d(jumpy(100, 3) - jumpy(99, 3) - 3.0, jumpy(100, 4) - jumpy(99, 4), 0)).norm() / r.step_p999,
      1e-9);
  EXPECT_GT(n.jump_ratio, 3.0);
  EXPECT_NEAR(n.step_share, 1.0 / 199, 1e-12);
  EXPECT_GT(n.jerk_ratio, 1.5);
  EXPECT_EQ(n.root_speed_ratio, 0.0);  // the reference root never moves: no ratio
}

TEST(Naturalness, SourceTransitionsCountEveryBreakInSourceTime) {
  EXPECT_EQ(source_transitions({}), 0);
  EXPECT_EQ(source_transitions({5, 6, 7, 8}), 0);
  EXPECT_EQ(source_transitions({5, 6, 20, 21, 22, 3}), 2);
  EXPECT_EQ(source_transitions({5, 5, 6}), 1);  // a held frame
  EXPECT_DOUBLE_EQ(transitions_per_second(3, 1.5), 2.0);
}

}  // namespace
}  // namespace gmg
