// Per-frame stance facts (engine/motion/stance.h) of the synthetic speaker's skeleton standing in the
// rest pose (hips 95 cm up, toe ends on the floor at (+-9, 0, 13)), with the hips carried at known
// speeds and with the left leg lifted; expected values worked out from the skeleton's offsets.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/motion/stance.h"
#include "engine/synth/synth.h"

namespace gmg {
namespace {

constexpr int kFrames = 60;
constexpr double kFps = 30.0;
// Hips (0, 95, 0) to a toe end (+-9, 0, 13).
const double kLeg = std::sqrt(9.0 * 9.0 + 95.0 * 95.0 + 13.0 * 13.0);

Motion standing() {
  Motion m = motion_rest(synth_skeleton(), kFps, kFrames);
  for (int f = 0; f < kFrames; ++f) m.translations[m.index(f, 0)] = glm::dvec3(0.0, 95.0, 0.0);
  return m;
}

CaptureRuns one_run() { return CaptureRuns(kFrames, {kFrames - 1}); }

Stance facts(const Motion& m) { return stance_facts(m, one_run(), find_body_layers(motion_slice(m, 0, 1))); }

float pose(const Stance& s, int f, int d) {
  return s.pose[static_cast<std::size_t>(f) * kStanceDims + static_cast<std::size_t>(d)];
}

TEST(Stance, StandingStill) {
  const Stance s = facts(standing());
  ASSERT_TRUE(s.known);
  EXPECT_DOUBLE_EQ(s.leg_length, kLeg);
  ASSERT_EQ(s.pose.size(), static_cast<std::size_t>(kFrames * kStanceDims));
  ASSERT_EQ(s.place.size(), static_cast<std::size_t>(2 * kFrames));
  ASSERT_EQ(s.speed.size(), static_cast<std::size_t>(kFrames));
  ASSERT_EQ(s.planted.size(), static_cast<std::size_t>(kFrames));
  const float expected[kStanceDims] = {static_cast<float>(9.0 / kLeg),
                                       static_cast<float>(-95.0 / kLeg),
                                       static_cast<float>(13.0 / kLeg),
                                       static_cast<float>(-9.0 / kLeg),
                                       static_cast<float>(-95.0 / kLeg),
                                       static_cast<float>(13.0 / kLeg),
                                       static_cast<float>(95.0 / kLeg),
                                       0.0f,
                                       0.0f};
  for (int f = 0; f < kFrames; ++f) {
    for (int d = 0; d < kStanceDims; ++d) EXPECT_NEAR(pose(s, f, d), expected[d], 1e-6) << f << " " << d;
    EXPECT_EQ(s.place[2 * static_cast<std::size_t>(f)], 0.0f);
    EXPECT_EQ(s.place[2 * static_cast<std::size_t>(f) + 1], 0.0f);
    EXPECT_EQ(s.speed[static_cast<std::size_t>(f)], 0.0f);
    EXPECT_EQ(s.planted[static_cast<std::size_t>(f)], 1) << f;
  }
  EXPECT_EQ(s.still_speed, 0.0f);
  EXPECT_EQ(stance_distance(s, 0, kFrames - 1), 0.0);
}

TEST(Stance, TheSameFacingElsewhere) {
  // Turned 90 degrees about +Y: the pose is in the hips' heading frame, so it does not change.
  Motion m = standing();
  for (int f = 0; f < kFrames; ++f) m.rotations[m.index(f, 0)] = glm::angleAxis(0.5 * M_PI, glm::dvec3(0, 1, 0));
  const Stance turned = facts(m), still = facts(standing());
  for (int f = 0; f < kFrames; ++f)
    for (int d = 0; d < kStanceDims; ++d) EXPECT_NEAR(pose(turned, f, d), pose(still, f, d), 1e-6);
  EXPECT_NEAR(stance_distance(turned, 0, 0), 0.0, 0.0);
}

TEST(Stance, PelvisTiltIsTheImageOfUp) {
  // The hips tilted 0.2 rad about +Z: +Y goes to (-sin 0.2, cos 0.2, 0).
  Motion m = standing();
  for (int f = 0; f < kFrames; ++f) m.rotations[m.index(f, 0)] = glm::angleAxis(0.2, glm::dvec3(0, 0, 1));
  const Stance s = facts(m);
  EXPECT_NEAR(pose(s, 10, 7), -std::sin(0.2), 1e-6);
  EXPECT_NEAR(pose(s, 10, 8), 0.0, 1e-6);
}

// The whole body carried along +X at `speed` leg lengths a second.
Stance carried(double speed) {
  Motion m = standing();
  for (int f = 0; f < kFrames; ++f) m.translations[m.index(f, 0)] = glm::dvec3(speed * kLeg * f / kFps, 95.0, 0.0);
  return facts(m);
}

TEST(Stance, HipsCarriedSlowlyStayPlanted) {
  // 0.05 leg lengths a second: under both the feet's contact speed (0.15) and kStanceHipSpeed (0.08).
  const Stance s = carried(0.05);
  for (int f = 0; f < kFrames; ++f) {
    EXPECT_NEAR(s.place[2 * static_cast<std::size_t>(f)], 0.05 * f / kFps, 1e-6);
    EXPECT_EQ(s.place[2 * static_cast<std::size_t>(f) + 1], 0.0f);
    EXPECT_EQ(s.planted[static_cast<std::size_t>(f)], 1) << f;
    // The legs move with the hips: nothing relative to them.
    EXPECT_NEAR(s.speed[static_cast<std::size_t>(f)], 0.0f, 1e-6);
  }
}

TEST(Stance, HipsFasterThanTheStanceSpeedAreNotPlanted) {
  // 0.10 leg lengths a second: the feet still count as in contact (under 0.15), the hips do not (0.08).
  const Stance s = carried(0.10);
  for (int f = 0; f < kFrames; ++f) EXPECT_EQ(s.planted[static_cast<std::size_t>(f)], 0) << f;
  // The hips' height is measured from the run's floor, not the origin.
  EXPECT_NEAR(pose(s, 30, 6), 95.0 / kLeg, 1e-6);
}

TEST(Stance, ALiftedFootIsNotPlanted) {
  // Frames 20-39: the left thigh swung forward 45 degrees (its toe 35 cm up), then back down.
  Motion m = standing();
  const int thigh = m.skeleton.find("LeftUpLeg");
  const double a = -0.25 * M_PI;
  for (int f = 20; f < 40; ++f) m.rotations[m.index(f, thigh)] = glm::angleAxis(a, glm::dvec3(1, 0, 0));
  const Stance s = facts(m);
  for (int f = 0; f < kFrames; ++f) EXPECT_EQ(s.planted[static_cast<std::size_t>(f)], f < 20 || f > 40 ? 1 : 0) << f;
  // The toe end, thigh to toe (0, -90, 13) turned about X, moves 2 |(0, -90, 13)| sin(22.5 deg) in one
  // frame at 20 and back at 40; nothing else moves.
  const double jump = 2.0 * std::sqrt(90.0 * 90.0 + 13.0 * 13.0) * std::sin(0.125 * M_PI) * kFps / kLeg;
  for (int f = 0; f < kFrames; ++f)
    EXPECT_NEAR(s.speed[static_cast<std::size_t>(f)], f == 20 || f == 40 ? jump : 0.0, 1e-4) << f;
  EXPECT_EQ(s.still_speed, 0.0f);
  // The left foot's place relative to the hips while lifted: (9, -5, 0) + R (0, -90, 13).
  const double h = std::sqrt(0.5);
  EXPECT_NEAR(pose(s, 30, 0), 9.0 / kLeg, 1e-6);
  EXPECT_NEAR(pose(s, 30, 1), (-5.0 - 90.0 * h + 13.0 * h) / kLeg, 1e-6);
  EXPECT_NEAR(pose(s, 30, 2), (90.0 * h + 13.0 * h) / kLeg, 1e-6);
  // The right foot has not moved.
  EXPECT_NEAR(pose(s, 30, 3), -9.0 / kLeg, 1e-6);
  EXPECT_NEAR(pose(s, 30, 4), -95.0 / kLeg, 1e-6);
  EXPECT_GT(stance_distance(s, 10, 30), 0.5);
}

TEST(Stance, UnknownWithoutLegsOrFrames) {
  const Motion m = standing();
  EXPECT_FALSE(stance_facts(m, one_run(), BodyLayers{}).known);
  const Motion one = motion_slice(m, 0, 1);
  EXPECT_FALSE(stance_facts(one, CaptureRuns(1, {0}), find_body_layers(one)).known);
}

}  // namespace
}  // namespace gmg
