// Capture facts: the root's largest step and extent and the feet's contacts, worked by hand.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/motion/capture_facts.h"

namespace gmg {
namespace {

// pelvis -> {left_hip -> left_knee -> left_ankle, right_hip -> right_knee -> right_ankle}: legs of
// 0.5 + 0.4 = 0.9 (find_legs), the ankles 0.9 below the pelvis with every rotation identity.
Skeleton two_legs() {
  Skeleton sk;
  auto joint = [&](const char* name, int parent, glm::dvec3 offset) {
    Joint j;
    j.name = name;
    j.parent = parent;
    j.offset = offset;
    j.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
    sk.joints.push_back(j);
  };
  joint("pelvis", -1, glm::dvec3(0.0));
  joint("left_hip", 0, glm::dvec3(0.1, 0, 0));
  joint("left_knee", 1, glm::dvec3(0, -0.5, 0));
  joint("left_ankle", 2, glm::dvec3(0, -0.4, 0));
  joint("right_hip", 0, glm::dvec3(-0.1, 0, 0));
  joint("right_knee", 4, glm::dvec3(0, -0.5, 0));
  joint("right_ankle", 5, glm::dvec3(0, -0.4, 0));
  return sk;
}

// 12 frames at 30 fps in two runs, [0, 5] and [6, 11] (a break at 5). Run A: the pelvis stands at
// x 0, 0, 0, then steps 0.1 twice (x 0.1, 0.2, 0.2). Run B: it stands at x 5 and rises by 0.2 at
// frame 9. Contact needs an ankle speed below 0.15 x 0.9 = 0.135 per second (0.0045 a frame) and a
// height within 0.09 of the run's lowest (every frame of A; frames 6-8 of B):
//   raw contact  1 1 1 0 0 1 | 1 1 1 0 0 0   (frames 3, 4 and 9 move; 10, 11 are too high)
//   gaps under 3 frames filled (3-4; the run boundary does not stop it): 1 x 9, then 0 0 0.
// The left knee is bent by 0.5 rad about x in every frame (sin 0.5 = 0.48 >= 0.3 of a full bend):
// its hinge is the knee plane's normal, -x; the straight right knee has none.
Motion walk() {
  Motion m = motion_rest(two_legs(), 30.0, 12);
  const double x[12] = {0, 0, 0, 0.1, 0.2, 0.2, 5, 5, 5, 5, 5, 5};
  const double y[12] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1.2, 1.2, 1.2};
  for (int f = 0; f < 12; ++f) {
    m.translations[m.index(f, 0)] = glm::dvec3(x[f], y[f], 0.0);
    m.rotations[m.index(f, 2)] = glm::angleAxis(0.5, glm::dvec3(1, 0, 0));
  }
  return m;
}

TEST(CaptureFacts, RootStepAndExtentStayInsideRuns) {
  const CaptureFacts f = capture_facts(walk(), CaptureRuns(12, {5, 11}));
  EXPECT_TRUE(f.known);
  // The 4.8 jump from frame 5 to 6 crosses the break and is not a step; the rise is not horizontal.
  EXPECT_EQ(f.largest_root_step, 0.1);
  EXPECT_EQ(f.root_lo, glm::dvec3(0.0, 1.0, 0.0));
  EXPECT_EQ(f.root_hi, glm::dvec3(5.0, 1.2, 0.0));
}

TEST(CaptureFacts, FeetOnTheGroundAndTheKneesHinge) {
  const CaptureFacts f = capture_facts(walk(), CaptureRuns(12, {5, 11}));
  const std::uint8_t both = foot_contact_bit(0) | foot_low_bit(0) | foot_contact_bit(1) | foot_low_bit(1);
  EXPECT_EQ(both, 15);
  std::vector<std::uint8_t> expected(12, both);
  for (int g = 9; g < 12; ++g) expected[static_cast<std::size_t>(g)] = 0;
  EXPECT_EQ(std::vector<std::uint8_t>(f.foot_flags.begin(), f.foot_flags.end()), expected);
  ASSERT_EQ(f.knee_hinges.size(), 2u);
  EXPECT_NEAR(f.knee_hinges[0].x, -1.0, 1e-15);
  EXPECT_EQ(f.knee_hinges[0].y, 0.0);
  EXPECT_EQ(f.knee_hinges[1], glm::dvec3(0.0));
}

TEST(CaptureFacts, NoLegsNoFlags) {
  Skeleton sk;
  Joint root;
  root.name = "root";
  sk.joints = {root};
  Motion m = motion_rest(sk, 30.0, 3);
  const CaptureFacts f = capture_facts(m, CaptureRuns(3, {2}));
  EXPECT_TRUE(f.known);
  EXPECT_TRUE(f.knee_hinges.empty());
  EXPECT_TRUE(f.foot_flags.empty());
  EXPECT_EQ(f.largest_root_step, 0.0);
}

}  // namespace
}  // namespace gmg
