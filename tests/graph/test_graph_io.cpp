// Graph files: save/load round trip, rejection of damaged files, DOT/GraphML export.
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <new>
#include <regex>
#include <tuple>
#include <utility>

#include <unistd.h>

#include <gtest/gtest.h>

#include "engine/core/checksum.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "graph/build.h"
#include "graph/graph_check.h"
#include "graph/graph_io.h"
#include "graph/key_poses.h"
#include "graph/reference_facts.h"
#include "graph/stats.h"
#include "tests/core/helpers.h"
#include "tests/graph/fixtures.h"
#include "tests/test_support.h"

// Bytes allocated while counting is on (this test executable's global operator new, on malloc;
// GCC takes the replacement's free for a mismatch with operator new).
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
std::atomic<bool> g_counting{false};
std::atomic<std::size_t> g_allocated{0};

void* operator new(std::size_t size) {
  if (g_counting) g_allocated += size;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace gmg {
namespace {

using namespace gmg::testing;

// A graph of a few thousand frames: its arrays dwarf the small allocations of a load.
MotionGraph long_graph() {
  std::vector<double> x;
  x.reserve(3000);
  for (int i = 0; i < 3000; ++i) x.push_back(0.8 * std::sin(i * 0.07) + 0.3 * std::sin(i * 0.23));
  return graph_build({{"long.bvh", line_motion(x), {10, 400}, {{20, "big"}}}}, GraphParams{});
}

// The bytes of a graph's nodes: what a load copies (the motion, the edges' row starts, targets and
// weights, the speech features and activity are read in place from the file).
std::size_t copied_bytes(const MotionGraph& g) { return g.graph.vertex_count() * sizeof(NodeInfo); }

TEST(GraphIo, LoadingServesTheMotionFromTheFile) {
  const MotionGraph g = long_graph();
  gmg::testing::TempDir dir;
  graph_save(dir.file("g.gmg"), g);
  const std::size_t motion = g.motion.rotations.size() * sizeof(glm::dquat) +
                             g.motion.translations.size() * sizeof(glm::dvec3) + g.speech.size() * sizeof(float);
  const std::size_t weights = g.edge_weights.size() * sizeof(double);
  const std::size_t targets = g.graph.edge_count() * sizeof(GraphVertex);
  const std::size_t copied = copied_bytes(g);
  ASSERT_GT(motion, 300000u);
  // As the command line does it: a graph declared first, then assigned the loaded one.
  MotionGraph h;
  g_allocated = 0;
  g_counting = true;
  h = graph_load(dir.file("g.gmg"));
  g_counting = false;
  EXPECT_EQ(h.frame_count(), g.frame_count());
  EXPECT_EQ(h.graph.edge_count(), g.graph.edge_count());
  EXPECT_TRUE(h.motion.rotations.is_view());
  EXPECT_TRUE(h.motion.translations.is_view());
  EXPECT_TRUE(h.speech.is_view());
  EXPECT_TRUE(h.edge_weights.is_view());
  EXPECT_TRUE(h.graph.row_starts().is_view());
  EXPECT_TRUE(h.graph.targets().is_view());
  EXPECT_EQ(h.graph.row_starts(), g.graph.row_starts());
  EXPECT_EQ(h.graph.targets(), g.graph.targets());
  EXPECT_EQ(h.motion.rotations, g.motion.rotations);
  EXPECT_EQ(h.speech, g.speech);
  EXPECT_EQ(h.edge_weights, g.edge_weights);
  // The nodes plus small change (names, skeleton); a copy of the motion would be more, and one of
  // the targets (half the weights' bytes) more than the change.
  ASSERT_GT(weights, 40000u);
  EXPECT_GE(g_allocated.load(), copied);
  EXPECT_LT(g_allocated.load(), copied + targets) << "the nodes are " << copied << " bytes, the targets " << targets
                                                  << ", the weights " << weights << ", the motion " << motion;
  // A copy of the graph shares the mapping; changing its motion copies it, not the file.
  MotionGraph c = h;
  EXPECT_EQ(std::as_const(c).motion.rotations.data(), std::as_const(h).motion.rotations.data());
  c.motion.rotations[0] = glm::dquat(0, 1, 0, 0);
  EXPECT_FALSE(c.motion.rotations.is_view());
  EXPECT_TRUE(std::as_const(h).motion.rotations.is_view());
  EXPECT_EQ(std::as_const(h).motion.rotations[0], g.motion.rotations[0]);
}

TEST(GraphIo, AGraphCutShortWhileInUseSaysSo) {
  const MotionGraph g = long_graph();
  gmg::testing::TempDir dir;
  const std::string path = dir.file("g.gmg");
  graph_save(path, g);
  const MotionGraph h = graph_load(path);
  h.check_unchanged();
  ASSERT_EQ(::truncate(path.c_str(), 4096), 0);
  // Every sample past the cut would have raised SIGBUS; they read as zeros now.
  double sum = 0.0;
  for (const glm::dquat& q : h.motion.rotations) sum += q.w * q.w;
  EXPECT_LT(sum, static_cast<double>(h.motion.rotations.size()));
  try {
    h.check_unchanged();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": changed while in use", 0), 0u) << e.what();
  }
}

TEST(GraphIo, SaveLoadRoundTrip) {
  const MotionGraph g = two_clip_graph();
  gmg::testing::TempDir dir;
  const std::string path = dir.file("g.gmg");
  graph_save(path, g);
  const MotionGraph h = graph_load(path);
  EXPECT_EQ(h.frame_count(), g.frame_count());
  EXPECT_EQ(h.graph.edge_count(), g.graph.edge_count());
  ASSERT_GT(g.key_sketch.axes, 0);
  EXPECT_EQ(h.key_sketch.axes, g.key_sketch.axes);
  EXPECT_EQ(h.key_sketch.basis, g.key_sketch.basis);
  EXPECT_EQ(h.key_sketch.scale, g.key_sketch.scale);
  EXPECT_EQ(h.key_sketch.values, g.key_sketch.values);
  EXPECT_EQ(h.node(150).keyword, "big");
  EXPECT_EQ(h.clips[1].name, "b.bvh");
  EXPECT_EQ(h.params.l_pn, g.params.l_pn);
  EXPECT_EQ(h.motion.rotations, g.motion.rotations);
  for (int f = 0; f < g.frame_count(); ++f) {
    EXPECT_EQ(h.node(f).kinds, g.node(f).kinds);
    EXPECT_EQ(h.node(f).keyword, g.node(f).keyword);
    std::vector<std::tuple<std::size_t, double>> a, b;
    for (const GraphEdge e : g.graph.out_edges(static_cast<GraphVertex>(f)))
      a.emplace_back(g.graph.target(e), g.weight(e));
    for (const GraphEdge e : h.graph.out_edges(static_cast<GraphVertex>(f)))
      b.emplace_back(h.graph.target(e), h.weight(e));
    EXPECT_EQ(a, b) << "frame " << f;
  }
  EXPECT_EQ(h.params.max_transitions, g.params.max_transitions);
  const GraphStats a = graph_stats(g), b = graph_stats(h);
  EXPECT_EQ(a.unnatural_edges, b.unnatural_edges);
  EXPECT_EQ(a.onset_nodes, b.onset_nodes);
}

// The SMPL-X body (shape and per-frame face; format 5 on) is the section before the motion, empty
// for a graph of BVH references: both load exactly, the payloads agree up to the body, and the face
// starts on a page boundary like the other large arrays. The motion is the last section (format 7):
// frames per block and each block's checksum, where the file's checksum stops, then (format 9) the
// key poses, the rotations and the translations, each on a page boundary.
TEST(GraphIo, TheBodyComesBeforeTheMotion) {
  MotionGraph g = two_clip_graph();
  gmg::testing::TempDir dir;
  // Format 11, whose body is the last section before the motion (format 12 puts the face speech
  // between them: tests/graph/test_graph_face_section.cpp).
  graph_save(dir.file("plain.gmg"), g, 11);
  const std::string plain = read_file_bytes(dir.file("plain.gmg"));
  EXPECT_EQ(plain[8], 11);
  EXPECT_FALSE(graph_load(dir.file("plain.gmg")).body.has_face());

  g.body.expression_dims = 2;
  for (int f = 0; f < g.frame_count(); ++f)
    g.body.expressions.insert(g.body.expressions.end(), {0.5 * f + 0.25, -1.0 / (f + 1)});
  g.body.betas = {1.25, -0.75, 3.0};
  g.body.gender = "female";
  g.body.model = "smplx2020";
  graph_save(dir.file("body.gmg"), g, 11);
  const std::string bytes = read_file_bytes(dir.file("body.gmg"));
  EXPECT_EQ(bytes[8], 11);
  const MotionGraph h = graph_load(dir.file("body.gmg"));
  EXPECT_EQ(h.body.expression_dims, 2);
  EXPECT_EQ(h.body.expressions, g.body.expressions);
  EXPECT_EQ(h.body.betas, g.body.betas);
  EXPECT_EQ(h.body.gender, "female");
  EXPECT_EQ(h.body.model, "smplx2020");

  // After the header (magic, version, payload size, the checksum's extent: 28 bytes) the two files
  // are the same bytes up to the body's first field, its u32 face coefficient count (0 without a
  // body, 2 here).
  constexpr std::size_t kHeader = 28;
  std::size_t m = kHeader;
  while (m < plain.size() && plain[m] == bytes[m]) ++m;
  ASSERT_LT(m + 4, plain.size());
  EXPECT_EQ(plain.compare(m, 4, std::string(4, '\0')), 0);
  EXPECT_EQ(bytes.compare(m, 4, std::string("\x02\0\0\0", 4)), 0);
  // Then the face's u64 value count, zero padding to the next 4096-byte boundary of the file, the
  // face's doubles there; without a body: no values, then betas (u64 count, doubles), gender and
  // model (u32 lengths, characters).
  const std::size_t face_at = (m + 4 + 8 + 4095) / 4096 * 4096;
  const std::string face(reinterpret_cast<const char*>(g.body.expressions.data()),
                         g.body.expressions.size() * sizeof(double));
  EXPECT_EQ(bytes.find(face), face_at);
  const std::size_t frames = static_cast<std::size_t>(g.frame_count()), joints = g.motion.skeleton.joints.size();
  auto bytes_of = [](const void* p, std::size_t n) { return std::string(static_cast<const char*>(p), n); };
  auto u64_at = [](const std::string& file, std::size_t at) {
    std::uint64_t v = 0;
    std::memcpy(&v, file.data() + at, 8);
    return v;
  };
  // The motion from `at` on: 64 frames a block, the blocks' count and checksums (each that of
  // its frames' rotations, then their translations), the end of what the file's checksum covers
  // (the header's last field); then the key poses', the rotations' and the translations' count,
  // padding and values; then the checksum.
  auto expect_motion_at = [&](const std::string& file, std::size_t at) {
    ASSERT_LT(at + 12, file.size());
    EXPECT_EQ(file.compare(at, 4, std::string("\x40\0\0\0", 4)), 0);
    const std::size_t blocks = (frames + 63) / 64;
    ASSERT_EQ(u64_at(file, at + 4), blocks);
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t first = b * 64, n = std::min<std::size_t>(64, frames - first);
      Checksum c;
      c.add(g.motion.rotations.data() + first * joints, n * joints * sizeof(glm::dquat));
      c.add(g.motion.translations.data() + first * joints, n * joints * sizeof(glm::dvec3));
      EXPECT_EQ(u64_at(file, at + 12 + 8 * b), c.value()) << b;
    }
    const std::size_t summed_end = at + 12 + 8 * blocks;
    EXPECT_EQ(u64_at(file, 20), summed_end - kHeader);
    EXPECT_EQ(u64_at(file, file.size() - 8), checksum_of(file.data() + kHeader, summed_end - kHeader));
    ASSERT_GT(g.key_poses.size(), 0u);
    EXPECT_EQ(u64_at(file, summed_end), g.key_poses.size());
    const std::size_t keys_at = (summed_end + 8 + 4095) / 4096 * 4096;
    const std::string keys = bytes_of(g.key_poses.data(), g.key_poses.size() * sizeof(double));
    EXPECT_EQ(file.compare(keys_at, keys.size(), keys), 0);
    EXPECT_EQ(u64_at(file, keys_at + keys.size()), frames * joints);
    const std::size_t rotations_at = (keys_at + keys.size() + 8 + 4095) / 4096 * 4096;
    const std::string rotations = bytes_of(g.motion.rotations.data(), frames * joints * sizeof(glm::dquat));
    EXPECT_EQ(file.compare(rotations_at, rotations.size(), rotations), 0);
    const std::size_t count_at = rotations_at + rotations.size();
    EXPECT_EQ(u64_at(file, count_at), frames * joints);
    const std::size_t translations_at = (count_at + 8 + 4095) / 4096 * 4096;
    const std::string translations = bytes_of(g.motion.translations.data(), frames * joints * sizeof(glm::dvec3));
    EXPECT_EQ(file.compare(translations_at, translations.size(), translations), 0);
    EXPECT_EQ(file.size(), translations_at + translations.size() + 8);
  };
  expect_motion_at(plain, face_at + 8 + 4 + 4);
  expect_motion_at(bytes, face_at + face.size() + 8 + 3 * sizeof(double) + 4 + 6 + 4 + 9);

  // A face that does not cover the frames is refused, even behind a valid checksum.
  MotionGraph bad = g;
  bad.body.expressions.pop_back();
  graph_save(dir.file("bad.gmg"), bad);
  try {
    graph_load(dir.file("bad.gmg"));
    ADD_FAILURE() << "a face shorter than the frames was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the face disagrees with frames x coefficients"), std::string::npos)
        << e.what();
  }
}

// MotionCheck::OnUse: the load leaves the motion's values to graph_check_frames, which checks the
// blocks of 64 frames a range touches, once each, and names the file and the first bad frame. A
// graph that lacks its reference facts (computed from every frame where used) is checked whole.
TEST(GraphIo, MotionCheckedOnUseIsCheckedBlockByBlock) {
  gmg::testing::TempDir dir;
  const std::string path = dir.file("hand.gmg");
  MotionGraph g = legged_graph();  // 210 frames: blocks 0-63, 64-127, 128-191, 192-209
  ASSERT_EQ(g.frame_count(), 210);
  const std::size_t joints = g.motion.skeleton.joints.size();
  g.motion.rotations[100 * joints + 1] = glm::dquat(2.0, 0.0, 0.0, 0.0);  // under a valid checksum
  graph_save(path, g);
  const std::string bad_frame = "frame 100 holds a value that is not finite or not a unit rotation";
  const std::string full_error = gmg::testing::error_of([&] { graph_load(path); });
  EXPECT_NE(full_error.find("hand.gmg: byte "), std::string::npos) << full_error;
  EXPECT_NE(full_error.find(bad_frame), std::string::npos) << full_error;

  const MotionGraph h = graph_load(path, MotionCheck::OnUse);
  ASSERT_NE(h.unchecked_motion, nullptr);
  EXPECT_EQ(h.unchecked_motion->checked, std::vector<std::uint8_t>(4, 0));
  graph_check_frames(h, -50, 63);  // clamped to the graph: block 0
  EXPECT_EQ(h.unchecked_motion->checked, std::vector<std::uint8_t>({1, 0, 0, 0}));
  graph_check_frames(h, 180, 1000);  // blocks 2 and 3
  EXPECT_EQ(h.unchecked_motion->checked, std::vector<std::uint8_t>({1, 0, 1, 1}));
  EXPECT_EQ(gmg::testing::error_of([&] { graph_check_frames(h, 120, 130); }),
            path + ": damaged graph file: " + bad_frame);
  EXPECT_EQ(gmg::testing::error_of([&] { graph_check_frames(h, 100, 100); }),
            path + ": damaged graph file: " + bad_frame);
  EXPECT_EQ(h.unchecked_motion->checked, std::vector<std::uint8_t>({1, 0, 1, 1}));
  EXPECT_EQ(h.motion.rotations[100 * joints + 1], glm::dquat(2.0, 0.0, 0.0, 0.0));  // read as written

  // A graph built in memory, or loaded whole, has nothing left to check.
  EXPECT_EQ(g.unchecked_motion, nullptr);
  graph_check_frames(g, 0, 209);
  graph_save(dir.file("sound.gmg"), legged_graph());
  EXPECT_EQ(graph_load(dir.file("sound.gmg")).unchecked_motion, nullptr);

  // Without reference facts the assembly computes them from every frame: the load checks all.
  MotionGraph bare = g;
  bare.capture = CaptureFacts{};
  bare.beat_cost = Samples<float>();
  graph_save(path, bare);
  EXPECT_NE(gmg::testing::error_of([&] { graph_load(path, MotionCheck::OnUse); }).find(bad_frame), std::string::npos);
  bare.motion.rotations[100 * joints + 1] = glm::dquat(1.0, 0.0, 0.0, 0.0);
  graph_save(path, bare);
  EXPECT_EQ(graph_load(path, MotionCheck::OnUse).unchecked_motion, nullptr);
}

// Format 9 keeps the key poses after the part the file's checksum covers, with a checksum per key
// in it. MotionCheck::OnLoad checks them all; MotionCheck::OnUse leaves each to
// graph_check_key_poses, which checks the keys a range asks for, once each, and names the file,
// the key and its frame: a value that is not finite behind a valid checksum, or a byte changed in
// the file, which no load notices until the key is read.
TEST(GraphIo, KeyPosesCheckedOnUseAreCheckedKeyByKey) {
  gmg::testing::TempDir dir;
  const std::string path = dir.file("keys.gmg");
  MotionGraph g = legged_graph();
  const std::size_t dims = static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton));
  const std::size_t keys = g.keys.size();
  ASSERT_GE(keys, 4u);
  ASSERT_EQ(g.key_poses.size(), keys * dims);
  const std::size_t bad = 2;
  const std::string where = "the junction pose of key node 2 (frame " + std::to_string(g.keys[bad]) + ")";
  MotionGraph nan_pose = g;
  nan_pose.key_poses[bad * dims + 5] = std::numeric_limits<double>::quiet_NaN();
  graph_save(path, nan_pose);
  const std::string load_error = gmg::testing::error_of([&] { graph_load(path); });
  EXPECT_NE(load_error.find("keys.gmg: byte "), std::string::npos) << load_error;
  EXPECT_NE(load_error.find(where + " holds a value that is not finite"), std::string::npos) << load_error;

  const MotionGraph h = graph_load(path, MotionCheck::OnUse);
  ASSERT_NE(h.unchecked_key_poses, nullptr);
  EXPECT_EQ(h.unchecked_key_poses->checked, std::vector<std::uint8_t>(keys, 0));
  graph_check_key_poses(h, 0, 1);
  std::vector<std::uint8_t> expected(keys, 0);
  expected[0] = expected[1] = 1;
  EXPECT_EQ(h.unchecked_key_poses->checked, expected);
  graph_check_key_poses(h, 3, keys + 10);  // clamped to the keys
  for (std::size_t k = 3; k < keys; ++k) expected[k] = 1;
  EXPECT_EQ(h.unchecked_key_poses->checked, expected);
  const std::string not_finite = path + ": damaged graph file: " + where + " holds a value that is not finite";
  EXPECT_EQ(gmg::testing::error_of([&] { graph_check_key_poses(h, 1, 2); }), not_finite);
  EXPECT_EQ(gmg::testing::error_of([&] { graph_check_key_poses(h, 2, 2); }), not_finite);
  EXPECT_EQ(h.unchecked_key_poses->checked, expected);

  // A byte changed among a key's pose in the file: its own checksum says so, the file's does not.
  graph_save(path, g);
  std::string bytes = read_file_bytes(path);
  const std::string pose(reinterpret_cast<const char*>(g.key_poses.data() + bad * dims), dims * sizeof(double));
  const std::size_t at = bytes.find(pose);
  ASSERT_NE(at, std::string::npos);
  bytes[at + 17] = static_cast<char>(bytes[at + 17] ^ 0x01);
  gmg::testing::write_text(path, bytes);
  const std::string damaged = gmg::testing::error_of([&] { graph_load(path); });
  EXPECT_EQ(damaged, path + ": graph file is damaged (checksum mismatch)");
  const MotionGraph d = graph_load(path, MotionCheck::OnUse);
  graph_check_key_poses(d, 0, 1);
  EXPECT_EQ(gmg::testing::error_of([&] { graph_check_key_poses(d, 0, keys - 1); }),
            path + ": graph file is damaged (checksum mismatch in " + where + ")");

  // A sound file loaded whole, a graph built in memory and a file of format 8 (its key poses under
  // the file's checksum, checked by every load) leave nothing to check, and read the same poses.
  graph_save(path, g);
  const MotionGraph whole = graph_load(path);
  EXPECT_EQ(whole.unchecked_key_poses, nullptr);
  EXPECT_EQ(whole.key_poses, g.key_poses);
  EXPECT_EQ(g.unchecked_key_poses, nullptr);
  graph_check_key_poses(g, 0, keys - 1);
  graph_save(path, g, 8);
  const MotionGraph eight = graph_load(path, MotionCheck::OnUse);
  EXPECT_EQ(eight.unchecked_key_poses, nullptr);
  EXPECT_EQ(eight.key_poses, g.key_poses);
  graph_save(path, nan_pose, 8);
  EXPECT_NE(
      gmg::testing::error_of([&] { graph_load(path, MotionCheck::OnUse); }).find("a key pose value is not finite"),
      std::string::npos);
}

TEST(GraphIo, LoadRejectsWrongDamagedAndTruncatedFiles) {
  const MotionGraph g = two_clip_graph();
  gmg::testing::TempDir dir;
  const std::string path = dir.file("g.gmg");
  graph_save(path, g);
  const std::string bytes = read_file_bytes(path);
  auto expect_error = [&](const std::string& content, const std::string& fragment) {
    const std::string p = dir.file("bad.gmg");
    gmg::testing::write_text(p, content);
    try {
      graph_load(p);
      ADD_FAILURE() << "accepted: " << fragment;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("bad.gmg"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_error("HIERARCHY\nROOT x", "not a gmg graph file");
  expect_error(bytes.substr(0, bytes.size() / 2), "truncated");
  // A byte changed in the part the file's checksum covers, or anywhere (here the middle, in the
  // padding before the key poses, which follow the checksummed part).
  std::string flipped = bytes;
  flipped[40] = static_cast<char>(flipped[40] ^ 0x40);
  expect_error(flipped, "checksum");
  flipped = bytes;
  flipped[bytes.size() / 2] = static_cast<char>(flipped[bytes.size() / 2] ^ 0x40);
  expect_error(flipped, "damaged");
  std::string version = bytes;
  version[8] = 13;
  expect_error(version, "version 13");
  // Files of the earlier formats (3: no key poses, unaligned arrays; 4: no body; 5: no reference
  // facts; 6: another checksum) are refused before anything else is read, with the advice to
  // rebuild them.
  for (char old : {3, 4, 5, 6}) {
    version[8] = old;
    expect_error(version, std::string("graph file format version ") + char('0' + old) +
                              ", this gmg reads versions 7 to 12: rebuild it with 'gmg build'");
  }
}

// A format 10 file whose version field says 9 (a version this gmg reads) fails a field's check as
// format 9 reads it; the error says which version it read the file as and which versions it reads,
// so a damaged version field is not taken for damage elsewhere. A format 10 file's error has no
// such note.
TEST(GraphIo, AnOlderVersionFieldIsNamedWhenTheFileDoesNotReadAsThatVersion) {
  gmg::testing::TempDir dir;
  const std::string path = dir.file("g.gmg");
  graph_save(path, two_clip_graph());
  std::string bytes = read_file_bytes(path);
  ASSERT_EQ(bytes[8], 12);
  bytes[8] = 9;
  gmg::testing::write_text(path, bytes);
  const std::string error = gmg::testing::error_of([&] { graph_load(path); });
  EXPECT_EQ(error.rfind(path + ": byte ", 0), 0u) << error;
  EXPECT_NE(error.find(": damaged graph file: "), std::string::npos) << error;
  const std::string note = " (read as format version 9, which its header gives; this gmg reads versions 7 to 12)";
  ASSERT_GE(error.size(), note.size());
  EXPECT_EQ(error.substr(error.size() - note.size()), note) << error;

  // The same damage read as format 12: a field's check fails without the note.
  bytes[8] = 12;
  const std::size_t flags = bytes.size() / 2;  // in the padding before the key poses
  bytes[flags] = static_cast<char>(bytes[flags] ^ 0x40);
  gmg::testing::write_text(path, bytes);
  const std::string current = gmg::testing::error_of([&] { graph_load(path); });
  EXPECT_NE(current.find("damaged"), std::string::npos) << current;
  EXPECT_EQ(current.find("read as format version"), std::string::npos) << current;
}

TEST(GraphIo, ExportsDotAndGraphml) {
  const MotionGraph g = two_clip_graph();
  gmg::testing::TempDir dir;
  constexpr int kFrom = 10, kTo = 50;
  graph_write_dot(dir.file("g.dot"), g, kFrom, kTo);
  graph_write_graphml(dir.file("g.graphml"), g, kFrom, kTo);
  const std::string dot = read_file_bytes(dir.file("g.dot"));
  const std::string xml = read_file_bytes(dir.file("g.graphml"));
  EXPECT_NE(dot.find("digraph"), std::string::npos);
  EXPECT_NE(dot.find("big"), std::string::npos);
  EXPECT_NE(xml.find("<graphml"), std::string::npos);
  EXPECT_NE(xml.find("keyword"), std::string::npos);

  // Every edge with both ends in the range, and no other, with its flag and weight: (source,
  // target) as the files number them (vertex i = frame kFrom + i) to (natural, weight).
  std::map<std::pair<int, int>, std::pair<bool, double>> want;
  int transitions = 0;
  for (int f = kFrom; f < kTo; ++f)
    for (const GraphEdge e : g.graph.out_edges(static_cast<GraphVertex>(f))) {
      const int b = static_cast<int>(g.graph.target(e));
      if (b < kFrom || b >= kTo) continue;
      const bool natural = b == f + 1;
      want[{f - kFrom, b - kFrom}] = {natural, g.weight(e)};
      transitions += natural ? 0 : 1;
    }
  ASSERT_GT(transitions, 0) << "the range should hold transitions";
  // The weights are declared numbers, so that readers (networkx, yEd, Gephi) parse them.
  EXPECT_NE(xml.find(R"(<key id="key4" for="edge" attr.name="weight" attr.type="double" />)"), std::string::npos);
  const std::regex edge(R"re(<edge id="e\d+" source="n(\d+)" target="n(\d+)">\s*)re"
                        R"re(<data key="key3">(\d)</data>\s*<data key="key4">([^<]+)</data>)re");
  std::map<std::pair<int, int>, std::pair<bool, double>> got;
  for (std::sregex_iterator it(xml.begin(), xml.end(), edge), end; it != end; ++it)
    got[{std::stoi((*it)[1]), std::stoi((*it)[2])}] = {(*it)[3] == "1", std::stod((*it)[4])};
  ASSERT_EQ(got.size(), want.size());
  for (const auto& [ends, value] : want) {
    ASSERT_EQ(got.count(ends), 1u) << ends.first << " -> " << ends.second;
    EXPECT_EQ(got[ends].first, value.first) << ends.first << " -> " << ends.second;
    // Each weight reads back as the same double.
    EXPECT_EQ(got[ends].second, value.second) << ends.first << " -> " << ends.second;
  }
  // The DOT file draws each transition in orange with its weight, each natural edge in gray.
  std::size_t orange = 0, gray = 0;
  for (std::size_t at = dot.find("color=orange"); at != std::string::npos; at = dot.find("color=orange", at + 1))
    ++orange;
  for (std::size_t at = dot.find("[color=gray]"); at != std::string::npos; at = dot.find("[color=gray]", at + 1))
    ++gray;
  EXPECT_EQ(orange, static_cast<std::size_t>(transitions));
  EXPECT_EQ(gray, want.size() - static_cast<std::size_t>(transitions));

  EXPECT_THROW(graph_write_dot(dir.file("x.dot"), g, 50, 500), Error);
}

// A file with a valid checksum can still be hostile (made by hand or by another tool): each
// field is checked. graph_save writes whatever it is given, so these files have valid checksums.
TEST(GraphIo, LoadChecksEveryFieldBehindTheChecksum) {
  gmg::testing::TempDir dir;
  auto error_after = [&](const std::function<void(MotionGraph&)>& damage) {
    MotionGraph g = two_clip_graph();
    damage(g);
    const std::string path = dir.file("hand.gmg");
    graph_save(path, g);
    try {
      graph_load(path);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  auto expect_refused = [&](const std::string& fragment, const std::function<void(MotionGraph&)>& damage) {
    const std::string what = error_after(damage);
    EXPECT_NE(what.find("hand.gmg: byte "), std::string::npos) << fragment << ": " << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  };
  expect_refused("frame rate inf is outside 1 to 1000 fps",
                 [](MotionGraph& g) { g.motion.fps = std::numeric_limits<double>::infinity(); });
  expect_refused("frame rate 1e+06 is outside", [](MotionGraph& g) { g.motion.fps = 1e6; });
  expect_refused("frame rate 0.5 is outside", [](MotionGraph& g) { g.motion.fps = 0.5; });
  expect_refused("clip table inconsistent", [](MotionGraph& g) { g.clips[1].frame_count = 2147483647; });
  expect_refused("clips do not cover the motion", [](MotionGraph& g) { g.clips.pop_back(); });
  expect_refused("not finite or not a unit rotation", [](MotionGraph& g) { g.motion.rotations[7].w = 2.0; });
  expect_refused("not finite or not a unit rotation",
                 [](MotionGraph& g) { g.motion.translations[3].y = std::numeric_limits<double>::quiet_NaN(); });
  expect_refused("keyword label on a frame that is not a keyword node",
                 [](MotionGraph& g) { g.graph[5].keyword = "stray"; });
  expect_refused("a node has unknown kinds", [](MotionGraph& g) { g.graph[5].kinds |= 0x80; });
  expect_refused("an edge weight is negative or not finite",
                 [](MotionGraph& g) { add_edge_to(g, 3, 90, EdgeInfo{-1.0}); });
  expect_refused("an edge weight is negative or not finite",
                 [](MotionGraph& g) { add_edge_to(g, 3, 90, EdgeInfo{std::numeric_limits<double>::quiet_NaN()}); });
  // A step to the next frame is the natural edge: its weight is 0 (the builder refuses another;
  // the weights are written to directly).
  expect_refused("an edge from frame 3 to the next frame is not its natural edge of weight 0", [](MotionGraph& g) {
    const GraphEdge first = *g.graph.out_edges(3).begin();
    ASSERT_EQ(g.graph.target(first), 4u);
    g.edge_weights[first] = 0.5;
  });
  // The key sketch: what makes its bound a bound (orthonormal rows, each zero off its part), its
  // sizes and finite values.
  expect_refused("the key sketch's basis is not orthonormal", [](MotionGraph& g) {
    for (int v = 0; v < junction_pose_dims(g.motion.skeleton); ++v)
      g.key_sketch.basis[static_cast<std::size_t>(v)] *= 1.001;
  });
  expect_refused("the key sketch's basis is not zero off its part", [](MotionGraph& g) {
    // The first row is a position axis; the pose's last value is a velocity.
    g.key_sketch.basis[static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton)) - 1] = 1e-3;
  });
  expect_refused("a key sketch value is not finite", [](MotionGraph& g) {
    std::vector<double> v(g.key_sketch.values.begin(), g.key_sketch.values.end());
    v[5] = std::numeric_limits<double>::quiet_NaN();
    g.key_sketch.values = std::move(v);
  });
  expect_refused("the key sketch's values disagree with key nodes x axes", [](MotionGraph& g) {
    std::vector<double> v(g.key_sketch.values.begin(), g.key_sketch.values.end());
    v.pop_back();
    g.key_sketch.values = std::move(v);
  });
  expect_refused("implausible key sketch axes", [](MotionGraph& g) { g.key_sketch.axes = 65; });
  expect_refused("the key sketch's scale is negative or not finite", [](MotionGraph& g) { g.key_sketch.scale = -1.0; });
  expect_refused("a key sketch without key poses", [](MotionGraph& g) { g.key_poses = Samples<double>(); });
  expect_refused("unknown or repeated channel", [](MotionGraph& g) {
    g.motion.skeleton.joints[1].channels.push_back(g.motion.skeleton.joints[1].channels.back());
  });
  expect_refused("build parameters are out of range", [](MotionGraph& g) { g.params.l_pn = 0; });
  EXPECT_EQ(error_after([](MotionGraph&) {}), "accepted");  // the control
}

// Format 6 keeps the reference facts (graph/reference_facts.h): they load exactly, the per-frame
// arrays in place from the file, and the index and transition scale the load takes from the nodes
// and edges equal those of the build, bit for bit.
// Format 7, the format before the key sketch, is still written on request and read: the same
// graph without a sketch. So are 8 and 9; no other version is written.
TEST(GraphIo, FormatSevenIsTheGraphWithoutItsSketch) {
  const MotionGraph g = two_clip_graph();
  gmg::testing::TempDir dir;
  graph_save(dir.file("g7.gmg"), g, 7);
  const std::string bytes = read_file_bytes(dir.file("g7.gmg"));
  EXPECT_EQ(bytes[8], 7);
  const MotionGraph h = graph_load(dir.file("g7.gmg"));
  EXPECT_EQ(h.key_sketch.axes, 0);
  EXPECT_TRUE(h.key_sketch.values.empty());
  EXPECT_EQ(h.key_poses, g.key_poses);
  EXPECT_EQ(h.motion.rotations, g.motion.rotations);
  EXPECT_EQ(h.graph.edge_count(), g.graph.edge_count());
  graph_save(dir.file("g8.gmg"), g, 8);
  EXPECT_EQ(read_file_bytes(dir.file("g8.gmg"))[8], 8);
  EXPECT_GT(read_file_bytes(dir.file("g8.gmg")).size(), bytes.size());
  // Format 9's row starts and targets are not aligned: they are copied, the same edges.
  graph_save(dir.file("g9.gmg"), g, 9);
  EXPECT_EQ(read_file_bytes(dir.file("g9.gmg"))[8], 9);
  const MotionGraph h9 = graph_load(dir.file("g9.gmg"));
  EXPECT_FALSE(h9.graph.row_starts().is_view());
  EXPECT_FALSE(h9.graph.targets().is_view());
  EXPECT_EQ(h9.graph.row_starts(), g.graph.row_starts());
  EXPECT_EQ(h9.graph.targets(), g.graph.targets());
  EXPECT_THROW(graph_save(dir.file("g6.gmg"), g, 6), Error);
  EXPECT_THROW(graph_save(dir.file("g13.gmg"), g, 13), Error);
  EXPECT_FALSE(std::filesystem::exists(dir.file("g6.gmg")));
}

// The file keeps each edge's natural flag after the weights (u64 count, one byte an edge): 1
// exactly for the steps to the next frame. A file whose flags say otherwise is refused even
// behind a valid checksum: a flag on a transition, or none on a step.
TEST(GraphIo, TheNaturalFlagsAreTheStepsToTheNextFrame) {
  const MotionGraph g = two_clip_graph();
  gmg::testing::TempDir dir;
  graph_save(dir.file("g.gmg"), g);
  const std::string bytes = read_file_bytes(dir.file("g.gmg"));
  const Samples<std::uint32_t>& rows = g.graph.row_starts();
  const Samples<GraphVertex>& columns = g.graph.targets();
  const std::size_t e = columns.size();
  std::string weights, flags;
  std::size_t transition = e, step = e;  // an edge of each kind
  for (std::size_t f = 0; f + 1 < rows.size(); ++f)
    for (std::size_t i = rows[f]; i < rows[f + 1]; ++i) {
      weights.append(reinterpret_cast<const char*>(&g.edge_weights[i]), sizeof(double));
      const bool natural = columns[i] == f + 1;
      flags += natural ? '\1' : '\0';
      (natural ? step : transition) = i;
    }
  ASSERT_LT(transition, e);
  ASSERT_LT(step, e);
  const std::size_t at = bytes.find(weights);
  ASSERT_NE(at, std::string::npos);
  const std::uint64_t count = e;
  ASSERT_EQ(bytes.compare(at + weights.size(), 8, std::string(reinterpret_cast<const char*>(&count), 8)), 0);
  const std::size_t flags_at = at + weights.size() + 8;
  ASSERT_EQ(bytes.compare(flags_at, e, flags), 0);

  // The same file with one flag changed and the checksum made right again.
  auto load_with_flag = [&](std::size_t edge, char flag) {
    std::string hand = bytes;
    hand[flags_at + edge] = flag;
    std::uint64_t summed = 0;
    std::memcpy(&summed, hand.data() + 20, 8);
    const std::uint64_t sum = checksum_of(hand.data() + 28, summed);
    std::memcpy(hand.data() + hand.size() - 8, &sum, 8);
    gmg::testing::write_text(dir.file("hand.gmg"), hand);
    try {
      graph_load(dir.file("hand.gmg"));
    } catch (const Error& err) {
      return std::string(err.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(load_with_flag(step, '\1'), "accepted");  // the control: the flag it had
  EXPECT_NE(load_with_flag(transition, '\1').find("is not a step to the next frame"), std::string::npos);
  EXPECT_NE(load_with_flag(step, '\0').find("to the next frame is not its natural edge"), std::string::npos);
}

// Format 10 keeps the edges' row starts and targets (u32 each) on page boundaries, read in place.
// A file whose arrays disagree is refused by the load even behind a valid checksum, naming the
// file: a target past the last frame, a row start that goes back.
TEST(GraphIo, TheEdgeArraysAreReadInPlaceAndChecked) {
  const MotionGraph g = two_clip_graph();
  gmg::testing::TempDir dir;
  graph_save(dir.file("g.gmg"), g);
  const std::string bytes = read_file_bytes(dir.file("g.gmg"));
  auto raw = [](const auto& values) {
    return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(values[0]));
  };
  const std::size_t rows_at = bytes.find(raw(g.graph.row_starts()));
  const std::size_t targets_at = bytes.find(raw(g.graph.targets()));
  ASSERT_NE(rows_at, std::string::npos);
  ASSERT_NE(targets_at, std::string::npos);
  EXPECT_EQ(rows_at % 4096, 0u);
  EXPECT_EQ(targets_at % 4096, 0u);
  const MotionGraph h = graph_load(dir.file("g.gmg"));
  EXPECT_EQ(std::as_const(h.graph).targets().data(),
            reinterpret_cast<const GraphVertex*>(h.source->data() + targets_at));

  auto load_with = [&](std::size_t at, std::uint32_t value) {
    std::string hand = bytes;
    std::memcpy(hand.data() + at, &value, sizeof value);
    std::uint64_t summed = 0;
    std::memcpy(&summed, hand.data() + 20, 8);
    const std::uint64_t sum = checksum_of(hand.data() + 28, summed);
    std::memcpy(hand.data() + hand.size() - 8, &sum, 8);
    gmg::testing::write_text(dir.file("hand.gmg"), hand);
    return gmg::testing::error_of([&] { graph_load(dir.file("hand.gmg")); });
  };
  const auto frames = static_cast<std::uint32_t>(g.frame_count());
  // The control: a target changed to another frame inside the graph (frame 0's natural edge,
  // which then no longer steps to the next frame: refused for its flag, not its range).
  EXPECT_NE(load_with(targets_at, 0).find("is not a step to the next frame"), std::string::npos);
  const std::string past = load_with(targets_at + 4, frames);
  EXPECT_NE(past.find("hand.gmg: byte "), std::string::npos) << past;
  EXPECT_NE(past.find("an edge target is outside the graph"), std::string::npos) << past;
  EXPECT_NE(load_with(rows_at + 8, 0).find("row starts are not ascending"), std::string::npos);
}

TEST(GraphIo, TheReferenceFactsRoundTrip) {
  const MotionGraph g = legged_graph();
  gmg::testing::TempDir dir;
  graph_save(dir.file("g.gmg"), g);
  const MotionGraph h = graph_load(dir.file("g.gmg"));
  ASSERT_TRUE(h.capture.known);
  EXPECT_EQ(h.capture.largest_root_step, g.capture.largest_root_step);
  EXPECT_EQ(h.capture.root_lo, g.capture.root_lo);
  EXPECT_EQ(h.capture.root_hi, g.capture.root_hi);
  EXPECT_EQ(h.capture.knee_hinges, g.capture.knee_hinges);
  EXPECT_EQ(h.capture.foot_flags, g.capture.foot_flags);
  EXPECT_EQ(h.beat_cost, g.beat_cost);
  EXPECT_TRUE(h.capture.foot_flags.is_view());
  EXPECT_TRUE(h.beat_cost.is_view());
  EXPECT_EQ(h.key_poses, g.key_poses);
  EXPECT_TRUE(h.indexed);
  EXPECT_EQ(h.keys, g.keys);
  EXPECT_EQ(h.breaks, g.breaks);
  EXPECT_EQ(h.transition_weight, g.transition_weight);
  EXPECT_GT(h.transition_weight, 0.0);

  // A graph made by hand without them saves and loads without them (they are computed where used).
  MotionGraph bare = two_clip_graph();
  bare.capture = CaptureFacts();
  bare.beat_cost = Samples<float>();
  graph_save(dir.file("bare.gmg"), bare);
  const MotionGraph b = graph_load(dir.file("bare.gmg"));
  EXPECT_FALSE(b.capture.known);
  EXPECT_TRUE(b.capture.foot_flags.empty());
  EXPECT_TRUE(b.beat_cost.empty());
  EXPECT_EQ(b.keys, bare.keys);
}

// Each value of the reference facts is checked behind the checksum, as the assembly and the
// planner use it; the error names the file and the byte.
TEST(GraphIo, LoadChecksTheReferenceFacts) {
  gmg::testing::TempDir dir;
  const std::string path = dir.file("hand.gmg");
  auto expect_refused = [&](const std::string& fragment, const std::function<void(MotionGraph&)>& damage) {
    MotionGraph g = legged_graph();
    damage(g);
    graph_save(path, g);
    try {
      graph_load(path);
      ADD_FAILURE() << "accepted: " << fragment;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("hand.gmg: byte "), std::string::npos) << what;
      EXPECT_NE(what.find("damaged graph file: " + fragment), std::string::npos) << what;
    }
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_refused("the largest root step is negative or not finite",
                 [](MotionGraph& g) { g.capture.largest_root_step = -0.5; });
  expect_refused("the largest root step is negative or not finite",
                 [&](MotionGraph& g) { g.capture.largest_root_step = nan; });
  expect_refused("the root's extent is not finite or its low end lies above its high end",
                 [](MotionGraph& g) { std::swap(g.capture.root_lo, g.capture.root_hi); });
  expect_refused("the root's extent is not finite or its low end lies above its high end",
                 [](MotionGraph& g) { g.capture.root_hi.z = std::numeric_limits<double>::infinity(); });
  expect_refused("the reference facts describe 1 legs, its skeleton has 2",
                 [](MotionGraph& g) { g.capture.knee_hinges.pop_back(); });
  expect_refused("the reference facts are unknown but describe legs", [](MotionGraph& g) { g.capture.known = false; });
  expect_refused("a knee hinge is not a unit axis",
                 [](MotionGraph& g) { g.capture.knee_hinges[0] = glm::dvec3(0.0, 2.0, 0.0); });
  expect_refused("a knee hinge is not a unit axis", [&](MotionGraph& g) { g.capture.knee_hinges[1].y = nan; });
  expect_refused("foot contacts disagree with the frame count",
                 [](MotionGraph& g) { g.capture.foot_flags.vec().pop_back(); });
  expect_refused("a foot contact has bits of no leg", [](MotionGraph& g) { g.capture.foot_flags[7] |= 0x10; });
  expect_refused("beat end costs disagree with the frame count", [](MotionGraph& g) { g.beat_cost.vec().pop_back(); });
  expect_refused("beat end costs disagree with the frame count",
                 [](MotionGraph& g) { g.beat_cost = Samples<float>(); });
  expect_refused("a beat end cost is not a number from 0 to 1", [](MotionGraph& g) { g.beat_cost[3] = 1.5f; });
  expect_refused("a beat end cost is not a number from 0 to 1",
                 [](MotionGraph& g) { g.beat_cost[3] = std::numeric_limits<float>::quiet_NaN(); });

  // The flag that says whether the facts are known is a byte, 0 or 1: the byte before the largest
  // root step and the root's extent, set to 2 under a valid checksum.
  const MotionGraph g = legged_graph();
  graph_save(path, g);
  std::string bytes = read_file_bytes(path);
  std::string facts(reinterpret_cast<const char*>(&g.capture.largest_root_step), sizeof(double));
  facts.append(reinterpret_cast<const char*>(&g.capture.root_lo), sizeof(glm::dvec3));
  facts.append(reinterpret_cast<const char*>(&g.capture.root_hi), sizeof(glm::dvec3));
  const std::size_t at = bytes.find(facts);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(bytes[at - 1], 1);
  bytes[at - 1] = 2;
  // The checksum covers as many payload bytes as the header's last field says (the header: magic,
  // version, payload size, that field).
  const std::size_t header = 8 + 4 + 8 + 8;
  std::uint64_t summed = 0;
  std::memcpy(&summed, bytes.data() + header - 8, 8);
  const std::uint64_t sum = checksum_of(bytes.data() + header, summed);
  bytes.replace(bytes.size() - 8, 8, reinterpret_cast<const char*>(&sum), 8);
  gmg::testing::write_text(path, bytes);
  try {
    graph_load(path);
    ADD_FAILURE() << "a known flag of 2 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the reference facts are neither known nor unknown"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace gmg
