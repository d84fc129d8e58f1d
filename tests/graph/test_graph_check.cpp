// Graph files loaded with MotionCheck::OnUse: the motion checked block by block and the key poses
// key by key when first read (graph/graph_check.h).
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

}  // namespace
}  // namespace gmg
