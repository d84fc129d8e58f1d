// Tests of engine/motion/rotation: Euler angles, quaternions, exponential map, slerp.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "engine/core/error.h"
#include "engine/core/math.h"
#include "engine/motion/rotation.h"
#include "tests/motion/motion_test_util.h"

namespace gmg {
namespace {

using testing::axis_matrix;

Eigen::Matrix3d quat_matrix(const glm::dquat& q) {
  const glm::dmat3 g = glm::mat3_cast(q);
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = g[c][r];
  return m;
}

// Distance between unit quaternions up to sign (q and -q are one rotation); precise near 0,
// unlike an acos of the dot product.
double same_rotation_error(const glm::dquat& a, const glm::dquat& b) {
  return std::min(glm::length(a - b), glm::length(a + b));
}

const std::vector<std::string> kOrders = {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"};

TEST(Rotation, EulerToQuatMatchesHandBuiltMatrices) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (const std::string& name : kOrders) {
    const EulerOrder order = euler_order_from_string(name);
    for (int trial = 0; trial < 50; ++trial) {
      const glm::dvec3 a(angle(rng), angle(rng), angle(rng));
      const Eigen::Matrix3d expected =
          axis_matrix(order[0], a[0]) * axis_matrix(order[1], a[1]) * axis_matrix(order[2], a[2]);
      EXPECT_LT((quat_matrix(euler_to_quat(a, order)) - expected).cwiseAbs().maxCoeff(), 1e-12) << name;
    }
  }
}

TEST(Rotation, EulerRoundTripAllOrders) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  std::uniform_real_distribution<double> middle(-kPi / 2 + 1e-3, kPi / 2 - 1e-3);
  for (const std::string& name : kOrders) {
    const EulerOrder order = euler_order_from_string(name);
    for (int trial = 0; trial < 200; ++trial) {
      const glm::dvec3 a(angle(rng), middle(rng), angle(rng));
      const glm::dvec3 back = quat_to_euler(euler_to_quat(a, order), order);
      EXPECT_NEAR(back.x, a.x, 1e-9) << name;
      EXPECT_NEAR(back.y, a.y, 1e-9) << name;
      EXPECT_NEAR(back.z, a.z, 1e-9) << name;
    }
  }
}

TEST(Rotation, EulerGimbalLockStillGivesTheSameRotation) {
  for (const std::string& name : kOrders) {
    const EulerOrder order = euler_order_from_string(name);
    for (double mid : {kPi / 2, -kPi / 2}) {
      const glm::dquat q = euler_to_quat(glm::dvec3(0.3, mid, -0.7), order);
      EXPECT_LT(same_rotation_error(euler_to_quat(quat_to_euler(q, order), order), q), 1e-6) << name;
    }
  }
}

TEST(Rotation, EulerNearPreviousKeepsTheSolutionBranch) {
  const EulerOrder order = euler_order_from_string("ZXY");
  // The middle angle sweeps past 90 degrees: quat_to_euler would switch to the other branch
  // (a + 180, 180 - b, c + 180); the near version keeps following the sweep.
  glm::dvec3 previous(0.2, 0.0, 0.3);
  for (int step = 0; step <= 250; ++step) {
    const double b = step * 0.01;
    const glm::dvec3 e = quat_to_euler_near(euler_to_quat(glm::dvec3(0.2, b, 0.3), order), order, previous);
    EXPECT_NEAR(e.x, 0.2, 1e-7);
    EXPECT_NEAR(e.y, b, 1e-7);
    EXPECT_NEAR(e.z, 0.3, 1e-7);
    previous = e;
  }
}

TEST(Rotation, RandomQuaternionsRoundTripThroughEverything) {
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    const glm::dquat q = glm::normalize(glm::dquat(n(rng), n(rng), n(rng), n(rng)));
    EXPECT_LT(same_rotation_error(expmap_to_quat(quat_to_expmap(q)), q), 1e-9);
    for (const std::string& name : kOrders) {
      const EulerOrder order = euler_order_from_string(name);
      EXPECT_LT(same_rotation_error(euler_to_quat(quat_to_euler(q, order), order), q), 1e-7);
    }
  }
}

TEST(Rotation, ExpMapNearZeroAndNear180) {
  for (double angle : {0.0, 1e-12, 1e-9, 1e-6, 1e-3, kPi - 1e-3, kPi - 1e-9, kPi}) {
    const glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    const glm::dvec3 v = axis * angle;
    const glm::dquat q = expmap_to_quat(v);
    EXPECT_NEAR(glm::length(q), 1.0, 1e-12);
    const Eigen::Matrix3d expected =
        Eigen::AngleAxisd(angle, Eigen::Vector3d(axis.x, axis.y, axis.z)).toRotationMatrix();
    EXPECT_LT((quat_matrix(q) - expected).cwiseAbs().maxCoeff(), 1e-12) << angle;
    const glm::dvec3 back = quat_to_expmap(q);
    EXPECT_LT(same_rotation_error(expmap_to_quat(back), q), 1e-9) << angle;
    if (angle < kPi - 1e-6) {
      EXPECT_NEAR(glm::length(back - v), 0.0, 1e-9) << angle;
    }
  }
}

TEST(Rotation, SlerpTakesTheShortArc) {
  const glm::dquat a = glm::angleAxis(0.1, glm::dvec3(0, 0, 1));
  const glm::dquat b = -glm::angleAxis(0.5, glm::dvec3(0, 0, 1));  // same rotation as +, far in 4D
  const glm::dquat mid = slerp_shortest(a, b, 0.5);
  EXPECT_NEAR(rotation_angle_between(mid, glm::angleAxis(0.3, glm::dvec3(0, 0, 1))), 0.0, 1e-9);
  EXPECT_LT(rotation_angle_between(slerp_shortest(a, b, 0.0), a), 1e-7);
  EXPECT_LT(rotation_angle_between(slerp_shortest(a, b, 1.0), b), 1e-7);
}

TEST(Rotation, BadOrderIsRejected) {
  EXPECT_THROW(euler_order_from_string("XXY"), Error);
  EXPECT_THROW(euler_order_from_string("XY"), Error);
}

// The angle of a rotation, exact for the small angles of a jaw (acos of the real part keeps only
// about 1e-8 rad there), the same for q and -q, pi for a half turn.
TEST(Rotation, AngleOfARotationSmallOrLarge) {
  const glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, -1.0, 0.2));
  for (double a : {0.0, 1e-9, 0.0123, 1.0, 3.0})
    EXPECT_NEAR(rotation_angle(glm::angleAxis(a, axis)), a, 1e-15 + 1e-15 * a) << a;
  EXPECT_NEAR(rotation_angle(-glm::angleAxis(0.0123, axis)), 0.0123, 1e-15);
  EXPECT_DOUBLE_EQ(rotation_angle(glm::dquat(0.0, 1.0, 0.0, 0.0)), kPi);
}

}  // namespace
}  // namespace gmg
