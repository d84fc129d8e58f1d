// Graph files the load refuses: another magic or version, a damaged or truncated file, and every
// field checked behind a valid checksum, each error naming the file and the problem.
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

namespace gmg {
namespace {

using namespace gmg::testing;

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

// A format 12 file whose version field says 10 (a version this gmg reads) fails a field's check as
// format 10 reads it; the error says which version it read the file as and which versions it reads,
// so a damaged version field is not taken for damage elsewhere. A format 12 file's error has no
// such note.
TEST(GraphIo, AnOlderVersionFieldIsNamedWhenTheFileDoesNotReadAsThatVersion) {
  gmg::testing::TempDir dir;
  const std::string path = dir.file("g.gmg");
  graph_save(path, two_clip_graph());
  std::string bytes = read_file_bytes(path);
  ASSERT_EQ(bytes[8], 12);
  bytes[8] = 10;
  gmg::testing::write_text(path, bytes);
  const std::string error = gmg::testing::error_of([&] { graph_load(path); });
  EXPECT_EQ(error.rfind(path + ": byte ", 0), 0u) << error;
  EXPECT_NE(error.find(": damaged graph file: "), std::string::npos) << error;
  const std::string note = " (read as format version 10, which its header gives; this gmg reads versions 7 to 12)";
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
