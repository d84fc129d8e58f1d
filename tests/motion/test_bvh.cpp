// Tests of engine/motion/bvh (bvh_read.cpp, bvh_write.cpp): parsing, writing, round trips,
// errors with file and line.
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/motion/bvh.h"
#include "engine/motion/motion.h"
#include "engine/motion/rotation.h"
#include "tests/core/helpers.h"
#include "tests/motion/motion_test_util.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using testing::error_of;
using testing::kChainBvh;
using testing::replace_once;

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

TEST(Bvh, Utf8BomIsSkipped) {
  const Motion m = bvh_parse("\xEF\xBB\xBF" + std::string(kChainBvh), "bom.bvh");
  EXPECT_EQ(m.joint_count(), 3);
  EXPECT_EQ(m.frame_count, 2);
}

TEST(Bvh, JointNamesAreTrimmedAndChannelNamesCaseInsensitive) {
  const std::string text =
      replace_once(replace_once(kChainBvh, "JOINT mid\r\n", "JOINT  left arm \t\r\n"),
                   "CHANNELS 3 Yrotation Zrotation Xrotation", "CHANNELS 3 YROTATION zRotation xrotation");
  const Motion m = bvh_parse(text, "names.bvh");
  EXPECT_EQ(m.skeleton.joints[1].name, "left arm");
  ASSERT_EQ(m.skeleton.joints[2].channels.size(), 3u);
  EXPECT_EQ(m.skeleton.joints[2].channels[0], Channel::Yrotation);
  EXPECT_EQ(m.skeleton.joints[2].channels[1], Channel::Zrotation);
  EXPECT_EQ(m.skeleton.joints[2].channels[2], Channel::Xrotation);
}

TEST(Bvh, FormatWritesTheCanonicalTextBack) {
  // Written the way bvh_format writes (tabs, 6 decimals, Frame Time with 8): a file read with its
  // Euler angles comes back byte for byte, including 180-degree and negative angles.
  const std::string text =
      "HIERARCHY\n"
      "ROOT hips\n{\n\tOFFSET 0.000000 90.000000 0.000000\n"
      "\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
      "\tJOINT head\n\t{\n\t\tOFFSET 0.000000 10.500000 -1.250000\n\t\tCHANNELS 3 Zrotation Xrotation Yrotation\n"
      "\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0.000000 5.000000 0.000000\n\t\t}\n\t}\n}\n"
      "MOTION\nFrames: 2\nFrame Time: 0.03333333\n"
      "1.500000 90.000000 -2.000000 0.000000 0.000000 0.000000 90.000000 -45.000000 10.000000\n"
      "1.500000 90.250000 -2.000000 180.000000 0.000000 0.000000 0.000000 0.000000 -30.000000\n";
  EXPECT_EQ(bvh_format(bvh_parse(text, "canonical.bvh")), text);
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
    // from_chars within the line: strtod would skip the CR LF and read the next line's first value
    // (past `end`, and past the buffer on the last line of a string_view).
    while (true) {
      while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
      if (p >= end) break;
      double v = 0.0;
      const auto res = std::from_chars(p, end, v);
      if (res.ec != std::errc()) break;
      row.push_back(v);
      p = res.ptr;
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
  expect_bvh_error(
      replace_once(kChainBvh, "CHANNELS 3 Xrotation Yrotation Zrotation", "CHANNELS 2 Xrotation Yrotation"),
      "hierarchy declares 11 channels");
}
TEST(BvhErrors, NonNumericValue) {
  expect_bvh_error(replace_once(kChainBvh, " 70 80", " 70 abc"), "line 24: value 11 is not a number");
}
TEST(BvhErrors, NanValue) { expect_bvh_error(replace_once(kChainBvh, " 70 80", " 70 nan"), "not finite"); }
TEST(BvhErrors, InfOffset) {
  expect_bvh_error(replace_once(kChainBvh, "OFFSET 0 1 0", "OFFSET 0 inf 0"), "line 8: OFFSET y is not finite");
}
TEST(BvhErrors, ZeroFrames) {
  std::string t = kChainBvh;
  t = t.substr(0, t.find("Frames: 2")) + "Frames: 0\r\nFrame Time: 0.0333333\r\n";
  expect_bvh_error(t, "zero frames");
}
TEST(BvhErrors, MoreFramesThanDeclared) {
  expect_bvh_error(replace_once(kChainBvh, "Frames: 2", "Frames: 1"), "more frame lines");
}
TEST(BvhErrors, UnknownChannel) {
  expect_bvh_error(replace_once(kChainBvh, "Zrotation Xrotation Yrotation", "Zrotation Qrotation Yrotation"),
                   "unknown channel 'Qrotation'");
}
TEST(BvhErrors, BadFrameTime) {
  expect_bvh_error(replace_once(kChainBvh, "Frame Time: 0.0333333", "Frame Time: 0"), "Frame Time must be positive");
}
TEST(BvhErrors, DuplicateJoint) {
  expect_bvh_error(replace_once(kChainBvh, "JOINT tip", "JOINT mid"), "duplicate joint name");
}
TEST(BvhErrors, MissingFileNamesThePath) {
  EXPECT_EQ(error_of([] { bvh_read("/nonexistent/dir/take.bvh"); }),
            "/nonexistent/dir/take.bvh: cannot open (No such file or directory)");
}
TEST(BvhErrors, ByteEfWithoutTheRestOfABomIsNotABom) {
  // Only the three bytes EF BB BF are a byte-order mark; a lone EF (a Latin-1 "i diaeresis")
  // before HIERARCHY used to be dropped with the next two bytes.
  expect_bvh_error("\xEFxxHIERARCHY\n" + std::string(kChainBvh).substr(11), "not a BVH file");
  expect_bvh_error("\xEF\xBBxHIERARCHY\n" + std::string(kChainBvh).substr(11), "not a BVH file");
}

// ---- hostile input: limits of engine/core/limits.h ----

TEST(BvhLimits, HundredThousandNestedJointsAreAnErrorNotAStackOverflow) {
  std::string text = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n";
  text.reserve(3'000'000);
  for (int i = 0; i < 100000; ++i) text += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 1 0\n";
  expect_bvh_error(text, "line 771: joints nested more than 256 deep");
}

TEST(BvhLimits, DepthAndJointCountAtTheLimitAreRead) {
  std::string deep = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n";
  for (int i = 1; i < 256; ++i) deep += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 1 0\n";
  for (int i = 0; i < 256; ++i) deep += "}\n";
  EXPECT_EQ(bvh_parse(deep + "MOTION\nFrames: 1\nFrame Time: 0.1\n5\n", "deep.bvh").joint_count(), 256);
  expect_bvh_error(replace_once(deep, "JOINT j255\n{\nOFFSET 0 1 0\n", "JOINT j255\n{\nOFFSET 0 1 0\nJOINT x\n{\n") +
                       "}\nMOTION\nFrames: 1\nFrame Time: 0.1\n5\n",
                   "joints nested more than 256 deep");

  auto flat = [](int joints) {
    std::string t = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n";
    for (int i = 1; i < joints; ++i) t += "JOINT " + std::to_string(i) + "\n{ OFFSET 0 1 0 }\n";
    return t + "}\nMOTION\nFrames: 1\nFrame Time: 0.1\n5\n";
  };
  EXPECT_EQ(bvh_parse(flat(1024), "wide.bvh").joint_count(), 1024);
  expect_bvh_error(flat(1025), "more than 1024 joints");
}

TEST(BvhLimits, AFramesHeaderBeyondTheFileIsRefusedBeforeAnythingIsAllocated) {
  // 10^8 frames of 3 joints would take 24 GB; the file has 2 frame lines.
  expect_bvh_error(replace_once(kChainBvh, "Frames: 2", "Frames: 100000000"),
                   "line 22: 'Frames: 100000000' of 3 joints would take 22888 MB of memory, more than a file of");
  expect_bvh_error(replace_once(kChainBvh, "Frames: 2", "Frames: 100000001"), "invalid frame count 100000001");
  // A modest lie within the budget is read as far as it goes and reported as truncated.
  expect_bvh_error(replace_once(kChainBvh, "Frames: 2", "Frames: 1000"),
                   "truncated: 'Frames:' declares 1000 frames but the file has 2");
}

TEST(BvhLimits, MemoryPerFileByteBoundsJointsWithoutChannels) {
  // 301 joints x 80 bytes x 1000 frames = 24 MB from a 10 KB file: more than the 16 MB floor and
  // 48 bytes per file byte.
  std::string t = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n";
  for (int i = 0; i < 300; ++i) t += "JOINT " + std::to_string(i) + "\n{ OFFSET 0 1 0 }\n";
  t += "}\nMOTION\nFrames: 1000\nFrame Time: 0.1\n";
  for (int i = 0; i < 1000; ++i) t += "0\n";
  expect_bvh_error(t, "'Frames: 1000' of 301 joints would take 22 MB of memory");
}

TEST(BvhLimits, FrameRateFromOneToAThousandFps) {
  EXPECT_DOUBLE_EQ(bvh_parse(replace_once(kChainBvh, "Frame Time: 0.0333333", "Frame Time: 0.001"), "a").fps, 1000);
  EXPECT_DOUBLE_EQ(bvh_parse(replace_once(kChainBvh, "Frame Time: 0.0333333", "Frame Time: 1"), "a").fps, 1);
  expect_bvh_error(replace_once(kChainBvh, "Frame Time: 0.0333333", "Frame Time: 0.000001"),
                   "line 23: Frame Time 1e-06 s is 1e+06 frames per second; gmg reads 1 to 1000 fps");
  expect_bvh_error(replace_once(kChainBvh, "Frame Time: 0.0333333", "Frame Time: 1e-300"), "e+299 frames per second");
  expect_bvh_error(replace_once(kChainBvh, "Frame Time: 0.0333333", "Frame Time: 2"), "0.5 frames per second");
}

TEST(BvhLimits, NoChannelsAtAllIsNamed) {
  const std::string t = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n\n";
  expect_bvh_error(t, "the hierarchy declares no channels");
}

TEST(Motion, WriteRefusesNanAndLeavesNoFile) {
  Motion m = bvh_parse(kChainBvh, "chain.bvh");
  m.rotations[1].x = std::nan("");
  gmg::testing::TempDir dir;
  const std::string out = dir.file("nan.bvh");
  EXPECT_EQ(error_of([&] { bvh_write(out, m); }), out + ": frame 0, joint 'mid': value is not finite");
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace gmg
