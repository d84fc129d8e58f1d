// Tests of engine/motion/npy, npz and motion_file: .npy parsing of bytes written by hand, the zip
// layer, SMPL-X archives on a template skeleton (hand-worked poses, the root offset, the joint
// mapping by name), round trips, errors naming the archive and the array, and the shared BEAT2
// recording read from its .npz with its BVH as template.
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
#include "tests/core/helpers.h"
#include "tests/motion/motion_test_util.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using testing::error_of;
using testing::kChainBvh;
using testing::replace_once;

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
  // The chain's frames, then 40 random frames: rotations within 1e-6 rad after npz, and after
  // the BVH written from the npz and read back (6 decimals of degrees).
  Motion a = bvh_parse(kChainBvh, "chain.bvh");
  Motion big = motion_rest(a.skeleton, 30.0, 40);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (std::size_t i = 0; i < big.rotations.size(); ++i)
    big.rotations[i] = expmap_to_quat(glm::dvec3(u(rng), u(rng), u(rng)) * 0.5);
  for (int f = 0; f < big.frame_count; ++f) big.translations[big.index(f, 0)] = glm::dvec3(u(rng), u(rng), u(rng));
  for (const Motion* m : {&a, &big}) {
    const Motion b = npz_parse(npz_format(*m, "r.npz"), "r.npz", m->skeleton);
    const Motion c = bvh_parse(bvh_format(b), "r.bvh");
    ASSERT_EQ(c.frame_count, m->frame_count);
    for (std::size_t i = 0; i < m->rotations.size(); ++i) {
      EXPECT_LT(quat_distance(m->rotations[i], b.rotations[i]), 1e-12) << i;
      EXPECT_LT(rotation_angle_between(m->rotations[i], c.rotations[i]), 1e-6) << i;
      EXPECT_LT(glm::length(m->translations[i] - c.translations[i]), 1e-6) << i;
    }
  }
}

// An SMPL-X skeleton in a BVH's depth-first order (not SMPL-X's): the 55 joints with SMPL-X's
// parents, written children-first as a BVH exporter walks them.
Skeleton smplx_depth_first() {
  const int parents[55] = {-1, 0,  0,  0,  1,  2,  3,  4,  5,  6,  7,  8,  9,  9,  9,  12, 13, 14, 16,
                           17, 18, 19, 15, 15, 15, 20, 25, 26, 20, 28, 29, 20, 31, 32, 20, 34, 35, 20,
                           37, 38, 21, 40, 41, 21, 43, 44, 21, 46, 47, 21, 49, 50, 21, 52, 53};
  Skeleton sk;
  std::vector<int> new_index(55, -1);
  std::function<void(int)> visit = [&](int k) {
    Joint j;
    j.name = smplx_joint_names()[k];
    j.parent = parents[k] < 0 ? -1 : new_index[parents[k]];
    j.offset = parents[k] < 0 ? glm::dvec3(0.0) : glm::dvec3(0.01 * k, 0.1, 0.0);
    j.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
    if (parents[k] < 0)
      j.channels.insert(j.channels.begin(), {Channel::Xposition, Channel::Yposition, Channel::Zposition});
    j.rotation_order = rotation_order_from_channels(j.channels);
    new_index[k] = sk.joint_count();
    sk.joints.push_back(j);
    for (int c = 0; c < 55; ++c)
      if (parents[c] == k) visit(c);
  };
  visit(0);
  return sk;
}

TEST(Npz, SmplxJointsAreMappedByNameAndWrittenInSmplxOrder) {
  const Skeleton sk = smplx_depth_first();
  ASSERT_EQ(sk.joint_count(), 55);
  ASSERT_EQ(sk.joints[2].name, "left_knee");  // depth-first: pelvis, left_hip, left_knee, ...
  Motion m = motion_rest(sk, 30.0, 1);
  m.rotations[m.index(0, sk.find("left_knee"))] = expmap_to_quat(glm::dvec3(0.3, 0, 0));
  m.rotations[m.index(0, sk.find("right_thumb3"))] = expmap_to_quat(glm::dvec3(0, 0, -0.2));
  const std::string bytes = npz_format(m, "s.npz");
  const ZipReader zip(bytes, "s.npz");
  const std::vector<double> poses = npy_parse(zip.read("poses.npy"), "p").values;
  ASSERT_EQ(poses.size(), 165u);
  // SMPL-X order: left_knee is joint 4 (values 12..14), right_thumb3 the last (162..164).
  EXPECT_NEAR(poses[12], 0.3, 1e-15);
  EXPECT_NEAR(poses[164], -0.2, 1e-15);
  EXPECT_EQ(poses[6], 0.0);  // joint 2, right_hip, is at rest
  // BEAT2's other arrays, so tools that load them run.
  for (const char* key : {"betas.npy", "expressions.npy", "gender.npy", "model.npy", "mocap_frame_rate.npy"})
    EXPECT_TRUE(zip.has(key)) << key;
  EXPECT_EQ(npy_parse(zip.read("betas.npy"), "b").values, std::vector<double>(300, 0.0));
  EXPECT_EQ(npy_parse(zip.read("mocap_frame_rate.npy"), "f").dtype, "<i4");
  // And read back by name onto the depth-first skeleton.
  const Motion back = npz_parse(bytes, "s.npz", sk);
  for (std::size_t i = 0; i < m.rotations.size(); ++i)
    EXPECT_LT(quat_distance(m.rotations[i], back.rotations[i]), 1e-12) << sk.joints[i].name;
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
  const Motion npz = motion_read(dir + "2_scott_0_1_1.npz", dir + "2_scott_0_1_1.bvh");
  ASSERT_EQ(npz.frame_count, bvh.frame_count);
  EXPECT_EQ(npz.fps, 30.0);
  const Eigen::MatrixXd pb = motion_forward_kinematics(bvh), pn = motion_forward_kinematics(npz);
  // The BVH's root channels are trans + the pelvis's rest position; its ROOT OFFSET is 0, so the
  // npz read on it sits lower by exactly that constant (data README), for every joint and frame.
  const Eigen::RowVector3d pelvis_rest(0.002777, -0.383289, 0.010682);
  Eigen::MatrixXd shifted = pn;
  for (Eigen::Index j = 0; j < npz.joint_count(); ++j) shifted.middleCols(3 * j, 3).rowwise() += pelvis_rest;
  // The BVH rounds angles to 1e-6 degrees and positions to 1e-6 m; poses are float32.
  EXPECT_LT(max_abs_diff(shifted, pb), 1e-5);
  EXPECT_GT(max_abs_diff(pn, pb), 0.38);
  // A template whose ROOT OFFSET is the pelvis's rest position gives the world positions as they are.
  testing::TempDir tmp;
  const std::string templ = tmp.file("template.bvh");
  testing::write_text(templ, replace_once(read_file_bytes(dir + "2_scott_0_1_1.bvh"),
                                          "OFFSET 0.000000 0.000000 0.000000", "OFFSET 0.002777 -0.383289 0.010682"));
  const Motion exact = motion_read(dir + "2_scott_0_1_1.npz", templ);
  EXPECT_LT(max_abs_diff(motion_forward_kinematics(exact), pb), 1e-5);
}

}  // namespace
}  // namespace gmg
