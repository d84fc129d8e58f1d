// Tests of engine/motion/motion: forward kinematics, skeleton comparison.
#include <gtest/gtest.h>
#include <Eigen/Core>

#include <cstring>
#include <memory>
#include <string>

#include "engine/core/files.h"
#include "engine/core/math.h"
#include "engine/motion/bvh.h"
#include "engine/motion/motion.h"
#include "tests/core/helpers.h"
#include "tests/motion/motion_test_util.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using testing::axis_matrix;
using testing::kChainBvh;
using testing::present_pages;
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
// A motion served from a file gives its pages back after a reader's stretch only when it is long:
// a short one keeps them (motion_release_pages).
TEST(Motion, OnlyALongServedMotionGivesItsPagesBack) {
  gmg::testing::TempDir dir;
  for (const std::size_t frames : {std::size_t{2000}, kKeepMotionPagesBelow / (56 * 10) + 2000}) {
    const std::size_t joints = 10, values = frames * joints;
    // A file of rotations then translations (unit quaternions, zero translations), mapped.
    std::string bytes(values * (sizeof(glm::dquat) + sizeof(glm::dvec3)), '\0');
    const glm::dquat unit(1, 0, 0, 0);
    for (std::size_t i = 0; i < values; ++i) std::memcpy(&bytes[i * sizeof unit], &unit, sizeof unit);
    gmg::testing::write_text(dir.file("m.bin"), bytes);
    auto file = std::make_shared<const MappedFile>(dir.file("m.bin"));
    Motion m;
    m.skeleton.joints.resize(joints);
    m.frame_count = static_cast<int>(frames);
    const auto* q = reinterpret_cast<const glm::dquat*>(file->data());
    m.rotations = Samples<glm::dquat>::view(q, values, file);
    m.translations = Samples<glm::dvec3>::view(reinterpret_cast<const glm::dvec3*>(q + values), values, file);
    const Motion& served = m;  // read, not changed (a change would copy the samples)
    double sum = 0.0;
    for (std::size_t i = 0; i < values; i += 64) sum += served.rotations[i].w + served.translations[i].x;
    EXPECT_EQ(sum, static_cast<double>((values + 63) / 64));
    const std::size_t read = present_pages(file->data(), file->size());
    ASSERT_GT(read, 0u);
    motion_release_pages(served);
    ASSERT_TRUE(served.rotations.is_view());
    const bool long_motion = bytes.size() >= kKeepMotionPagesBelow;
    if (long_motion) {
      EXPECT_LE(present_pages(file->data(), file->size()), 2u) << frames << " frames";
    } else {
      EXPECT_EQ(present_pages(file->data(), file->size()), read) << frames << " frames";
    }
  }
}

}  // namespace gmg
