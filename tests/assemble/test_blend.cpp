// Blending junctions: offset and cross-fade modes, curves, short arcs.
#include <gtest/gtest.h>

#include "engine/assemble/blend.h"
#include "tests/assemble/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(Blend, JunctionHasNoJump) {
  // Left sweeps up at 0.04 rad/frame and ends at 1.16. Right pieces as graph transitions give
  // them: (a) 0.24 rad behind where left was heading, sweeping on; (b) exactly where left was
  // heading (a continuous join); (c) turning back from left's last pose. With the default
  // (offset) blend no step across the junction exceeds the largest step of the inputs near it.
  const std::vector<double> a = ramp(0.0, 0.04, 30);
  const std::vector<std::vector<double>> rights = {ramp(0.96, 0.04, 30), ramp(1.20, 0.04, 30), ramp(1.16, -0.04, 30)};
  BlendParams params;  // defaults: offset, sigmoid, l_blend 4
  for (const BlendCurve curve : {BlendCurve::Linear, BlendCurve::Sigmoid}) {
    params.curve = curve;
    for (const std::vector<double>& b : rights) {
      const Motion left = arm_motion(a), right = arm_motion(b);
      const Motion out = blend_concatenate({left, right}, params);
      ASSERT_EQ(out.frame_count, 60);
      const double inputs = std::max(max_step(hand_path(a), 20, 30), max_step(hand_path(b), 0, 10));
      EXPECT_LE(max_step(motion_forward_kinematics(out), 20, 40), inputs * (1.0 + 1e-9))
          << enum_name(kBlendCurveNames, curve) << " from " << b[0];
      // Away from the junction the pieces are untouched.
      EXPECT_LT(rotation_angle_between(out.rotation(10, 1), left.rotation(10, 1)), 1e-9);
      EXPECT_LT(rotation_angle_between(out.rotation(50, 1), right.rotation(20, 1)), 1e-9);
    }
  }
  // A continuous join comes out exactly as the raw concatenation.
  const Motion joined = blend_concatenate({arm_motion(a), arm_motion(rights[1])}, params);
  const Motion whole = arm_motion(ramp(0.0, 0.04, 60));
  for (int f = 0; f < 60; ++f)
    EXPECT_LT(rotation_angle_between(joined.rotation(f, 1), whole.rotation(f, 1)), 1e-7) << f;
  // Without blending, case (a) jumps back by 0.2 rad: the check above can fail.
  params.l_blend = 0;
  const double raw =
      max_step(motion_forward_kinematics(blend_concatenate({arm_motion(a), arm_motion(rights[0])}, params)), 20, 40);
  EXPECT_GT(raw, 4.0 * max_step(hand_path(a), 20, 30));
}

TEST(Blend, GapAlongTheMotionIsSpreadEvenly) {
  // Right starts 0.12 rad ahead of where left was heading: that gap must be covered somewhere;
  // linear offset blending adds exactly 0.12 / (L_l + L_r + 1) to each of the 9 steps.
  BlendParams params;
  params.curve = BlendCurve::Linear;
  params.l_blend = 4;
  const Eigen::MatrixXd p = motion_forward_kinematics(
      blend_concatenate({arm_motion(ramp(0.0, 0.04, 30)), arm_motion(ramp(1.32, 0.04, 30))}, params));
  const double radius = 30.0;
  auto chord = [&](double angle) { return radius * 2.0 * std::sin(angle / 2.0); };
  for (int f = 26; f <= 34; ++f) EXPECT_NEAR((p.row(f) - p.row(f - 1)).norm(), chord(0.04 + 0.12 / 9.0), 1e-9) << f;
  EXPECT_NEAR((p.row(25) - p.row(24)).norm(), chord(0.04), 1e-9);
  EXPECT_NEAR((p.row(36) - p.row(35)).norm(), chord(0.04), 1e-9);
}

TEST(Blend, CrossfadeSpreadsTheJump) {
  // SPEC's literal cross-fade (blend_mode=crossfade). A step inside it is
  // (1-w) dA + w dB + dw (B - A), and |B - A| is at most the gap g plus the motion lost while
  // one side is held (n steps of v), so with linear weights no step exceeds
  // v + (g + n v) / (n + 1): the 0.3 rad jump is spread over the window.
  const std::vector<double> a = ramp(0.0, 0.04, 30);
  BlendParams params;
  params.mode = BlendMode::Crossfade;
  params.curve = BlendCurve::Linear;
  params.l_blend = 4;
  const int n = 8;
  const double v = 0.04, g = 0.3, radius = 30.0;
  auto chord = [&](double angle) { return radius * 2.0 * std::sin(angle / 2.0); };
  for (const std::vector<double>& b : {ramp(1.46, 0.04, 30), ramp(0.86, -0.04, 30)}) {
    const Motion left = arm_motion(a), right = arm_motion(b);
    const double blended = max_step(motion_forward_kinematics(blend_concatenate({left, right}, params)), 20, 40);
    EXPECT_LE(blended, chord(v + (g + n * v) / (n + 1)) * 1.0001);
    params.l_blend = 0;
    const double raw = max_step(motion_forward_kinematics(blend_concatenate({left, right}, params)), 20, 40);
    params.l_blend = 4;
    EXPECT_NEAR(raw, chord(g), 1e-6);
    EXPECT_LT(blended, 0.5 * raw);
  }
}

TEST(Blend, QuaternionsTakeTheShortArc) {
  std::vector<double> a(10, 0.3), b(10, 0.35);
  Motion left = arm_motion(a), right = arm_motion(b);
  for (int f = 0; f < right.frame_count; ++f) right.rotations[right.index(f, 1)] = -right.rotations[right.index(f, 1)];
  for (const BlendMode mode : {BlendMode::Offset, BlendMode::Crossfade}) {
    BlendParams params;
    params.mode = mode;
    const Motion out = blend_concatenate({left, right}, params);
    for (int f = 1; f < out.frame_count; ++f)
      EXPECT_LT(rotation_angle_between(out.rotation(f, 1), out.rotation(f - 1, 1)), 0.05 + 1e-9)
          << enum_name(kBlendModeNames, mode) << " " << f;
  }
}

TEST(Blend, WeightsRiseStrictlyInsideZeroOne) {
  for (const BlendCurve curve : {BlendCurve::Linear, BlendCurve::Sigmoid}) {
    double previous = 0.0;
    for (int i = 0; i < 8; ++i) {
      const double w = blend_weight(i, 8, curve);
      EXPECT_GT(w, previous);
      EXPECT_LT(w, 1.0);
      previous = w;
    }
  }
}

}  // namespace
}  // namespace gmg
