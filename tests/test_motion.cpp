// Rotations, BVH reading/writing and forward kinematics.
#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "engine/motion/bvh.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/motion/motion.h"
#include "engine/motion/rotation.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Rotation matrices built by hand, independent of the code under test.
Eigen::Matrix3d axis_matrix(int axis, double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d m;
  if (axis == 0) m << 1, 0, 0, 0, c, -s, 0, s, c;
  if (axis == 1) m << c, 0, s, 0, 1, 0, -s, 0, c;
  if (axis == 2) m << c, -s, 0, s, c, 0, 0, 0, 1;
  return m;
}

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
      const Eigen::Matrix3d expected = axis_matrix(order[0], a[0]) * axis_matrix(order[1], a[1]) * axis_matrix(order[2], a[2]);
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
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(angle, Eigen::Vector3d(axis.x, axis.y, axis.z)).toRotationMatrix();
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

// A 3-joint chain: root (6 channels, ZXY), mid (3 channels, XYZ), tip (3 channels, YZX).
const char* kChainBvh =
    "HIERARCHY\r\n"
    "ROOT root\r\n{\r\n\tOFFSET 0 0 0\r\n\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\r\n"
    "\tJOINT mid\r\n\t{\r\n\t\tOFFSET 0 1 0\r\n\t\tCHANNELS 3 Xrotation Yrotation Zrotation\r\n"
    "\t\tJOINT tip\r\n\t\t{\r\n\t\t\tOFFSET 0 0 2\r\n\t\t\tCHANNELS 3 Yrotation Zrotation Xrotation\r\n"
    "\t\t\tEnd Site\r\n\t\t\t{\r\n\t\t\t\tOFFSET 1 0 0\r\n\t\t\t}\r\n\t\t}\r\n\t}\r\n}\r\n"
    "MOTION\r\nFrames: 2\r\nFrame Time: 0.0333333\r\n"
    "1 2 3 10 20 30 40 -50 60 70 80 -90\r\n"
    "0 0 0 0 0 0 90 0 0 0 0 0\r\n";

TEST(Bvh, ParsesAChainWithCrlfAndTabs) {
  const Motion m = bvh_parse(kChainBvh, "chain.bvh");
  ASSERT_EQ(m.joint_count(), 3);
  EXPECT_EQ(m.frame_count, 2);
  EXPECT_DOUBLE_EQ(m.fps, 30.0);
  EXPECT_EQ(m.skeleton.joints[2].parent, 1);
  EXPECT_TRUE(m.skeleton.joints[2].has_end_site);
  EXPECT_EQ(euler_order_to_string(m.skeleton.joints[0].rotation_order), "ZXY");
  EXPECT_EQ(euler_order_to_string(m.skeleton.joints[2].rotation_order), "YZX");
}

TEST(Bvh, ForwardKinematicsMatchesHandComputedChain) {
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

// Channel values of a motion as the file lists them (degrees for rotations).
std::vector<std::vector<double>> channel_values(const std::string& text) {
  std::vector<std::vector<double>> rows;
  const std::size_t motion = text.find("Frame Time:");
  std::size_t pos = text.find('\n', motion) + 1;
  while (pos < text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    std::vector<double> row;
    const char* p = text.data() + pos;
    const char* end = text.data() + eol;
    while (p < end) {
      char* next = nullptr;
      const double v = std::strtod(p, &next);
      if (next == p) break;
      row.push_back(v);
      p = next;
    }
    if (!row.empty()) rows.push_back(row);
    pos = eol + 1;
  }
  return rows;
}

double max_channel_difference(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b) {
  double worst = 0.0;
  for (std::size_t f = 0; f < a.size(); ++f)
    for (std::size_t c = 0; c < a[f].size(); ++c) worst = std::max(worst, std::abs(a[f][c] - b[f][c]));
  return worst;
}

TEST(Bvh, ChainRoundTripReproducesChannels) {
  const Motion m = bvh_parse(kChainBvh, "chain.bvh");
  const std::string written = bvh_format(m);
  const Motion back = bvh_parse(written, "written");
  EXPECT_TRUE(skeletons_match(m.skeleton, back.skeleton));
  const auto a = channel_values(kChainBvh);
  const auto b = channel_values(written);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_LT(max_channel_difference(a, b), 1e-4);
}

class SharedBvh : public ::testing::TestWithParam<std::string> {};

TEST_P(SharedBvh, WriteThenReadReproducesEveryChannel) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string path = gmg::testing::shared_data_dir() + "/" + GetParam();
  const std::string original = read_file_bytes(path);
  const Motion m = bvh_read(path);
  gmg::testing::TempDir dir;
  const std::string out = dir.file("round.bvh");
  bvh_write(out, m);
  const Motion back = bvh_read(out);
  ASSERT_TRUE(skeletons_match(m.skeleton, back.skeleton));
  EXPECT_EQ(back.frame_count, m.frame_count);
  EXPECT_DOUBLE_EQ(back.fps, m.fps);
  const auto a = channel_values(original);
  const auto b = channel_values(bvh_format(back));
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a[0].size(), b[0].size());
  EXPECT_LT(max_channel_difference(a, b), 1e-4) << GetParam();
  // Forward kinematics agree too.
  EXPECT_LT((motion_forward_kinematics(m) - motion_forward_kinematics(back)).cwiseAbs().maxCoeff(), 1e-4);
}

INSTANTIATE_TEST_SUITE_P(AllStyles, SharedBvh,
                         ::testing::Values("beat2_scott/2_scott_0_1_1.bvh", "zeggs/067_Speech_2_x_1_0.bvh",
                                           "genea2023_format/sample1.bvh", "genea2023_format/sample2.bvh"));

TEST(Bvh, ReadsTheThreeSkeletonStyles) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string dir = gmg::testing::shared_data_dir();
  const Motion beat = bvh_read(dir + "/beat2_scott/2_scott_0_1_1.bvh");
  EXPECT_EQ(beat.joint_count(), 55);
  EXPECT_EQ(beat.frame_count, 1906);
  EXPECT_EQ(beat.skeleton.joints[0].name, "pelvis");
  const Motion zeggs = bvh_read(dir + "/zeggs/067_Speech_2_x_1_0.bvh");
  EXPECT_EQ(zeggs.joint_count(), 75);
  EXPECT_EQ(zeggs.frame_count, 2065);
  EXPECT_EQ(euler_order_to_string(zeggs.skeleton.joints[1].rotation_order), "ZYX");
  const Motion genea = bvh_read(dir + "/genea2023_format/sample1.bvh");
  EXPECT_EQ(genea.skeleton.joints[0].name, "body_world");
  EXPECT_EQ(genea.skeleton.joints[1].name, "b_root");
  for (const Joint& j : genea.skeleton.joints) EXPECT_EQ(j.channels.size(), 6u) << j.name;
  EXPECT_DOUBLE_EQ(genea.fps, 30.0);
}

// ---- bad input ----

void expect_bvh_error(const std::string& text, const std::string& fragment) {
  try {
    bvh_parse(text, "bad.bvh");
    ADD_FAILURE() << "no error for: " << fragment;
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.bvh"), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

std::string replace_once(std::string s, const std::string& from, const std::string& to) {
  const std::size_t p = s.find(from);
  EXPECT_NE(p, std::string::npos);
  return s.replace(p, from.size(), to);
}

TEST(BvhErrors, EmptyFile) { expect_bvh_error("", "empty file"); }
TEST(BvhErrors, NotBvh) { expect_bvh_error("hello world", "not a BVH file"); }
TEST(BvhErrors, TruncatedHierarchy) { expect_bvh_error(std::string(kChainBvh).substr(0, 200), "found end of file"); }
TEST(BvhErrors, TruncatedFrames) {
  const std::string t = kChainBvh;
  expect_bvh_error(t.substr(0, t.rfind("0 0 0 0 0 0 90")), "truncated: 'Frames:' declares 2 frames but the file has 1");
}
TEST(BvhErrors, TruncatedMidLineIsAChannelCountError) {
  const std::string t = kChainBvh;
  expect_bvh_error(t.substr(0, t.size() - 8), "line 25: frame has 9 values");
}
TEST(BvhErrors, ChannelCountDisagreesWithData) {
  expect_bvh_error(replace_once(kChainBvh, "CHANNELS 3 Xrotation Yrotation Zrotation", "CHANNELS 2 Xrotation Yrotation"),
                   "hierarchy declares 11 channels");
}
TEST(BvhErrors, NonNumericValue) { expect_bvh_error(replace_once(kChainBvh, " 70 80", " 70 abc"), "line 24: value 11 is not a number"); }
TEST(BvhErrors, NanValue) { expect_bvh_error(replace_once(kChainBvh, " 70 80", " 70 nan"), "not finite"); }
TEST(BvhErrors, InfOffset) { expect_bvh_error(replace_once(kChainBvh, "OFFSET 0 1 0", "OFFSET 0 inf 0"), "line 8: OFFSET y is not finite"); }
TEST(BvhErrors, ZeroFrames) {
  std::string t = kChainBvh;
  t = t.substr(0, t.find("Frames: 2")) + "Frames: 0\r\nFrame Time: 0.0333333\r\n";
  expect_bvh_error(t, "zero frames");
}
TEST(BvhErrors, MoreFramesThanDeclared) { expect_bvh_error(replace_once(kChainBvh, "Frames: 2", "Frames: 1"), "more frame lines"); }
TEST(BvhErrors, UnknownChannel) { expect_bvh_error(replace_once(kChainBvh, "Zrotation Xrotation Yrotation", "Zrotation Qrotation Yrotation"), "unknown channel 'Qrotation'"); }
TEST(BvhErrors, BadFrameTime) { expect_bvh_error(replace_once(kChainBvh, "Frame Time: 0.0333333", "Frame Time: 0"), "Frame Time must be positive"); }
TEST(BvhErrors, DuplicateJoint) { expect_bvh_error(replace_once(kChainBvh, "JOINT tip", "JOINT mid"), "duplicate joint name"); }
TEST(BvhErrors, MissingFileNamesThePath) {
  try {
    bvh_read("/nonexistent/dir/take.bvh");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/take.bvh"), std::string::npos);
  }
}

TEST(Skeleton, MismatchIsExplained) {
  const Motion a = bvh_parse(kChainBvh, "a");
  const Motion b = bvh_parse(replace_once(kChainBvh, "JOINT tip", "JOINT hand"), "b");
  std::string why;
  EXPECT_FALSE(skeletons_match(a.skeleton, b.skeleton, &why));
  EXPECT_NE(why.find("hand"), std::string::npos);
  EXPECT_TRUE(skeletons_match(a.skeleton, a.skeleton));
}

TEST(Motion, WriteRefusesNanAndLeavesNoFile) {
  Motion m = bvh_parse(kChainBvh, "chain.bvh");
  m.rotations[1].x = std::nan("");
  gmg::testing::TempDir dir;
  const std::string out = dir.file("nan.bvh");
  EXPECT_THROW(bvh_write(out, m), Error);
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace gmg
