// The up axis (engine/motion/up_axis.h): a standing synthetic clip and its Z-up copy made by hand
// here (root translation (x, y, z) -> (x, -z, y), root rotation premultiplied by a quarter turn
// about +X), detected, turned both ways, and compared joint by joint in the world.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/motion/motion_file.h"
#include "engine/motion/up_axis.h"
#include "engine/synth/synth.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

Motion standing_clip() {
  SynthSpec spec;
  spec.duration_s = 2.0;
  spec.seed = 3;
  return synth_speaker(spec).motion;
}

// The Z-up copy, built without the code under test: +90 degrees about X takes +Y to +Z.
Motion z_up_copy(const Motion& m) {
  Motion z = m;
  const double h = std::sqrt(0.5);
  const glm::dquat turn(h, h, 0.0, 0.0);  // w, x, y, z
  for (int f = 0; f < z.frame_count; ++f) {
    const std::size_t i = z.index(f, 0);
    const glm::dvec3 t = m.translations[i];
    z.translations[i] = glm::dvec3(t.x, -t.z, t.y);
    z.rotations[i] = turn * m.rotations[i];
  }
  return z;
}

// Rotations compared as rotations (q and -q are the same).
void expect_same_motion(const Motion& a, const Motion& b, double tolerance) {
  ASSERT_EQ(a.frame_count, b.frame_count);
  ASSERT_EQ(a.joint_count(), b.joint_count());
  for (std::size_t i = 0; i < a.rotations.size(); ++i) {
    const glm::dquat p = a.rotations[i], q = b.rotations[i];
    const double sign = glm::dot(p, q) < 0.0 ? -1.0 : 1.0;
    for (int c = 0; c < 4; ++c) ASSERT_NEAR(p[c], sign * q[c], tolerance) << "rotation " << i;
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(a.translations[i][c], b.translations[i][c], tolerance) << "translation " << i;
  }
}

TEST(UpAxis, DetectsYAndZ) {
  const Motion y = standing_clip();
  EXPECT_EQ(detect_up_axis(y), UpAxis::Y);
  EXPECT_EQ(detect_up_axis(z_up_copy(y)), UpAxis::Z);
}

TEST(UpAxis, ArmsOutSidewaysAreNotUp) {
  // With three finger segments the T-pose is wider along X (171 cm) than tall (155 cm): X is never
  // taken for up.
  const Motion rest = motion_rest(synth_skeleton(52), 30.0, 3);
  const Eigen::MatrixXd p = motion_forward_kinematics(rest);
  double x_lo = 1e9, x_hi = -1e9;
  for (int j = 0; j < rest.joint_count(); ++j) {
    x_lo = std::min(x_lo, p(0, 3 * j));
    x_hi = std::max(x_hi, p(0, 3 * j));
  }
  ASSERT_GT(x_hi - x_lo, 155.0);
  EXPECT_EQ(detect_up_axis(rest), UpAxis::Y);
  EXPECT_EQ(detect_up_axis(z_up_copy(rest)), UpAxis::Z);
}

TEST(UpAxis, NoFramesIsY) {
  const Motion empty = motion_rest(synth_skeleton(), 30.0, 0);
  EXPECT_EQ(detect_up_axis(empty), UpAxis::Y);
  EXPECT_EQ(resolve_up_axis(empty, UpChoice::Z), UpAxis::Z);
}

TEST(UpAxis, ResolveTakesAGivenChoice) {
  const Motion y = standing_clip();
  const Motion z = z_up_copy(y);
  EXPECT_EQ(resolve_up_axis(y, UpChoice::Auto), UpAxis::Y);
  EXPECT_EQ(resolve_up_axis(z, UpChoice::Auto), UpAxis::Z);
  EXPECT_EQ(resolve_up_axis(y, UpChoice::Z), UpAxis::Z);
  EXPECT_EQ(resolve_up_axis(z, UpChoice::Y), UpAxis::Y);
}

TEST(UpAxis, ZUpCopyTurnsBackExactly) {
  const Motion y = standing_clip();
  Motion z = z_up_copy(y);
  motion_to_y_up(z, UpAxis::Z);
  expect_same_motion(z, y, 1e-12);
}

TEST(UpAxis, YUpTurnsIntoTheZUpCopy) {
  const Motion y = standing_clip();
  Motion m = y;
  motion_from_y_up(m, UpAxis::Z);
  expect_same_motion(m, z_up_copy(y), 1e-12);
  motion_to_y_up(m, UpAxis::Z);
  expect_same_motion(m, y, 1e-12);
}

TEST(UpAxis, YIsLeftAsItIs) {
  const Motion y = standing_clip();
  Motion m = y;
  motion_to_y_up(m, UpAxis::Y);
  expect_same_motion(m, y, 0.0);
  motion_from_y_up(m, UpAxis::Y);
  expect_same_motion(m, y, 0.0);
}

TEST(UpAxis, WorldPositionsAreTheYUpOnesRotated) {
  const Motion y = standing_clip();
  const Eigen::MatrixXd py = motion_forward_kinematics(y);
  const Eigen::MatrixXd pz = motion_forward_kinematics(z_up_copy(y));
  ASSERT_EQ(py.rows(), pz.rows());
  for (int f = 0; f < py.rows(); ++f)
    for (int j = 0; j < y.joint_count(); ++j) {
      ASSERT_NEAR(pz(f, 3 * j), py(f, 3 * j), 1e-9);
      ASSERT_NEAR(pz(f, 3 * j + 1), -py(f, 3 * j + 2), 1e-9);
      ASSERT_NEAR(pz(f, 3 * j + 2), py(f, 3 * j + 1), 1e-9);
    }
  // Only the root changed.
  const Motion z = z_up_copy(y);
  for (int f = 0; f < y.frame_count; ++f)
    for (int j = 1; j < y.joint_count(); ++j) {
      ASSERT_EQ(z.rotation(f, j), y.rotation(f, j));
      ASSERT_EQ(z.translation(f, j), y.translation(f, j));
    }
}

TEST(UpAxis, RootEulerHintsAreDropped) {
  Motion m = standing_clip();
  m.euler_hints = std::vector<glm::dvec3>(m.rotations.size(), glm::dvec3(0.1, 0.2, 0.3));
  motion_to_y_up(m, UpAxis::Z);
  for (int f = 0; f < m.frame_count; ++f) {
    EXPECT_EQ(m.euler_hints[m.index(f, 0)], glm::dvec3(0.0));
    EXPECT_EQ(m.euler_hints[m.index(f, 1)], glm::dvec3(0.1, 0.2, 0.3));
  }
}

TEST(UpAxis, ReadTurnsAZUpFileIntoYUp) {
  // The Z-up copy written as BVH and read back in Y-up: the joints stand where the Y-up clip's do
  // (to the file's decimal places).
  const Motion y = standing_clip();
  const testing::TempDir dir;
  motion_write(dir.file("z.bvh"), z_up_copy(y));
  motion_write(dir.file("y.bvh"), y);
  const Eigen::MatrixXd expected = motion_forward_kinematics(y);
  for (const char* name : {"z.bvh", "y.bvh"}) {
    const Motion read = motion_read_y_up(dir.file(name));
    const Eigen::MatrixXd p = motion_forward_kinematics(read);
    ASSERT_EQ(p.rows(), expected.rows());
    ASSERT_EQ(p.cols(), expected.cols());
    EXPECT_LT((p - expected).cwiseAbs().maxCoeff(), 1e-3) << name;
  }
}

TEST(UpAxis, VectorsBetweenTheFrames) {
  const glm::dvec3 v(1.0, 2.0, 3.0);
  EXPECT_EQ(to_y_up(v, UpAxis::Z), glm::dvec3(1.0, 3.0, -2.0));
  EXPECT_EQ(from_y_up(v, UpAxis::Z), glm::dvec3(1.0, -3.0, 2.0));
  EXPECT_EQ(to_y_up(v, UpAxis::Y), v);
  EXPECT_EQ(from_y_up(v, UpAxis::Y), v);
  EXPECT_EQ(from_y_up(to_y_up(v, UpAxis::Z), UpAxis::Z), v);
  // Up in Z-up is up in Y-up.
  EXPECT_EQ(to_y_up(glm::dvec3(0.0, 0.0, 1.0), UpAxis::Z), glm::dvec3(0.0, 1.0, 0.0));
}

}  // namespace
}  // namespace gmg
