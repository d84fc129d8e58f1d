// Jerk spikes (engine/motion/spikes.h) of the synthetic speaker's left hand swinging smoothly
// (forearm rotating 0.3 rad sin(2 pi f / 40) about Z, jerk about 0.03 cm/frame^3), with one frame
// jolted, a capture break placed on a jump, and without either.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/motion/spikes.h"
#include "engine/synth/synth.h"

namespace gmg {
namespace {

constexpr int kFrames = 120;

// The left forearm swings; `extra(f)` is added to its angle at frame f.
template <typename Extra>
Motion swinging(const Extra& extra) {
  Motion m = motion_rest(synth_skeleton(), 30.0, kFrames);
  const int fore = m.skeleton.find("LeftForeArm");
  for (int f = 0; f < kFrames; ++f) {
    const double a = 0.3 * std::sin(2.0 * M_PI * f / 40.0) + extra(f);
    m.rotations[m.index(f, fore)] = glm::angleAxis(a, glm::dvec3(0, 0, 1));
  }
  return m;
}

std::vector<int> hand(const Motion& m) { return {m.skeleton.find("LeftHand")}; }

std::vector<int> marked(const std::vector<std::uint8_t>& spikes) {
  std::vector<int> out;
  for (std::size_t f = 0; f < spikes.size(); ++f)
    if (spikes[f]) out.push_back(static_cast<int>(f));
  return out;
}

TEST(Spikes, SmoothMotionHasNone) {
  const Motion m = swinging([](int) { return 0.0; });
  const std::vector<std::uint8_t> s = jerk_spikes(m, CaptureRuns(kFrames, {kFrames - 1}), hand(m));
  ASSERT_EQ(s.size(), static_cast<std::size_t>(kFrames));
  EXPECT_TRUE(marked(s).empty());
}

TEST(Spikes, OneJoltedFrame) {
  // Frame 60 jolted by 0.5 rad: the hand leaps 2 * 25 cm * sin(0.25) = 12 cm and back, 400 times the
  // smooth jerk. The third difference over frames f-3..f (placed at f-1) is then
  // +d, -3d, +3d, -d at frames 59, 60, 61, 62: each over the limit, each widened by 2 frames.
  const int jolt = 60;
  const Motion m = swinging([&](int f) { return f == jolt ? 0.5 : 0.0; });
  const std::vector<std::uint8_t> s = jerk_spikes(m, CaptureRuns(kFrames, {kFrames - 1}), hand(m));
  std::vector<int> expected;
  for (int f = jolt - 1 - kSpikeMargin; f <= jolt + 2 + kSpikeMargin; ++f) expected.push_back(f);
  EXPECT_EQ(marked(s), expected);
  // The jolted frame and kSpikeMargin frames either side are always among them.
  for (int f = jolt - kSpikeMargin; f <= jolt + kSpikeMargin; ++f) EXPECT_EQ(s[static_cast<std::size_t>(f)], 1) << f;
}

TEST(Spikes, OnlyTheGivenJointsCount) {
  const Motion m = swinging([](int f) { return f == 60 ? 0.5 : 0.0; });
  const CaptureRuns runs(kFrames, {kFrames - 1});
  // The right hand never moves: its median jerk is 0 and a still joint has no spikes.
  EXPECT_TRUE(marked(jerk_spikes(m, runs, {m.skeleton.find("RightHand")})).empty());
  EXPECT_TRUE(marked(jerk_spikes(m, runs, {})).empty());
}

TEST(Spikes, AJumpAtACaptureBreakIsNotASpike) {
  // From frame 60 on the forearm is turned 0.5 rad further: a jump between frames 59 and 60.
  const Motion m = swinging([](int f) { return f >= 60 ? 0.5 : 0.0; });
  // Two clips, the second starting at the jump: nothing is differenced across it.
  EXPECT_TRUE(marked(jerk_spikes(m, CaptureRuns(kFrames, {59, kFrames - 1}), hand(m))).empty());
  // One clip: the jump is a jolt (third differences +d, -2d, +d at frames 59, 60, 61).
  std::vector<int> expected;
  for (int f = 59 - kSpikeMargin; f <= 61 + kSpikeMargin; ++f) expected.push_back(f);
  EXPECT_EQ(marked(jerk_spikes(m, CaptureRuns(kFrames, {kFrames - 1}), hand(m))), expected);
}

TEST(Spikes, TooShortForAJerk) {
  const Motion m = motion_slice(swinging([](int) { return 0.0; }), 0, 3);
  const std::vector<std::uint8_t> s = jerk_spikes(m, CaptureRuns(3, {2}), hand(m));
  EXPECT_EQ(s, std::vector<std::uint8_t>(3, 0));
}

}  // namespace
}  // namespace gmg
