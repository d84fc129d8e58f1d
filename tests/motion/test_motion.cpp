// Tests of engine/motion/motion: forward kinematics, skeleton comparison.
#include <gtest/gtest.h>
#include <Eigen/Core>

#include <string>

#include "engine/core/math.h"
#include "engine/motion/bvh.h"
#include "engine/motion/motion.h"
#include "tests/core/helpers.h"
#include "tests/motion/motion_test_util.h"

namespace gmg {
namespace {

using testing::axis_matrix;
using testing::kChainBvh;
using testing::replace_once;

TEST(Motion, ForwardKinematicsMatchesHandComputedChain) {
  const Motion m = bvh_parse(kChainBvh, "chain.bvh");
  const Eigen::MatrixXd p = motion_forward_kinematics(m);
  const double d = kPi / 180.0;
  // Frame 0 by hand: world = T(root) * Rz Rx Ry(root) * [T(0,1,0) * Rx Ry Rz(mid) * [T(0,0,2)]]
  const Eigen::Matrix3d r_root = axis_matrix(2, 10 * d) * axis_matrix(0, 20 * d) * axis_matrix(1, 30 * d);
  const Eigen::Matrix3d r_mid = axis_matrix(0, 40 * d) * axis_matrix(1, -50 * d) * axis_matrix(2, 60 * d);
  const Eigen::Vector3d root(1, 2, 3);
  const Eigen::Vector3d mid = root + r_root * Eigen::Vector3d(0, 1, 0);
  const Eigen::Vector3d tip = mid + r_root * r_mid * Eigen::Vector3d(0, 0, 2);
  EXPECT_LT((p.block<1, 3>(0, 0).transpose() - root).norm(), 1e-9);
  EXPECT_LT((p.block<1, 3>(0, 3).transpose() - mid).norm(), 1e-9);
  EXPECT_LT((p.block<1, 3>(0, 6).transpose() - tip).norm(), 1e-9);
  // Frame 1: mid rotated 90 degrees about X, so the tip offset (0,0,2) points along -Y.
  EXPECT_LT((p.block<1, 3>(1, 6).transpose() - Eigen::Vector3d(0, 1, 0) - Eigen::Vector3d(0, -2, 0)).norm(), 1e-9);
}

TEST(Skeleton, MismatchIsExplained) {
  const Motion a = bvh_parse(kChainBvh, "a");
  const Motion b = bvh_parse(replace_once(kChainBvh, "JOINT tip", "JOINT hand"), "b");
  std::string why;
  EXPECT_FALSE(skeletons_match(a.skeleton, b.skeleton, &why));
  EXPECT_NE(why.find("hand"), std::string::npos);
  EXPECT_TRUE(skeletons_match(a.skeleton, a.skeleton));
}

}  // namespace
}  // namespace gmg
