// Joining the body's layers (engine/assemble/layers.h) on the synthetic speaker's skeleton: two
// motions whose every joint differs, the lower one's pelvis tilted and turned by known angles.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/assemble/layers.h"
#include "engine/core/error.h"
#include "engine/synth/synth.h"

namespace gmg {
namespace {

constexpr int kFrames = 40;

glm::dquat about(double angle, glm::dvec3 axis) { return glm::angleAxis(angle, glm::normalize(axis)); }

// Every joint turned by its own small angle (different per motion and frame), the root placed at `root`.
Motion posed(double seed, glm::dvec3 root, glm::dquat pelvis) {
  Motion m = motion_rest(synth_skeleton(), 30.0, kFrames);
  for (int f = 0; f < kFrames; ++f) {
    for (int j = 1; j < m.joint_count(); ++j)
      m.rotations[m.index(f, j)] = about(0.05 * seed + 0.01 * j + 0.002 * f, glm::dvec3(1.0, seed, 0.5 * j));
    m.rotations[m.index(f, 0)] = pelvis;
    m.translations[m.index(f, 0)] = root + glm::dvec3(0.1 * f, 0.0, 0.0);
  }
  return m;
}

glm::dquat world(const Motion& m, int f, int j) {
  glm::dquat q(1.0, 0.0, 0.0, 0.0);
  for (int k = j; k >= 0; k = m.skeleton.joints[static_cast<std::size_t>(k)].parent) q = m.rotation(f, k) * q;
  return q;
}

void expect_rotation(const glm::dquat& a, const glm::dquat& b, double tolerance) {
  const double sign = glm::dot(a, b) < 0.0 ? -1.0 : 1.0;
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(a[c], sign * b[c], tolerance);
}

struct Pair {
  Motion upper, lower;
  BodyLayers layers;
};

Pair make_pair(glm::dquat lower_pelvis) {
  Pair p;
  p.upper = posed(1.0, {0.0, 95.0, 0.0}, about(0.1, {1, 0, 0}));
  p.lower = posed(2.0, {5.0, 92.0, -3.0}, lower_pelvis);
  p.layers = find_body_layers(motion_rest(p.upper.skeleton, 30.0, 1));
  return p;
}

TEST(JoinLayers, LowerJointsFromTheLowerMotionUpperFromTheUpper) {
  const Pair p = make_pair(about(-0.15, {0, 0, 1}));
  ASSERT_TRUE(p.layers.layered());
  for (double follow : {0.0, 1.0}) {
    const Motion out = join_layers(p.upper, p.lower, p.layers, follow);
    ASSERT_EQ(out.frame_count, kFrames);
    const int spine = p.layers.spine.front();
    for (int f = 0; f < kFrames; ++f)
      for (int j = 0; j < out.joint_count(); ++j) {
        const bool lower = p.layers.lower[static_cast<std::size_t>(j)];
        const Motion& from = lower ? p.lower : p.upper;
        EXPECT_EQ(out.translation(f, j), from.translation(f, j)) << f << " " << j;
        if (j == spine && follow > 0.0) continue;  // the spine takes up the pelvis difference
        EXPECT_EQ(out.rotation(f, j), from.rotation(f, j)) << f << " " << j;
      }
  }
}

TEST(JoinLayers, FollowZeroRidesOnTheLowerPelvis) {
  const Pair p = make_pair(about(-0.15, {0, 0, 1}));
  const Motion out = join_layers(p.upper, p.lower, p.layers, 0.0);
  const int spine = p.layers.spine.front();
  for (int f = 0; f < kFrames; ++f) {
    EXPECT_EQ(out.rotation(f, spine), p.upper.rotation(f, spine));
    // The chest's world rotation: the lower pelvis times the upper layer's own spine.
    expect_rotation(world(out, f, spine), p.lower.rotation(f, 0) * p.upper.rotation(f, spine), 1e-12);
  }
}

TEST(JoinLayers, FollowOneKeepsTheUpperChestPosture) {
  // Both pelvises face +Z (tilts about X and Z have no heading): the chest and everything above it
  // turn exactly as in the upper motion.
  const Pair p = make_pair(about(-0.15, {0, 0, 1}));
  const Motion out = join_layers(p.upper, p.lower, p.layers, 1.0);
  for (int f = 0; f < kFrames; ++f)
    for (int j = 0; j < out.joint_count(); ++j)
      if (!p.layers.lower[static_cast<std::size_t>(j)]) expect_rotation(world(out, f, j), world(p.upper, f, j), 1e-12);
}

TEST(JoinLayers, FollowOneTurnsTheChestToTheLowerHeading) {
  // The lower pelvis turned 0.4 rad about +Y (and tilted): the chest keeps the upper posture,
  // turned by the same 0.4 rad to face where the legs face.
  const glm::dquat turn = about(0.4, {0, 1, 0});
  const Pair p = make_pair(turn * about(0.12, {1, 0, 0}));
  const Motion out = join_layers(p.upper, p.lower, p.layers, 1.0);
  for (int f = 0; f < kFrames; ++f)
    for (int j : p.layers.spine) expect_rotation(world(out, f, j), turn * world(p.upper, f, j), 1e-12);
}

TEST(JoinLayers, HeadingIsTheTwistAboutUp) {
  const glm::dquat h = heading_of(about(0.7, {0, 1, 0}) * about(0.3, {1, 0, 0}));
  expect_rotation(h, about(0.7, {0, 1, 0}), 1e-15);
  expect_rotation(heading_of(about(0.3, {0, 0, 1})), glm::dquat(1.0, 0.0, 0.0, 0.0), 1e-15);
  // A half turn about a horizontal axis has no heading.
  expect_rotation(heading_of(glm::dquat(0.0, 1.0, 0.0, 0.0)), glm::dquat(1.0, 0.0, 0.0, 0.0), 0.0);
}

TEST(JoinLayers, WithoutLayersTheUpperMotion) {
  const Pair p = make_pair(about(-0.15, {0, 0, 1}));
  const Motion out = join_layers(p.upper, p.lower, BodyLayers{}, 1.0);
  for (std::size_t i = 0; i < out.rotations.size(); ++i) {
    ASSERT_EQ(out.rotations[i], p.upper.rotations[i]);
    ASSERT_EQ(out.translations[i], p.upper.translations[i]);
  }
}

TEST(JoinLayers, MismatchedMotionsThrow) {
  const Pair p = make_pair(about(-0.15, {0, 0, 1}));
  EXPECT_THROW(join_layers(p.upper, motion_slice(p.lower, 0, kFrames - 1), p.layers, 1.0), Error);
}

}  // namespace
}  // namespace gmg
