// Tests of engine/motion/motion_file's motion_convert (`gmg convert`): what is exact in each
// direction between BVH and SMPL-X .npz, with hand-built motions and the shared BEAT2 recording.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/motion/bvh.h"
#include "engine/motion/motion_file.h"
#include "engine/motion/npy.h"
#include "engine/motion/npz.h"
#include "tests/core/helpers.h"
#include "tests/motion/motion_test_util.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using testing::error_of;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A smooth random motion on the SMPL-X skeleton, as gmg writes motions (no Euler hints).
Motion smooth_smplx_motion(int frames, unsigned seed) {
  Motion m = motion_rest(testing::smplx_depth_first(), 30.0, frames);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<glm::dvec3> base(static_cast<std::size_t>(m.joint_count())), speed(base);
  for (std::size_t j = 0; j < base.size(); ++j) {
    base[j] = glm::dvec3(u(rng), u(rng), u(rng)) * 1.2;
    speed[j] = glm::dvec3(u(rng), u(rng), u(rng)) * 0.05;
  }
  for (int f = 0; f < frames; ++f) {
    for (int j = 0; j < m.joint_count(); ++j) {
      const auto k = static_cast<std::size_t>(j);
      m.rotations[m.index(f, j)] = expmap_to_quat(base[k] + speed[k] * static_cast<double>(f));
    }
    m.translations[m.index(f, 0)] = glm::dvec3(0.1 * std::sin(0.1 * f), 1.3 + 0.01 * f, -0.2 * std::cos(0.05 * f));
  }
  return m;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= text.size(); ++i)
    if (i == text.size() || text[i] == '\n') {
      out.push_back(text.substr(start, i - start));
      start = i + 1;
    }
  return out;
}

TEST(Convert, BvhToNpzToBvhGivesTheBvhsBytesBackWithFloat64Arrays) {
  testing::TempDir dir;
  const std::string a = dir.file("a.bvh"), npz = dir.file("a.npz"), b = dir.file("b.bvh");
  bvh_write(a, smooth_smplx_motion(60, 3));
  ConvertOptions o;
  o.floats = NpzFloats::Float64;
  const ConvertSummary s = motion_convert(a, npz, o);
  EXPECT_EQ(s.frames, 60);
  EXPECT_EQ(s.joints, 55);
  EXPECT_EQ(s.fps, 30.0);
  ASSERT_EQ(s.notes.size(), 2u);  // a BVH has no face and no shape
  EXPECT_TRUE(contains(s.notes[0], "has no face: the .npz's expressions are zeros"));
  o.skeleton = a;
  motion_convert(npz, b, o);
  EXPECT_EQ(read_file_bytes(b), read_file_bytes(a));
}

TEST(Convert, BvhToNpzToBvhWithBeat2sFloat32KeepsTheRootAndEveryRotationToFloat32) {
  testing::TempDir dir;
  const std::string a = dir.file("a.bvh"), npz = dir.file("a.npz"), b = dir.file("b.bvh");
  bvh_write(a, smooth_smplx_motion(60, 4));
  motion_convert(a, npz, {});
  ConvertOptions o;
  o.skeleton = a;
  motion_convert(npz, b, o);
  const Motion ma = bvh_read(a), mb = bvh_read(b);
  ASSERT_EQ(ma.frame_count, mb.frame_count);
  for (std::size_t i = 0; i < ma.rotations.size(); ++i)
    EXPECT_LT(rotation_angle_between(ma.rotations[i], mb.rotations[i]), 3e-7) << i;
  // trans is float64 in BEAT2's layout: the root's position channels come back as written.
  const std::vector<std::string> la = lines_of(read_file_bytes(a)), lb = lines_of(read_file_bytes(b));
  ASSERT_EQ(la.size(), lb.size());
  const std::size_t motion_line = std::find(la.begin(), la.end(), "MOTION") - la.begin() + 3;
  for (std::size_t i = motion_line; i + 1 < la.size(); ++i) {
    std::istringstream sa(la[i]), sb(lb[i]);
    std::string xa, xb;
    for (int c = 0; c < 3; ++c) {
      sa >> xa;
      sb >> xb;
      EXPECT_EQ(xa, xb) << "line " << i << " column " << c;
    }
  }
}

TEST(Convert, NpzToBvhToNpzKeepsPosesTransAndFrameRateToTheBvhsDecimals) {
  testing::TempDir dir;
  const std::string templ = dir.file("t.bvh"), npz = dir.file("a.npz"), bvh = dir.file("a.bvh"),
                    back = dir.file("b.npz");
  const Motion m = smooth_smplx_motion(50, 5);
  bvh_write(templ, motion_slice(m, 0, 1));
  SmplxBody body;
  body.betas = {0.25, -1.5, 2.0};
  body.expression_dims = 3;
  for (int i = 0; i < 150; ++i) body.expressions.push_back(0.01 * i);
  npz_write(npz, m, body);
  ConvertOptions o;
  o.skeleton = templ;
  const ConvertSummary s = motion_convert(npz, bvh, o);
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_TRUE(contains(s.notes[0], "a BVH holds no body: the face and shape of " + npz + " are not kept"));
  // Back to .npz with the shape given again (a BVH cannot carry it).
  testing::write_text(dir.file("b.npy"), npy_format("<f8", {3}, body.betas));
  ConvertOptions again;
  again.betas = dir.file("b.npy");
  motion_convert(bvh, back, again);
  SmplxBody back_body;
  const Motion first = npz_read(npz, testing::smplx_depth_first());
  const Motion second = npz_read(back, testing::smplx_depth_first(), &back_body);
  ASSERT_EQ(second.frame_count, first.frame_count);
  EXPECT_EQ(second.fps, first.fps);
  for (std::size_t i = 0; i < first.rotations.size(); ++i)
    EXPECT_LT(rotation_angle_between(first.rotations[i], second.rotations[i]), 1e-6) << i;
  for (int f = 0; f < first.frame_count; ++f)
    EXPECT_LT(glm::length(first.translation(f, 0) - second.translation(f, 0)), 1e-6) << f;
  EXPECT_EQ(back_body.betas, body.betas);
  EXPECT_FALSE(back_body.has_face());
}

TEST(Convert, RefusesToOverwriteItsInputAndNeedsATemplateForAnNpz) {
  testing::TempDir dir;
  const std::string a = dir.file("a.bvh");
  bvh_write(a, smooth_smplx_motion(5, 6));
  EXPECT_TRUE(contains(error_of([&] { motion_convert(a, a, {}); }), "OUT would overwrite the input given as IN"));
  motion_convert(a, dir.file("a.npz"), {});
  EXPECT_TRUE(contains(error_of([&] { motion_convert(dir.file("a.npz"), dir.file("b.bvh"), {}); }),
                       "needs a skeleton template"));
  EXPECT_FALSE(std::filesystem::exists(dir.file("b.bvh")));
}

TEST(Convert, SharedBeat2NpzToBvhGivesTheBeat2BvhAndBackGivesTheNpz) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string dir = testing::shared_data_dir() + "/beat2_scott/";
  testing::TempDir tmp;
  ConvertOptions o;
  o.skeleton = dir + "2_scott_0_1_1.bvh";
  motion_convert(dir + "2_scott_0_1_1.npz", tmp.file("s.bvh"), o);
  // The BVH made from the npz has the shipped BVH's joint positions (its root channels are trans
  // plus the pelvis rest position, as BEAT2's own conversion made them).
  const Motion shipped = bvh_read(dir + "2_scott_0_1_1.bvh"), made = bvh_read(tmp.file("s.bvh"));
  ASSERT_EQ(made.frame_count, shipped.frame_count);
  const Eigen::MatrixXd diff = motion_forward_kinematics(made) - motion_forward_kinematics(shipped);
  EXPECT_LT(diff.cwiseAbs().maxCoeff(), 1e-5);
  // And back: BEAT2's arrays, poses within 1e-6 rad and trans within 1e-6 m of the original.
  ConvertOptions back;
  back.betas = dir + "2_scott_0_1_1.npz";
  motion_convert(tmp.file("s.bvh"), tmp.file("s.npz"), back);
  SmplxBody body, original_body;
  const Motion original = npz_read(dir + "2_scott_0_1_1.npz", shipped.skeleton, &original_body);
  const Motion again = npz_read(tmp.file("s.npz"), shipped.skeleton, &body);
  double worst_angle = 0, worst_root = 0;
  for (std::size_t i = 0; i < original.rotations.size(); ++i)
    worst_angle = std::max(worst_angle, rotation_angle_between(original.rotations[i], again.rotations[i]));
  for (int f = 0; f < original.frame_count; ++f)
    worst_root = std::max(worst_root, glm::length(original.translation(f, 0) - again.translation(f, 0)));
  EXPECT_LT(worst_angle, 1e-6);
  EXPECT_LT(worst_root, 1e-6);
  EXPECT_EQ(body.betas, original_body.betas);
}

TEST(Convert, SharedBvhsComeBackThroughAnNpzAsTheSameRotations) {
  GMG_REQUIRE_SHARED_DATA();
  // A file's own Euler angles (ZEGGS keeps solutions near gimbal lock that are not the continuous
  // choice) come back as the same rotations; position channels of joints other than the root
  // (the GENEA skeleton's) come back as the joints' offsets, and a note says so.
  for (const std::string name : {"zeggs/067_Speech_2_x_1_0.bvh", "genea2023_format/sample1.bvh"}) {
    testing::TempDir dir;
    const std::string original = testing::shared_data_dir() + "/" + name;
    ConvertOptions o;
    o.floats = NpzFloats::Float64;
    const ConvertSummary s = motion_convert(original, dir.file("m.npz"), o);
    const bool genea = name.rfind("genea", 0) == 0;
    EXPECT_EQ(!s.notes.empty() && contains(s.notes[0], "has position channels on joints other than the root"), genea)
        << name;
    o.skeleton = original;
    motion_convert(dir.file("m.npz"), dir.file("m.bvh"), o);
    const Motion a = bvh_read(original), b = bvh_read(dir.file("m.bvh"));
    ASSERT_EQ(a.frame_count, b.frame_count) << name;
    double worst = 0;
    for (std::size_t i = 0; i < a.rotations.size(); ++i)
      worst = std::max(worst, rotation_angle_between(a.rotations[i], b.rotations[i]));
    EXPECT_LT(worst, 1e-6) << name;
    for (int f = 0; f < a.frame_count; ++f) {
      EXPECT_LT(glm::length(a.translation(f, 0) - b.translation(f, 0)), 1e-6) << name << " frame " << f;
      for (int j = 1; j < a.joint_count(); ++j)
        if (genea) {
          EXPECT_EQ(b.translation(f, j), b.skeleton.joints[static_cast<std::size_t>(j)].offset);
        }
    }
  }
}

}  // namespace
}  // namespace gmg
