// gmg batch's draw of a reference for every test clip, and a pool of the shared recordings
// (BEAT2 and ZEGGS, two skeletons) reenacting BEAT2 test clips.
#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "audio/wav.h"
#include "engine/batch/batch.h"
#include "engine/motion/bvh.h"
#include "tests/test_support.h"

namespace gmg {

// Status names in failure messages (defined in test_batch.cpp).
std::ostream& operator<<(std::ostream& os, BatchClipStatus s);

namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::write_text;

TEST(BatchDraw, IsSeededReproducibleAndNeverPairsAClipWithItself) {
  const std::vector<std::string> pool = {"a", "b", "c", "d"};
  std::vector<std::string> tests;
  tests.reserve(200);
  for (int i = 0; i < 200; ++i) tests.push_back("t" + std::to_string(1000 + i));
  tests.push_back("b");
  const auto d1 = batch_draw_references(tests, pool, 7);
  const auto d2 = batch_draw_references(tests, pool, 7);
  const auto d3 = batch_draw_references(tests, pool, 8);
  EXPECT_EQ(d1, d2);
  EXPECT_NE(d1, d3);
  std::map<std::string, int> counts;
  for (const std::string& r : d1) ++counts[r];
  EXPECT_EQ(counts.size(), 4u);                             // every reference is drawn
  for (const auto& [r, n] : counts) EXPECT_GT(n, 25) << r;  // roughly uniform (50 expected)
  EXPECT_NE(d1.back(), "b");
  EXPECT_EQ(batch_draw_references({"only"}, {"only"}, 1), std::vector<std::string>{""});
  // The draw is the documented one: mt19937_64(seed), rng() % n in test order.
  std::mt19937_64 rng(7);
  for (std::size_t i = 0; i < 10; ++i) EXPECT_EQ(d1[i], pool[rng() % 4]);
}

// Real data: pool = BEAT2 2_scott_0_1_1 (55 joints, metres) and the ZEGGS clip (75 joints, cm);
// tests = 2_scott_0_2_2 and 2_scott_0_3_3 with their TextGrids.
TEST(BatchRealData, BeatAndZeggsPool) {
  GMG_REQUIRE_SHARED_DATA();
  const fs::path data = testing::shared_data_dir();
  TempDir work;
  const std::string tm = work.file("tests.csv");
  std::string manifest = "stem,wav,transcript\n";
  for (const char* stem : {"2_scott_0_2_2", "2_scott_0_3_3"})
    manifest += std::string(stem) + "," + (data / "beat2_scott" / (std::string(stem) + ".wav")).string() + "," +
                (data / "beat2_scott" / (std::string(stem) + ".TextGrid")).string() + "\n";
  write_text(tm, manifest);

  // A seed that gives the two tests different references, so both skeletons are exercised.
  const std::vector<std::string> tests = {"2_scott_0_2_2", "2_scott_0_3_3"};
  const std::vector<std::string> pool = {"067_Speech_2_x_1_0", "2_scott_0_1_1"};
  std::uint64_t seed = 1;
  while (true) {
    const auto d = batch_draw_references(tests, pool, seed);
    if (d[0] != d[1]) break;
    ++seed;
  }

  BatchOptions o;
  o.pool_dirs = {(data / "beat2_scott").string(), (data / "zeggs").string()};
  o.test_manifests = {tm};
  o.output_dir = work.file("out");
  o.seed = seed;
  o.progress = BatchProgress::Lines;
  std::ostringstream log;
  const BatchSummary s = batch_run(o, Config{}, log);
  ASSERT_EQ(s.references.size(), 2u);  // the test WAVs in beat2_scott have no BVH: not in the pool
  ASSERT_EQ(s.clips.size(), 2u);
  EXPECT_EQ(s.failed, 0) << log.str();
  std::set<std::string> used;
  for (const BatchClipResult& c : s.clips) {
    ASSERT_EQ(c.status, BatchClipStatus::Ok) << c.test_stem << ": " << c.error;
    used.insert(c.reference_stem);
    const Motion out = bvh_read(c.output);
    const std::string ref_dir = c.reference_stem == "2_scott_0_1_1" ? "beat2_scott" : "zeggs";
    const Motion ref = bvh_read((data / ref_dir / (c.reference_stem + ".bvh")).string());
    std::string why;
    EXPECT_TRUE(skeletons_match(out.skeleton, ref.skeleton, &why)) << why;
    EXPECT_EQ(out.joint_count(), c.reference_stem == "2_scott_0_1_1" ? 55 : 75);
    EXPECT_DOUBLE_EQ(out.fps, ref.fps);
    EXPECT_EQ(out.frame_count,
              static_cast<int>(std::lround(
                  audio::read_wav((data / "beat2_scott" / (c.test_stem + ".wav")).string()).duration() * ref.fps)));
    motion_check_finite(out, c.output);
  }
  EXPECT_EQ(used.size(), 2u);
}

}  // namespace
}  // namespace gmg
