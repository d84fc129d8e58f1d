// Tests of engine/motion/npy, npz and motion_file: .npy parsing of bytes written by hand, the zip
// layer, SMPL-X archives on a template skeleton (hand-worked poses, the root offset, the joint
// mapping by name), round trips, errors naming the archive and the array, and the shared BEAT2
// recording read from its .npz with its BVH as template.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/motion/bvh.h"
#include "engine/motion/motion_file.h"
#include "engine/motion/npy.h"
#include "engine/motion/npz.h"
#include "engine/motion/zip.h"
#include "tests/core/helpers.h"
#include "tests/motion/motion_test_util.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using testing::error_of;
using testing::kChainBvh;
using testing::replace_once;
using testing::smplx_depth_first;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// An .npy file the way numpy writes format 1.0, assembled here byte by byte: magic, version,
// little-endian header length, the dict padded with spaces to a multiple of 64 bytes with a final
// newline, then the raw data.
std::string npy_by_hand(const std::string& dict, const std::string& data) {
  std::string header = dict;
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  out += static_cast<char>(header.size() & 0xFF);
  out += static_cast<char>(header.size() >> 8);
  return out + header + data;
}

template <class T>
std::string raw(const std::vector<T>& values) {
  std::string s(values.size() * sizeof(T), '\0');
  if (!values.empty()) std::memcpy(&s[0], values.data(), s.size());  // data() may be null when empty
  return s;
}

std::string f8(const std::string& shape, const std::vector<double>& v) {
  return npy_by_hand("{'descr': '<f8', 'fortran_order': False, 'shape': " + shape + ", }", raw(v));
}

// An archive of the given (name, .npy bytes) members.
std::string archive(const std::vector<std::pair<std::string, std::string>>& members, bool deflate = false) {
  std::vector<ZipMember> m;
  m.reserve(members.size());
  for (const auto& [name, bytes] : members) m.push_back({name, bytes, deflate});
  return zip_format(m, "test.npz");
}

std::string fps30() { return npy_by_hand("{'descr': '<i4', 'fortran_order': False, 'shape': (), }", raw<int>({30})); }

// The largest component difference of two quaternions of the same rotation (q and -q are one).
double quat_distance(const glm::dquat& a, const glm::dquat& b) {
  double plus = 0, minus = 0;
  for (int i = 0; i < 4; ++i) {
    plus = std::max(plus, std::abs(a[i] - b[i]));
    minus = std::max(minus, std::abs(a[i] + b[i]));
  }
  return std::min(plus, minus);
}

double max_abs_diff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).cwiseAbs().maxCoeff(); }

// ---- .npy ---------------------------------------------------------------------------------------

TEST(Npy, ParsesFloat64Float32AndIntegerArraysWrittenByHand) {
  const NpyArray a = npy_parse(f8("(2, 3)", {1, 2, 3, 4, 5, -6.5}), "a.npy");
  EXPECT_EQ(a.dtype, "<f8");
  EXPECT_EQ(a.shape, (std::vector<std::uint64_t>{2, 3}));
  EXPECT_EQ(a.values, (std::vector<double>{1, 2, 3, 4, 5, -6.5}));

  const NpyArray b = npy_parse(
      npy_by_hand("{'descr': '<f4', 'fortran_order': False, 'shape': (3,), }", raw<float>({0.1f, 2, -3})), "b.npy");
  ASSERT_EQ(b.values.size(), 3u);
  EXPECT_EQ(b.values[0], static_cast<double>(0.1f));  // the float's exact value, widened
  EXPECT_EQ(b.values[2], -3.0);

  const NpyArray c = npy_parse(fps30(), "c.npy");
  EXPECT_TRUE(c.shape.empty());
  EXPECT_EQ(c.values, std::vector<double>{30});

  // Keys in another order, double quotes, no trailing comma: still the dict numpy means.
  const NpyArray d = npy_parse(
      npy_by_hand("{\"shape\": (1, 1), \"fortran_order\": False, \"descr\": \"<i8\"}", raw<long long>({-7})), "d.npy");
  EXPECT_EQ(d.values, std::vector<double>{-7});
}

TEST(Npy, WritesWhatItReadsAndPadsTheHeaderTo64Bytes) {
  const std::string bytes = npy_format("<f8", {2, 2}, {1.5, -2, 0, 1e-300});
  ASSERT_GE(bytes.size(), 10u);
  const std::size_t header = static_cast<unsigned char>(bytes[8]) | static_cast<unsigned char>(bytes[9]) << 8;
  EXPECT_EQ((10 + header) % 64, 0u);
  EXPECT_EQ(bytes.size(), 10 + header + 32);             // 4 float64 values
  EXPECT_EQ(bytes, f8("(2, 2)", {1.5, -2, 0, 1e-300}));  // byte for byte what numpy writes
  // A text scalar as numpy saves a str: dtype '<U7', shape (), UTF-32 little-endian.
  std::string utf32;
  for (char c : std::string("neutral")) utf32 += std::string(1, c) + std::string(3, '\0');
  EXPECT_EQ(npy_format_text("neutral"), npy_by_hand("{'descr': '<U7', 'fortran_order': False, 'shape': (), }", utf32));
}

TEST(Npy, RejectsWhatItCannotReadFaithfullyNamingTheArray) {
  const std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (2,), }";
  const std::string two = raw<double>({1, 2});
  EXPECT_TRUE(contains(error_of([&] { npy_parse("PK\x03\x04 not an array", "x.npz: poses.npy"); }),
                       "x.npz: poses.npy: not a .npy array"));
  EXPECT_TRUE(contains(error_of([&] { npy_parse(npy_by_hand(replace_once(dict, "<f8", ">f8"), two), "p"); }),
                       "p: big-endian dtype '>f8'"));
  EXPECT_TRUE(
      contains(error_of([&] { npy_parse(npy_by_hand(replace_once(dict, "<f8", "<U9"), two), "p"); }), "holds text"));
  EXPECT_TRUE(
      contains(error_of([&] { npy_parse(npy_by_hand(replace_once(dict, "<f8", "|O"), two), "p"); }), "Python objects"));
  EXPECT_TRUE(contains(error_of([&] { npy_parse(npy_by_hand(replace_once(dict, "<f8", "<c16"), two), "p"); }),
                       "dtype '<c16' is not supported"));
  const std::string fortran = "{'descr': '<f8', 'fortran_order': True, 'shape': (1, 2), }";
  EXPECT_TRUE(contains(error_of([&] { npy_parse(npy_by_hand(fortran, two), "p"); }), "Fortran-order"));
  EXPECT_TRUE(contains(error_of([&] { npy_parse(npy_by_hand(dict, two.substr(0, 12)), "p"); }),
                       "shape (2,) of <f8 needs 16 bytes of data, the array has 12 (truncated)"));
  EXPECT_TRUE(contains(error_of([&] { npy_parse(npy_by_hand(dict, two + "x"), "p"); }), "the array has 17"));
  EXPECT_TRUE(contains(error_of([&] { npy_parse(npy_by_hand("{'descr': '<f8', 'shape': (2,), }", two), "p"); }),
                       "lacks 'fortran_order'"));
  EXPECT_TRUE(contains(error_of([&] { npy_parse(npy_by_hand(replace_once(dict, "}", "'x': 1, }"), two), "p"); }),
                       "unexpected key 'x'"));
  EXPECT_TRUE(contains(error_of([&] { npy_parse(npy_by_hand(replace_once(dict, "(2,)", "(2, a)"), two), "p"); }),
                       "malformed .npy header"));
  // A shape whose size overflows is refused before anything is allocated.
  EXPECT_TRUE(contains(
      error_of([&] { npy_parse(npy_by_hand(replace_once(dict, "(2,)", "(2147483648, 2147483648)"), two), "p"); }),
      "too large"));
  std::string version = npy_by_hand(dict, two);
  version[6] = '\x04';
  EXPECT_TRUE(contains(error_of([&] { npy_parse(version, "p"); }), "format version 4.0 is not supported"));
  std::string long_header = npy_by_hand(dict, two);
  long_header[9] = '\x7f';  // declares a header longer than the file
  EXPECT_TRUE(contains(error_of([&] { npy_parse(long_header, "p"); }), "truncated .npy header"));
}

// ---- zip ----------------------------------------------------------------------------------------

TEST(Zip, StoredAndDeflatedArchivesReadTheSameAndWritingIsDeterministic) {
  const std::string poses = f8("(1, 3)", {0.1, 0.2, 0.3});
  const std::string stored = archive({{"poses.npy", poses}, {"x.npy", fps30()}});
  const std::string deflated = archive({{"poses.npy", poses}, {"x.npy", fps30()}}, true);
  EXPECT_EQ(stored, archive({{"poses.npy", poses}, {"x.npy", fps30()}}));
  // A zip local header: signature, version, flags, then the method at byte 8 (0 = stored, 8 = deflate).
  EXPECT_EQ(stored.compare(0, 4, "PK\x03\x04"), 0);
  EXPECT_EQ(stored[8], 0);
  EXPECT_EQ(deflated[8], 8);
  for (const std::string* bytes : {&stored, &deflated}) {
    const ZipReader zip(*bytes, "a.npz");
    EXPECT_EQ(zip.names(), (std::vector<std::string>{"poses.npy", "x.npy"}));
    EXPECT_EQ(zip.read("poses.npy"), poses);
    EXPECT_FALSE(zip.has("trans.npy"));
  }
}

TEST(Zip, ACorruptOrForeignArchiveIsAClearError) {
  EXPECT_TRUE(contains(error_of([] {
                         const std::string bvh = "HIERARCHY\nROOT x";
                         ZipReader(bvh, "m.npz");
                       }),
                       "m.npz: not a readable zip archive"));
  EXPECT_TRUE(contains(error_of([] {
                         const std::string empty;
                         ZipReader(empty, "m.npz");
                       }),
                       "m.npz: not a readable zip archive"));
  // A flipped data byte in a stored member: the CRC catches it.
  std::string bytes = archive({{"poses.npy", f8("(4,)", {1, 2, 3, 4})}});
  const std::size_t data = bytes.find(raw<double>({1, 2, 3, 4}));
  ASSERT_NE(data, std::string::npos);
  bytes[data + 3] ^= 0x40;
  const ZipReader zip(bytes, "m.npz");
  EXPECT_TRUE(contains(error_of([&] { zip.read("poses.npy"); }), "m.npz: poses.npy: corrupt member"));
  // Truncated in the middle: the central directory is gone.
  const std::string whole = archive({{"poses.npy", f8("(4,)", {1, 2, 3, 4})}});
  EXPECT_TRUE(contains(error_of([&] {
                         const std::string half = whole.substr(0, whole.size() / 2);
                         ZipReader(half, "t.npz");
                       }),
                       "t.npz: not a readable zip archive"));
}

// ---- SMPL-X archives on a template ---------------------------------------------------------------

TEST(Npz, HandWorkedPoseOnTheChainTemplate) {
  // One frame: root unrotated at trans (1, 2, 3); mid turned 90 degrees about X (axis-angle
  // (pi/2, 0, 0)), so the tip's offset (0, 0, 2) points along -Y: mid at root + (0, 1, 0) =
  // (1, 3, 3), tip at (1, 3 - 2, 3) = (1, 1, 3).
  const Skeleton sk = bvh_parse(kChainBvh, "chain.bvh").skeleton;
  const double h = std::acos(-1.0) / 2;
  const std::string npz = archive({{"poses.npy", f8("(1, 9)", {0, 0, 0, h, 0, 0, 0, 0, 0})},
                                   {"trans.npy", f8("(1, 3)", {1, 2, 3})},
                                   {"mocap_frame_rate.npy", fps30()}});
  const Motion m = npz_parse(npz, "one.npz", sk);
  EXPECT_EQ(m.frame_count, 1);
  EXPECT_EQ(m.fps, 30.0);
  const Eigen::MatrixXd p = motion_forward_kinematics(m);
  const double expected[9] = {1, 2, 3, 1, 3, 3, 1, 1, 3};
  for (int c = 0; c < 9; ++c) EXPECT_NEAR(p(0, c), expected[c], 1e-12) << "column " << c;
}

TEST(Npz, TheRootTranslationIsTransPlusTheTemplatesRootOffsetAndWritingSubtractsIt) {
  Skeleton sk = bvh_parse(kChainBvh, "chain.bvh").skeleton;
  sk.joints[0].offset = glm::dvec3(0.5, -0.25, 0.0);  // the pelvis's rest position
  const std::string npz = archive({{"poses.npy", f8("(1, 9)", std::vector<double>(9, 0.0))},
                                   {"trans.npy", f8("(1, 3)", {1, 2, 3})},
                                   {"mocap_frame_rate.npy", fps30()}});
  const Motion m = npz_parse(npz, "one.npz", sk);
  EXPECT_EQ(m.translation(0, 0), glm::dvec3(1.5, 1.75, 3.0));
  const std::string bytes = npz_format(m, "w.npz");  // the reader keeps a view of it
  const ZipReader written(bytes, "w.npz");
  EXPECT_EQ(npy_parse(written.read("trans.npy"), "t").values, (std::vector<double>{1, 2, 3}));
}

TEST(Npz, ABvhNpzBvhRoundTripKeepsEveryRotation) {
  // The chain's frames, then 40 random frames: with float64 arrays the rotations come back to
  // 1e-12, with BEAT2's float32 poses to float32's rounding (half an ulp of pi is 1.2e-7 rad per
  // axis-angle component), and after the BVH written from the npz and read back within 1e-6 rad
  // (6 decimals of degrees).
  Motion a = bvh_parse(kChainBvh, "chain.bvh");
  Motion big = motion_rest(a.skeleton, 30.0, 40);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (std::size_t i = 0; i < big.rotations.size(); ++i)
    big.rotations[i] = expmap_to_quat(glm::dvec3(u(rng), u(rng), u(rng)) * 0.5);
  for (int f = 0; f < big.frame_count; ++f) big.translations[big.index(f, 0)] = glm::dvec3(u(rng), u(rng), u(rng));
  for (const Motion* m : {&a, &big}) {
    const Motion b = npz_parse(npz_format(*m, "r.npz", {}, NpzFloats::Float64), "r.npz", m->skeleton);
    const Motion b32 = npz_parse(npz_format(*m, "r.npz"), "r.npz", m->skeleton);
    const Motion c = bvh_parse(bvh_format(b), "r.bvh");
    ASSERT_EQ(c.frame_count, m->frame_count);
    for (std::size_t i = 0; i < m->rotations.size(); ++i) {
      EXPECT_LT(quat_distance(m->rotations[i], b.rotations[i]), 1e-12) << i;
      EXPECT_LT(rotation_angle_between(m->rotations[i], b32.rotations[i]), 3e-7) << i;
      EXPECT_LT(rotation_angle_between(m->rotations[i], c.rotations[i]), 1e-6) << i;
      EXPECT_LT(glm::length(m->translations[i] - c.translations[i]), 1e-6) << i;
      EXPECT_EQ(m->translations[i], b32.translations[i]) << i;  // trans is float64 in BEAT2 too
    }
  }
}

TEST(Npz, SmplxJointsAreMappedByNameAndWrittenInSmplxOrderWithBeat2sArrays) {
  const Skeleton sk = smplx_depth_first();
  ASSERT_EQ(sk.joint_count(), 55);
  ASSERT_EQ(sk.joints[2].name, "left_knee");  // depth-first: pelvis, left_hip, left_knee, ...
  Motion m = motion_rest(sk, 30.0, 1);
  m.rotations[m.index(0, sk.find("left_knee"))] = expmap_to_quat(glm::dvec3(0.3, 0, 0));
  m.rotations[m.index(0, sk.find("right_thumb3"))] = expmap_to_quat(glm::dvec3(0, 0, -0.2));
  const std::string bytes = npz_format(m, "s.npz");
  const ZipReader zip(bytes, "s.npz");
  const NpyArray poses_array = npy_parse(zip.read("poses.npy"), "p");
  EXPECT_EQ(poses_array.dtype, "<f4");  // as BEAT2 ships poses
  const std::vector<double>& poses = poses_array.values;
  ASSERT_EQ(poses.size(), 165u);
  // SMPL-X order: left_knee is joint 4 (values 12..14), right_thumb3 the last (162..164).
  EXPECT_EQ(poses[12], static_cast<double>(0.3f));
  EXPECT_EQ(poses[164], static_cast<double>(-0.2f));
  EXPECT_EQ(poses[6], 0.0);  // joint 2, right_hip, is at rest
  // BEAT2's arrays in BEAT2's order and dtypes, so tools that load them run.
  EXPECT_EQ(zip.names(), (std::vector<std::string>{"betas.npy", "poses.npy", "expressions.npy", "trans.npy",
                                                   "model.npy", "gender.npy", "mocap_frame_rate.npy"}));
  const NpyArray betas = npy_parse(zip.read("betas.npy"), "b");
  EXPECT_EQ(betas.dtype, "<f4");
  EXPECT_EQ(betas.values, std::vector<double>(300, 0.0));
  const NpyArray expressions = npy_parse(zip.read("expressions.npy"), "e");
  EXPECT_EQ(expressions.dtype, "<f8");
  EXPECT_EQ(expressions.shape, (std::vector<std::uint64_t>{1, 100}));
  EXPECT_EQ(npy_parse(zip.read("trans.npy"), "t").dtype, "<f8");
  EXPECT_EQ(npy_parse(zip.read("mocap_frame_rate.npy"), "f").dtype, "<i4");
  EXPECT_EQ(npy_parse_text(zip.read("gender.npy"), "g"), "neutral");
  EXPECT_EQ(npy_parse_text(zip.read("model.npy"), "m"), "smplx2020");
  // And read back by name onto the depth-first skeleton.
  const Motion back = npz_parse(bytes, "s.npz", sk);
  for (std::size_t i = 0; i < m.rotations.size(); ++i)
    EXPECT_LT(rotation_angle_between(m.rotations[i], back.rotations[i]), 3e-7) << sk.joints[i].name;
}

TEST(Npz, ASmplxSkeletonWithAZeroRootOffsetPutsBeat2sPelvisRestBetweenTransAndTheRoot) {
  // BEAT2's BVH convention: ROOT OFFSET 0, root channels = trans + the pelvis rest position.
  const Skeleton sk = smplx_depth_first();
  ASSERT_EQ(sk.joints[0].offset, glm::dvec3(0.0));
  EXPECT_EQ(npz_root_rest(sk), glm::dvec3(0.002777, -0.383289, 0.010682));
  std::vector<double> zeros(165, 0.0);
  const std::string npz = archive({{"poses.npy", f8("(1, 165)", zeros)},
                                   {"trans.npy", f8("(1, 3)", {1, 2, 3})},
                                   {"mocap_frame_rate.npy", fps30()}});
  const Motion m = npz_parse(npz, "one.npz", sk);
  EXPECT_EQ(m.translation(0, 0), glm::dvec3(1, 2, 3) + glm::dvec3(0.002777, -0.383289, 0.010682));
  const std::string bytes = npz_format(m, "w.npz");
  const ZipReader written(bytes, "w.npz");
  const std::vector<double> trans = npy_parse(written.read("trans.npy"), "t").values;
  ASSERT_EQ(trans.size(), 3u);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(trans[static_cast<std::size_t>(c)], c + 1.0, 1e-15);
  // Another skeleton with a zero ROOT OFFSET keeps trans as the root's translation.
  const Skeleton chain = bvh_parse(kChainBvh, "chain.bvh").skeleton;
  EXPECT_EQ(npz_root_rest(chain), chain.joints[0].offset);
}

TEST(Npz, TheBodyIsReadAndWrittenBackAndItsArraysAreChecked) {
  const Skeleton sk = smplx_depth_first();
  std::vector<double> expressions(8), betas = {0.5, -2.25, 1.0};
  for (std::size_t i = 0; i < expressions.size(); ++i) expressions[i] = 0.1 * static_cast<double>(i) - 0.3;
  std::string utf32;
  for (char c : std::string("male")) utf32 += std::string(1, c) + std::string(3, '\0');
  const std::string gender = npy_by_hand("{'descr': '<U4', 'fortran_order': False, 'shape': (), }", utf32);
  auto npz = [&](const std::string& expr, const std::string& bet) {
    return archive({{"betas.npy", bet},
                    {"poses.npy", f8("(2, 165)", std::vector<double>(330, 0.0))},
                    {"expressions.npy", expr},
                    {"trans.npy", f8("(2, 3)", std::vector<double>(6, 0.0))},
                    {"gender.npy", gender},
                    {"mocap_frame_rate.npy", fps30()}});
  };
  SmplxBody body;
  const Motion m = npz_parse(npz(f8("(2, 4)", expressions), f8("(3,)", betas)), "b.npz", sk, &body);
  EXPECT_EQ(body.betas, betas);
  EXPECT_EQ(body.expression_dims, 4);
  EXPECT_EQ(body.expressions, expressions);
  EXPECT_EQ(body.gender, "male");
  EXPECT_EQ(body.model, "");
  // Written back: the same face (float64, exact), shape (float32) and gender.
  const std::string bytes = npz_format(m, "w.npz", body);
  SmplxBody again;
  npz_parse(bytes, "w.npz", sk, &again);
  EXPECT_EQ(again.expressions, expressions);
  EXPECT_EQ(again.betas, (std::vector<double>{0.5, -2.25, 1.0}));  // exact in float32
  EXPECT_EQ(again.gender, "male");
  EXPECT_EQ(again.model, "smplx2020");
  // A face of another length than the poses, or a value that is not finite, names the array.
  EXPECT_TRUE(contains(
      error_of([&] { npz_parse(npz(f8("(3, 4)", std::vector<double>(12)), f8("(3,)", betas)), "b.npz", sk, &body); }),
      "b.npz: expressions.npy: expected shape (2, coefficients) to match poses, found (3, 4)"));
  std::vector<double> bad = betas;
  bad[1] = std::nan("");
  EXPECT_TRUE(
      contains(error_of([&] { npz_parse(npz(f8("(2, 4)", expressions), f8("(3,)", bad)), "b.npz", sk, &body); }),
               "b.npz: betas.npy: the value at frame 0, column 1 is not finite"));
  // Without out_body the body is not looked at: a motion reader that needs no face reads on.
  EXPECT_NO_THROW(npz_parse(npz(f8("(3, 4)", std::vector<double>(12)), f8("(3,)", betas)), "b.npz", sk));
  // A face that does not fit the motion is refused when writing.
  SmplxBody wrong = body;
  wrong.expressions.resize(4);
  EXPECT_TRUE(contains(error_of([&] { npz_format(m, "w.npz", wrong); }), "w.npz: the face has 1 frames, the motion 2"));
}

TEST(Npz, BetasComeFromAnArchiveOrAnNpyFile) {
  testing::TempDir dir;
  const std::vector<double> betas = {1.5, -0.5};
  testing::write_text(dir.file("b.npy"), f8("(2,)", betas));
  testing::write_text(dir.file("row.npy"), f8("(1, 2)", betas));
  testing::write_text(dir.file("b.npz"), archive({{"betas.npy", f8("(2,)", betas)}, {"x.npy", fps30()}}));
  testing::write_text(dir.file("none.npz"), archive({{"x.npy", fps30()}}));
  EXPECT_EQ(read_betas_file(dir.file("b.npy")), betas);
  EXPECT_EQ(read_betas_file(dir.file("row.npy")), betas);
  EXPECT_EQ(read_betas_file(dir.file("b.npz")), betas);
  EXPECT_TRUE(contains(error_of([&] { read_betas_file(dir.file("none.npz")); }),
                       dir.file("none.npz") + ": no 'betas' array (the archive holds: x.npy)"));
  testing::write_text(dir.file("m.npy"), f8("(2, 2)", {1, 2, 3, 4}));
  EXPECT_TRUE(contains(error_of([&] { read_betas_file(dir.file("m.npy")); }),
                       "expected shape (betas,) or (1, betas), found (2, 2)"));
}

TEST(Npy, TextArraysAndFloat32AreReadAndWrittenAsNumpyDoes) {
  EXPECT_EQ(npy_parse_text(npy_format_text("smplx2020"), "m"), "smplx2020");
  // numpy pads a shorter text in a wider dtype with NULs.
  std::string padded;
  for (char c : std::string("ab")) padded += std::string(1, c) + std::string(3, '\0');
  padded += std::string(8, '\0');
  EXPECT_EQ(npy_parse_text(npy_by_hand("{'descr': '<U4', 'fortran_order': False, 'shape': (), }", padded), "t"), "ab");
  EXPECT_TRUE(contains(error_of([&] { npy_parse_text(f8("()", {1.0}), "t"); }), "t: expected text"));
  const std::string f4 = npy_format("<f4", {3}, {0.1, 2, -3});
  EXPECT_EQ(f4, npy_by_hand("{'descr': '<f4', 'fortran_order': False, 'shape': (3,), }", raw<float>({0.1f, 2, -3})));
  EXPECT_TRUE(contains(error_of([&] { npy_format("<f4", {1}, {1e300}); }), "exceeds float32"));
}

TEST(Npz, ShapesThatDoNotFitTheTemplateAndBadValuesAreErrorsNamingTheArray) {
  const Skeleton sk = bvh_parse(kChainBvh, "chain.bvh").skeleton;
  const std::string poses = f8("(2, 9)", std::vector<double>(18, 0.0)), trans = f8("(2, 3)", std::vector<double>(6));
  auto npz = [&](const std::string& p, const std::string& t, const std::string& fps) {
    return archive({{"poses.npy", p}, {"trans.npy", t}, {"mocap_frame_rate.npy", fps}});
  };
  EXPECT_NO_THROW(npz_parse(npz(poses, trans, fps30()), "ok.npz", sk));
  EXPECT_TRUE(
      contains(error_of([&] { npz_parse(npz(f8("(2, 12)", std::vector<double>(24)), trans, fps30()), "a.npz", sk); }),
               "a.npz: poses.npy: 4 joints a frame, but the skeleton template has 3 joints"));
  EXPECT_TRUE(
      contains(error_of([&] { npz_parse(npz(f8("(18,)", std::vector<double>(18)), trans, fps30()), "a.npz", sk); }),
               "a.npz: poses.npy: expected shape (frames, 3 x joints), found (18,)"));
  EXPECT_TRUE(
      contains(error_of([&] { npz_parse(npz(poses, f8("(3, 3)", std::vector<double>(9)), fps30()), "a.npz", sk); }),
               "a.npz: trans.npy: expected shape (2, 3) to match poses, found (3, 3)"));
  std::vector<double> nan(18, 0.0);
  nan[13] = std::nan("");
  EXPECT_TRUE(contains(error_of([&] { npz_parse(npz(f8("(2, 9)", nan), trans, fps30()), "a.npz", sk); }),
                       "a.npz: poses.npy: the value at frame 1, column 4 is not finite"));
  EXPECT_TRUE(contains(error_of([&] { npz_parse(npz(poses, trans, f8("()", {0.0})), "a.npz", sk); }),
                       "a.npz: mocap_frame_rate.npy: frame rate 0 is not a positive"));
  EXPECT_TRUE(contains(error_of([&] { npz_parse(npz(f8("(0, 9)", {}), f8("(0, 3)", {}), fps30()), "a.npz", sk); }),
                       "zero frames"));
  const std::string no_trans = archive({{"poses.npy", poses}, {"betas.npy", f8("(1,)", {0})}});
  EXPECT_TRUE(contains(error_of([&] { npz_parse(no_trans, "a.npz", sk); }),
                       "a.npz: no 'trans' array (an SMPL-X motion needs poses, trans and mocap_frame_rate; the "
                       "archive holds: poses.npy, betas.npy)"));
  // AMASS spells the frame rate mocap_framerate.
  const Motion amass =
      npz_parse(archive({{"poses.npy", poses}, {"trans.npy", trans}, {"mocap_framerate.npy", f8("()", {120.0})}}),
                "amass.npz", sk);
  EXPECT_EQ(amass.fps, 120.0);
}

TEST(MotionFile, DispatchesByExtensionAndZipSignatureAndNeedsATemplateForNpz) {
  testing::TempDir dir;
  const std::string templ = dir.file("chain.bvh");
  testing::write_text(templ, kChainBvh);
  const Motion chain = motion_read(templ);  // a BVH; no template needed
  const std::string npz = dir.file("chain.npz");
  motion_write(npz, chain);
  EXPECT_EQ(read_file_bytes(npz).compare(0, 4, "PK\x03\x04"), 0);
  EXPECT_TRUE(
      contains(error_of([&] { motion_read(npz); }), npz + ": an SMPL-X .npz motion has joint rotations but no"));
  EXPECT_TRUE(contains(error_of([&] { motion_read(npz, npz); }), "a skeleton template must be a BVH file"));
  const Motion back = motion_read(npz, templ);
  EXPECT_EQ(back.frame_count, chain.frame_count);
  // An archive named .bvh is still read as one, rather than "not a BVH file".
  const std::string misnamed = dir.file("archive.bvh");
  std::filesystem::copy_file(npz, misnamed);
  EXPECT_EQ(motion_read(misnamed, templ).frame_count, chain.frame_count);
  // Writing .bvh writes a BVH.
  const std::string bvh = dir.file("out.BVH");
  motion_write(bvh, back);
  EXPECT_EQ(read_file_bytes(bvh).rfind("HIERARCHY", 0), 0u);
}

// ---- the shared BEAT2 recording ------------------------------------------------------------------

TEST(Npz, SharedBeat2NpzWithItsBvhAsTemplateGivesTheBvhsJointPositions) {
  GMG_REQUIRE_SHARED_DATA();
  const std::string dir = testing::shared_data_dir() + "/beat2_scott/";
  const Motion bvh = bvh_read(dir + "2_scott_0_1_1.bvh");
  SmplxBody body;
  const Motion npz = motion_read(dir + "2_scott_0_1_1.npz", dir + "2_scott_0_1_1.bvh", &body);
  ASSERT_EQ(npz.frame_count, bvh.frame_count);
  EXPECT_EQ(npz.fps, 30.0);
  // The BVH's root channels are trans + the pelvis's rest position (data README) and its ROOT
  // OFFSET is 0: the npz read on it puts the pelvis rest back, so every joint of every frame is
  // where the BVH has it. The BVH rounds angles to 1e-6 degrees and positions to 1e-6 m; poses
  // are float32.
  EXPECT_LT(max_abs_diff(motion_forward_kinematics(npz), motion_forward_kinematics(bvh)), 1e-5);
  // Its body: BEAT2's 300 betas and 100 expression coefficients a frame.
  ASSERT_EQ(body.betas.size(), 300u);
  EXPECT_NEAR(*std::min_element(body.betas.begin(), body.betas.end()), -2.5227702, 1e-6);
  EXPECT_EQ(body.expression_dims, 100);
  EXPECT_EQ(body.expressions.size(), 1906u * 100u);
  EXPECT_EQ(body.gender, "neutral");
  EXPECT_EQ(body.model, "smplx2020");

  // Written back, from the npz or from the BVH: the file's trans (BEAT2's convention, whichever
  // way the motion came), its poses to float32 and its body exactly.
  const std::string original = read_file_bytes(dir + "2_scott_0_1_1.npz");
  const ZipReader zo(original, "original");
  const NpyArray trans = npy_parse(zo.read("trans.npy"), "t"), poses = npy_parse(zo.read("poses.npy"), "p");
  for (const Motion* m : {&npz, &bvh}) {
    const std::string bytes = npz_format(*m, "w.npz", m == &npz ? body : SmplxBody{});
    const ZipReader zw(bytes, "w.npz");
    const NpyArray t = npy_parse(zw.read("trans.npy"), "t"), p = npy_parse(zw.read("poses.npy"), "p");
    ASSERT_EQ(t.values.size(), trans.values.size());
    double worst = 0;
    for (std::size_t i = 0; i < t.values.size(); ++i) worst = std::max(worst, std::abs(t.values[i] - trans.values[i]));
    EXPECT_LT(worst, m == &npz ? 1e-12 : 1e-6) << (m == &npz ? "from the npz" : "from the BVH");
    if (m == &npz) {
      // float32 -> double rotation -> float32: the same floats.
      EXPECT_EQ(p.values, poses.values);
      EXPECT_EQ(npy_parse(zw.read("expressions.npy"), "e").values, npy_parse(zo.read("expressions.npy"), "e").values);
      EXPECT_EQ(npy_parse(zw.read("betas.npy"), "b").values, npy_parse(zo.read("betas.npy"), "b").values);
    }
  }
}

}  // namespace
}  // namespace gmg
