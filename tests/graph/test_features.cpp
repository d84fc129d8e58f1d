// Pose features and the pose distance, on hand-worked values.
#include <cmath>

#include <gtest/gtest.h>

#include "graph/features.h"
#include "tests/graph/fixtures.h"

namespace gmg {
namespace {

using namespace gmg::testing;

TEST(Features, PoseDistanceWeighsPositionAndVelocity) {
  PoseFeatures f;
  f.positions = Eigen::MatrixXd::Zero(6, 2);
  f.velocities = Eigen::MatrixXd::Zero(6, 2);
  f.positions.col(0) << 0, 0, 0, 3, 4, 0;   // joint 1 at (3, 4, 0): 5 away from frame 1's origin
  f.velocities.col(1) << 0, 0, 0, 1, 2, 2;  // velocity difference of length 3
  GraphParams p;
  EXPECT_DOUBLE_EQ(pose_distance(f, 0, 1, p), 5.0 + 3.0);
  p.lambda_pos = 2.0;
  p.lambda_vel = 0.5;
  EXPECT_DOUBLE_EQ(pose_distance(f, 0, 1, p), 2.0 * 5.0 + 0.5 * 3.0);
  EXPECT_DOUBLE_EQ(pose_distance(f, 1, 0, p), pose_distance(f, 0, 1, p));
  EXPECT_DOUBLE_EQ(pose_distance(f, 1, 1, p), 0.0);
}

TEST(Features, HandOfATurningRoot) {
  // The root turns about Z by 0 then pi/2: the hand (offset (0, 1, 0)) goes from (0, 1, 0) to
  // (-1, 0, 0); its velocity at frame 1 is (-1, -1, 0), and v_0 = v_1.
  const PoseFeatures f = pose_features(line_motion({0.0, 1.5707963267948966}));
  ASSERT_EQ(f.positions.rows(), 6);
  ASSERT_EQ(f.frame_count(), 2);
  EXPECT_NEAR(f.positions(3, 0), 0.0, 1e-12);
  EXPECT_NEAR(f.positions(4, 0), 1.0, 1e-12);
  EXPECT_NEAR(f.positions(3, 1), -1.0, 1e-12);
  EXPECT_NEAR(f.positions(4, 1), 0.0, 1e-12);
  for (int c = 0; c < 2; ++c) {
    EXPECT_NEAR(f.velocities(3, c), -1.0, 1e-12);
    EXPECT_NEAR(f.velocities(4, c), -1.0, 1e-12);
    EXPECT_EQ(f.positions.col(c).head(3).norm(), 0.0);  // the root's own rows
  }
}

// SPEC: features are root-relative, so where the speaker stands does not change a distance.
TEST(Features, IgnoreWhereTheSpeakerStands) {
  const Motion m = line_motion({0.0, 0.3, 0.6, 0.9});
  Motion moved = m;
  for (int f = 0; f < moved.frame_count; ++f) moved.translations[moved.index(f, 0)] += glm::dvec3(50.0 * f, -20.0, 7.0);
  const PoseFeatures a = pose_features(m), b = pose_features(moved);
  EXPECT_LT((a.positions - b.positions).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((a.velocities - b.velocities).cwiseAbs().maxCoeff(), 1e-12);
  GraphParams p;
  EXPECT_NEAR(pose_distance(a, 1, b, 1, p), 0.0, 1e-12);
}

}  // namespace
}  // namespace gmg
