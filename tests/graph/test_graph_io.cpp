// Graph files: the save/load round trip, the layout of the sections, older formats, and the arrays
// a load reads in place from the file (the refusals: test_graph_load_checks.cpp).
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

// Format 11 keeps the layers: the reference's up axis, the lower joints named at build, the stance
// of every frame and the capture's spikes, exactly. Format 10 has none of them: read back, the
// axis is Y and the stance unknown (a reenactment computes it from the motion).
TEST(GraphIo, TheLayersRoundTripInFormat11) {
  MotionGraph g = two_clip_graph();
  const std::size_t n = static_cast<std::size_t>(g.frame_count());
  g.up = UpAxis::Z;
  g.lower_joints = {g.motion.skeleton.joints[0].name};
  g.stance.known = true;
  g.stance.leg_length = 0.875;
  g.stance.still_speed = 0.0625f;
  std::vector<float> pose(n * kStanceDims), place(n * 2), speed(n);
  std::vector<std::uint8_t> planted(n), spikes(n);
  for (std::size_t f = 0; f < n; ++f) {
    for (int d = 0; d < kStanceDims; ++d) pose[f * kStanceDims + static_cast<std::size_t>(d)] = 0.125f * d - 0.01f * f;
    place[2 * f] = 0.5f * f;
    place[2 * f + 1] = -0.25f * f;
    speed[f] = 0.001f * f;
    planted[f] = f % 3 == 0;
    spikes[f] = f == 17 ? 1 : 0;
  }
  g.stance.pose = pose;
  g.stance.place = place;
  g.stance.speed = speed;
  g.stance.planted = planted;
  g.spikes = spikes;
  TempDir dir;
  graph_save(dir.file("g.gmg"), g);
  const MotionGraph h = graph_load(dir.file("g.gmg"));
  EXPECT_EQ(h.up, UpAxis::Z);
  EXPECT_EQ(h.lower_joints, g.lower_joints);
  EXPECT_TRUE(h.stance.known);
  EXPECT_EQ(h.stance.leg_length, 0.875);
  EXPECT_EQ(h.stance.still_speed, 0.0625f);
  EXPECT_EQ(h.stance.pose, g.stance.pose);
  EXPECT_EQ(h.stance.place, g.stance.place);
  EXPECT_EQ(h.stance.speed, g.stance.speed);
  EXPECT_EQ(h.stance.planted, g.stance.planted);
  EXPECT_EQ(h.spikes, g.spikes);

  graph_save(dir.file("g10.gmg"), g, 10);
  EXPECT_EQ(read_file_bytes(dir.file("g10.gmg"))[8], 10);
  const MotionGraph old = graph_load(dir.file("g10.gmg"));
  EXPECT_EQ(old.up, UpAxis::Y);
  EXPECT_TRUE(old.lower_joints.empty());
  EXPECT_FALSE(old.stance.known);
  EXPECT_TRUE(old.spikes.empty());
  EXPECT_EQ(old.motion.rotations, g.motion.rotations);

  // A lower joint the skeleton lacks, or an unknown axis, is refused behind a valid checksum.
  MotionGraph bad = g;
  bad.lower_joints = {"no_such_joint"};
  graph_save(dir.file("bad.gmg"), bad);
  EXPECT_NE(error_of([&] { graph_load(dir.file("bad.gmg")); }).find("a lower joint is not a joint of its skeleton"),
            std::string::npos);
}

}  // namespace
}  // namespace gmg
