// Inertialized transitions, the root anchor and foot locking, on motions with known answers.
#include <cmath>

#include <gtest/gtest.h>

#include "engine/assemble/foot_lock.h"
#include "engine/assemble/inertialize.h"
#include "engine/assemble/transitions.h"
#include "tests/assemble/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

// Source: frames 0..99 turn the arm from 0 at 0.02 rad/frame; frames 100..199 do the same from
// 1.5 rad, so a jump from frame 40 to frame 140 turns the arm by 1.5 rad at the same speed.
Motion two_takes() {
  std::vector<double> a;
  a.reserve(200);
  for (int f = 0; f < 200; ++f) a.push_back((f < 100 ? 0.0 : 1.5) + 0.02 * (f % 100));
  return arm_motion(a);
}

std::vector<char> continues_except(int frames, const std::vector<int>& breaks) {
  std::vector<char> c(static_cast<std::size_t>(frames), 1);
  for (int b : breaks) c[static_cast<std::size_t>(b)] = 0;
  return c;
}

PathPiece run(int first, int length) {
  PathPiece p;
  for (int f = first; f < first + length; ++f) p.path.push_back(f);
  p.length = length;
  return p;
}

BlendParams inertialize_only() {
  BlendParams p;
  p.mode = BlendMode::Inertialize;
  p.foot_lock = false;
  return p;
}

TEST(Transitions, ContinuousJunctionIsUntouched) {
  const Motion src = two_takes();
  const Motion out =
      assemble_inertialized(src, continues_except(200, {99, 199}), {run(0, 40), run(40, 40)}, inertialize_only());
  ASSERT_EQ(out.frame_count, 80);
  for (int f = 0; f < 80; ++f)
    for (int j = 0; j < 3; ++j) EXPECT_LT(rotation_angle_between(out.rotation(f, j), src.rotation(f, j)), 1e-12);
}

TEST(Transitions, PositionAndVelocityStayContinuousAndTheOffsetDecays) {
  const Motion src = two_takes();
  const BlendParams params = inertialize_only();
  const Motion out = assemble_inertialized(src, continues_except(200, {99, 199}), {run(0, 40), run(140, 60)}, params);
  const Eigen::MatrixXd hand = motion_forward_kinematics(out).rightCols(3);
  // A hard cut would jump by the chord of 1.5 rad on the 30 cm arm: 2 * 30 * sin(0.75) = 40.9 cm in
  // one frame. The spring spreads it: an offset x0 starting at rest, x0 (1 + y t) e^(-y t), moves at
  // most x0 y / e per frame and its second difference is at most x0 y^2 (at the switch).
  const double jump = 60.0 * std::sin(0.75);
  const double natural_step = 60.0 * std::sin(0.01);  // 0.6 cm per frame
  const double natural_second = 30.0 * 0.02 * 0.02;   // centripetal, 0.012 cm per frame^2
  const double y = spring_damping(params.halflife_s * 30.0);
  double largest_step = 0.0;
  for (int f = 1; f < 100; ++f) {
    const double step = (hand.row(f) - hand.row(f - 1)).norm();
    largest_step = std::max(largest_step, step);
    EXPECT_LT(step, natural_step + 1.1 * jump * y / std::exp(1.0)) << f;  // no pop
    if (f >= 2) {
      const double second = (hand.row(f) - 2 * hand.row(f - 1) + hand.row(f - 2)).norm();
      EXPECT_LT(second, natural_second + 1.1 * jump * y * y) << f;  // velocity continuous: no whip
    }
  }
  EXPECT_LT(largest_step, 0.15 * jump);
  // Where the output was heading at the junction: the arm keeps turning at 0.02 rad/frame.
  EXPECT_NEAR(glm::angle(out.rotation(40, 1)), 0.80, 1e-9);
  // Documented settling: under 1 % of the 1.5 rad offset after spring_settle_frames (the two takes
  // move at the same speed, so the offset starts at rest).
  const int settled = 40 + static_cast<int>(std::ceil(spring_settle_frames(y, 0.01)));
  ASSERT_LT(settled, 100);
  EXPECT_NEAR(spring_settle_frames(y, 0.01) / (params.halflife_s * 30.0), 4.79, 0.01);
  for (int f = settled; f < 100; ++f) {
    const double offset = rotation_angle_between(out.rotation(f, 1), src.rotation(100 + f, 1));
    EXPECT_LT(offset, 0.01 * 1.5) << f;
  }
  EXPECT_GT(rotation_angle_between(out.rotation(settled - 10, 1), src.rotation(90 + settled, 1)), 0.01 * 1.5);
}

TEST(Transitions, RootWalkingALineNeverStepsFurtherThanItsCapture) {
  // The root walks 2 cm per frame along x; pieces from far apart places of the walk.
  Motion src = arm_motion(std::vector<double>(200, 0.3));
  for (int f = 0; f < 200; ++f) src.translations[src.index(f, 0)] = glm::dvec3(2.0 * f, 90.0, 0.0);
  const std::vector<PathPiece> pieces = {run(0, 50), run(150, 50), run(20, 50), run(120, 30)};
  BlendParams params = inertialize_only();
  const Motion anchored = assemble_inertialized(src, continues_except(200, {199}), pieces, params);
  double largest = 0.0;
  for (int f = 1; f < anchored.frame_count; ++f)
    largest = std::max(largest, glm::length(anchored.translation(f, 0) - anchored.translation(f - 1, 0)));
  EXPECT_LE(largest, 2.0 + 1e-9);
  // The landed behaviour (a free root) teleports the speaker: the anchor is what prevents it.
  params.root = RootMode::Free;
  const Motion free = assemble_inertialized(src, continues_except(200, {199}), pieces, params);
  double free_largest = 0.0;
  for (int f = 1; f < free.frame_count; ++f)
    free_largest = std::max(free_largest, glm::length(free.translation(f, 0) - free.translation(f - 1, 0)));
  EXPECT_GT(free_largest, 10.0);
}

// A standing pair of legs: hips at y = 90, knees bent a little, feet on the ground (y = 0).
Motion standing(int frames) {
  Skeleton sk;
  auto joint = [&](const char* name, int parent, glm::dvec3 offset) {
    Joint j;
    j.name = name;
    j.parent = parent;
    j.offset = offset;
    j.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
    sk.joints.push_back(j);
  };
  joint("Hips", -1, glm::dvec3(0, 90, 0));
  sk.joints[0].channels.insert(sk.joints[0].channels.begin(),
                               {Channel::Xposition, Channel::Yposition, Channel::Zposition});
  joint("LeftUpLeg", 0, glm::dvec3(10, 0, 0));
  joint("LeftLeg", 1, glm::dvec3(0, -45, 2));
  joint("LeftFoot", 2, glm::dvec3(0, -45, -2));
  joint("RightUpLeg", 0, glm::dvec3(-10, 0, 0));
  joint("RightLeg", 4, glm::dvec3(0, -45, 2));
  joint("RightFoot", 5, glm::dvec3(0, -45, -2));
  return motion_rest(sk, 30.0, frames);
}

TEST(Transitions, PlantedFeetStayWhereTheyAre) {
  // Two stances, both standing still: frames 100..199 have the left leg swung out 0.15 rad.
  Motion src = standing(200);
  for (int f = 100; f < 200; ++f) src.rotations[src.index(f, 1)] = glm::angleAxis(0.15, glm::dvec3(0, 0, 1));
  const std::vector<Leg> legs = find_legs(src.skeleton);
  ASSERT_EQ(legs.size(), 2u);
  EXPECT_EQ(src.skeleton.joints[static_cast<std::size_t>(legs[0].ankle)].name, "LeftFoot");
  EXPECT_NEAR(legs[0].length, 2.0 * std::sqrt(45.0 * 45.0 + 4.0), 1e-9);
  BlendParams params = inertialize_only();
  params.foot_lock = true;
  const std::vector<PathPiece> pieces = {run(0, 50), run(150, 50)};
  const Motion out = assemble_inertialized(src, continues_except(200, {99, 199}), pieces, params);
  const Eigen::MatrixXd p = motion_forward_kinematics(out);
  const Eigen::Index left = legs[0].ankle;
  for (int f = 1; f < 100; ++f) EXPECT_LT((p.block<1, 3>(f, 3 * left) - p.block<1, 3>(0, 3 * left)).norm(), 1e-6) << f;
  // Without the lock the left foot glides to the second stance.
  params.foot_lock = false;
  const Eigen::MatrixXd q =
      motion_forward_kinematics(assemble_inertialized(src, continues_except(200, {99, 199}), pieces, params));
  EXPECT_GT((q.block<1, 3>(99, 3 * left) - q.block<1, 3>(0, 3 * left)).norm(), 5.0);
}

// A foot the leg can no longer reach (the second stance stands 40 cm to the side and the root is
// free to follow it, gliding there over a second) is not dragged along the floor: it steps, off the
// floor and down again (touching down on a foot that moves with the body costs a frame or two of
// each step), and ends where the new stance has it.
TEST(Transitions, AFootThatMustMoveStepsInsteadOfSliding) {
  Motion src = standing(200);
  for (int f = 100; f < 200; ++f) src.translations[src.index(f, 0)] = glm::dvec3(40, 90, 0);
  const std::vector<Leg> legs = find_legs(src.skeleton);
  BlendParams params = inertialize_only();
  params.foot_lock = true;
  params.root = RootMode::Free;
  const std::vector<PathPiece> pieces = {run(0, 50), run(150, 50)};
  const Motion out = assemble_inertialized(src, continues_except(200, {99, 199}), pieces, params);
  const Eigen::MatrixXd p = motion_forward_kinematics(out);
  const Eigen::MatrixXd source = motion_forward_kinematics(src);
  for (const Leg& leg : legs) {
    const Eigen::Index a = 3 * leg.ankle;
    double highest = 0.0;
    int sliding = 0;
    for (int f = 1; f < 100; ++f) {
      highest = std::max(highest, p(f, a + 1));
      const double horizontal = std::hypot(p(f, a) - p(f - 1, a), p(f, a + 2) - p(f - 1, a + 2)) * 30.0;
      sliding += p(f, a + 1) < 1.0 && horizontal > 10.0;
    }
    EXPECT_LE(sliding, 4) << "frames with the foot on the floor moving faster than 10 cm/s";
    EXPECT_GT(highest, 5.0) << "the foot is lifted on its way";
    // It is planted again on the floor, most of the 40 cm over (where it touched down: the leg
    // reaches the rest of the way).
    EXPECT_NEAR(p(99, a + 1), 0.0, 1.0);
    EXPECT_LT(std::abs(p(99, a) - source(150, a)), 10.0);
    EXPECT_NEAR(p(99, a + 2), source(150, a + 2), 1.0);
  }
}

}  // namespace
}  // namespace gmg
