// gmg batch on several machines: --shard K/N parts, --merge of their summaries, and --graph
// (one built graph, loaded once, shared by every worker).
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "engine/batch/batch.h"
#include "engine/cli/cli.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/synth/synth.h"
#include "tests/cli/cli_run.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Every file of a folder but the summaries, by name, with its bytes.
std::map<std::string, std::string> outputs(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    // Bookkeeping of the run, not outputs: summaries, pairing, the lock and the settings record.
    if (name.rfind("summary.", 0) == 0 || name == "pairs.csv" || name == ".gmg-batch.lock" || name == "batch.json")
      continue;
    out[name] = read_file_bytes(e.path().string());
  }
  return out;
}

// The rows of a pairs.csv after its header.
std::set<std::string> pair_rows(const fs::path& file) {
  std::set<std::string> rows;
  std::istringstream in(read_file_bytes(file.string()));
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) rows.insert(line);
  return rows;
}

// Two references (10 s) and seven test speeches (4 s to 7 s), made once.
class ShardData : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>();
    fs::create_directories(dir_->path() / "pool");
    fs::create_directories(dir_->path() / "tests");
    for (int i = 0; i < 2; ++i) {
      SynthSpec s;
      s.duration_s = 10.0;
      s.seed = 10 + static_cast<std::uint64_t>(i);
      synth_write(synth_speaker(s), pool(), "ref_" + std::to_string(i));
    }
    for (int i = 1; i <= 7; ++i) {
      SynthSpec s;
      s.duration_s = 3.5 + 0.5 * i;
      s.seed = 40 + static_cast<std::uint64_t>(i);
      synth_write(synth_speaker(s), tests(), "t" + std::to_string(i));
      fs::remove(fs::path(tests()) / ("t" + std::to_string(i) + ".bvh"));  // speech only
    }
  }
  static void TearDownTestSuite() { dir_.reset(); }
  static std::string pool() { return (dir_->path() / "pool").string(); }
  static std::string tests() { return (dir_->path() / "tests").string(); }

  static BatchOptions options(const fs::path& out, std::optional<BatchShard> shard = std::nullopt) {
    BatchOptions o;
    o.pool_dirs = {pool()};
    o.test_dirs = {tests()};
    o.output_dir = out.string();
    o.jobs = 2;
    o.seed = 7;
    o.reports = true;
    o.progress = BatchProgress::Quiet;
    o.shard = shard;
    return o;
  }

  static std::unique_ptr<TempDir> dir_;
};

std::unique_ptr<TempDir> ShardData::dir_;

TEST_F(ShardData, PartsTogetherWriteExactlyWhatOneRunWrites) {
  TempDir work;
  std::ostringstream log;
  const BatchSummary whole = batch_run(options(work.path() / "whole"), Config{}, log);
  ASSERT_EQ(whole.ok, 7) << log.str();
  std::map<std::string, std::string> joined;
  std::set<std::string> joined_pairs;
  std::vector<std::string> parts;
  for (int k = 1; k <= 3; ++k) {
    const fs::path out = work.path() / ("part" + std::to_string(k));
    const BatchSummary s = batch_run(options(out, BatchShard{k, 3}), Config{}, log);
    // Test clips t1..t7 in stem order: part k holds clips k-1, k+2, k+5 (from 0).
    EXPECT_EQ(s.clips.size(), k == 1 ? 3u : 2u);
    EXPECT_EQ(s.clips.front().test_stem, "t" + std::to_string(k));
    EXPECT_EQ(s.batch_clips, 7);
    for (const auto& [name, bytes] : outputs(out)) EXPECT_TRUE(joined.emplace(name, bytes).second) << name;
    for (const std::string& row : pair_rows(out / "pairs.csv")) joined_pairs.insert(row);
    // Every part records the settings of the whole batch (seed, pairing, pool, parameters).
    EXPECT_EQ(read_file_bytes((out / "batch.json").string()),
              read_file_bytes((work.path() / "whole" / "batch.json").string()));
    parts.push_back(out.string());
  }
  const std::map<std::string, std::string> single = outputs(work.path() / "whole");
  EXPECT_EQ(single.size(), 14u) << "7 BVH and 7 reports";
  EXPECT_TRUE(joined == single) << "the union of the parts' BVH and JSON files differs from one run's";
  EXPECT_EQ(joined_pairs, pair_rows(work.path() / "whole" / "pairs.csv"));

  const BatchSummary merged = batch_merge(parts, (work.path() / "merged").string(), log);
  EXPECT_EQ(merged.ok, 7);
  // The merged folder holds every part's BVH and report, byte for byte one run's, each clip's
  // output naming its copy there: one folder, ready for what comes next.
  EXPECT_TRUE(outputs(work.path() / "merged") == single) << "the merged folder lacks the parts' outputs";
  for (const BatchClipResult& c : merged.clips)
    EXPECT_EQ(c.output, (work.path() / "merged" / (c.test_stem + ".bvh")).string());
  const BatchSummary again = batch_merge(parts, (work.path() / "merged").string(), log);  // a re-run changes nothing
  EXPECT_EQ(again.ok, 7);
  EXPECT_TRUE(outputs(work.path() / "merged") == single);
  EXPECT_EQ(read_file_bytes((work.path() / "merged" / "pairs.csv").string()),
            read_file_bytes((work.path() / "whole" / "pairs.csv").string()));
  const auto a = nlohmann::json::parse(read_file_bytes((work.path() / "whole" / "summary.json").string()));
  const auto b = nlohmann::json::parse(read_file_bytes((work.path() / "merged" / "summary.json").string()));
  ASSERT_EQ(a["clips"].size(), b["clips"].size());
  for (std::size_t i = 0; i < a["clips"].size(); ++i)
    for (const char* key : {"test", "reference", "status", "frames", "fallbacks", "failures"})
      EXPECT_EQ(a["clips"][i][key], b["clips"][i][key]) << i << " " << key;
  EXPECT_EQ(a["counts"], b["counts"]);
  EXPECT_EQ(a["seed"], b["seed"]);
  EXPECT_EQ(b["parts"].size(), 3u);
  for (std::size_t i = 0; i < a["references"].size(); ++i)
    EXPECT_EQ(a["references"][i]["clips"], b["references"][i]["clips"]);
}

// The error text of batch_merge on these part folders ("" when it succeeds).
std::string merge_error(const std::vector<std::string>& parts, const fs::path& out) {
  std::ostringstream log;
  try {
    batch_merge(parts, out.string(), log);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST_F(ShardData, MergeRejectsMissingRepeatedForeignAndOverlappingParts) {
  TempDir work;
  std::ostringstream log;
  std::vector<std::string> thirds, halves;
  for (int k = 1; k <= 3; ++k) {
    thirds.push_back((work.path() / ("third" + std::to_string(k))).string());
    batch_run(options(thirds.back(), BatchShard{k, 3}), Config{}, log);
  }
  halves.push_back((work.path() / "half1").string());
  batch_run(options(halves.back(), BatchShard{1, 2}), Config{}, log);
  const fs::path out = work.path() / "out";

  EXPECT_TRUE(contains(merge_error({thirds[0], thirds[2]}, out), "missing part(s) 2/3"))
      << merge_error({thirds[0], thirds[2]}, out);
  EXPECT_TRUE(contains(merge_error({thirds[0], thirds[1], thirds[1], thirds[2]}, out), "part 2/3 is given twice"));
  EXPECT_TRUE(contains(merge_error({thirds[0], thirds[1], halves[0]}, out), "not from the same batch"));
  // A part that claims to be 3/3 but holds part 2's clips: t2 would be made twice.
  const fs::path forged = work.path() / "forged";
  fs::create_directories(forged);
  std::string text = read_file_bytes(thirds[1] + "/summary.json");
  text.replace(text.find("\"index\": 2"), 10, "\"index\": 3");
  testing::write_text((forged / "summary.json").string(), text);
  EXPECT_TRUE(contains(merge_error({thirds[0], thirds[1], forged.string()}, out), "test clip 't2' is in two parts"))
      << merge_error({thirds[0], thirds[1], forged.string()}, out);
  // A whole run's summary is no part; a folder without summary is named.
  const fs::path whole = work.path() / "whole";
  batch_run(options(whole), Config{}, log);
  EXPECT_TRUE(contains(merge_error({whole.string()}, out), "not a part's"));
  EXPECT_TRUE(contains(merge_error({thirds[0], (work.path() / "none").string()}, out), "has no summary.json"));
  EXPECT_FALSE(fs::exists(out / "summary.json")) << "a rejected merge writes nothing";
  EXPECT_EQ(merge_error(thirds, out), "");
}

TEST(BatchShard, ParsesKOfN) {
  EXPECT_EQ(parse_batch_shard("2/5").index, 2);
  EXPECT_EQ(parse_batch_shard("2/5").count, 5);
  for (const char* bad : {"0/3", "4/3", "x/3", "1/0", "3", "1.5/3", "-1/3"})
    EXPECT_THROW(parse_batch_shard(bad), Error) << bad;
}

// Exit code of `gmg args...`; *err gets what it printed on stderr.
int run_cli(std::vector<std::string> args, std::string* err = nullptr) {
  const testing::CliRun r = testing::run_gmg(std::move(args));
  if (err) *err = r.err;
  return r.code;
}

TEST_F(ShardData, GraphIsLoadedOnceAndEveryClipEqualsReenactFromIt) {
  TempDir work;
  const std::string graph = work.file("ref_0.gmg");
  ASSERT_EQ(run_cli({"build", "--motion", pool() + "/ref_0.bvh", "--audio", pool() + "/ref_0.wav", "--transcript",
                     pool() + "/ref_0.tsv", "-o", graph}),
            0);
  std::string log;
  ASSERT_EQ(run_cli({"batch", "--graph", graph, "--tests", tests(), "-o", work.file("out"), "--jobs", "2", "--seed",
                     "7", "--progress", "lines"},
                    &log),
            0)
      << log;
  std::size_t loads = 0;
  for (std::size_t at = log.find("loaded in"); at != std::string::npos; at = log.find("loaded in", at + 1)) ++loads;
  EXPECT_EQ(loads, 1u) << log;
  for (const char* t : {"t2", "t5"}) {
    ASSERT_EQ(run_cli({"reenact", "--graph", graph, "--audio", tests() + "/" + t + ".wav", "--transcript",
                       tests() + "/" + t + ".tsv", "--seed", "7", "-o", work.file(std::string(t) + ".bvh")}),
              0);
    EXPECT_EQ(read_file_bytes(work.file("out/" + std::string(t) + ".bvh")),
              read_file_bytes(work.file(std::string(t) + ".bvh")))
        << t;
  }
  EXPECT_TRUE(contains(read_file_bytes(work.file("out/pairs.csv")), "t1,ref_0"));
  // Shard and merge errors on the command line exit with 2.
  EXPECT_EQ(run_cli({"batch", "--graph", graph, "--tests", tests(), "-o", work.file("x"), "--shard", "4/3"}), 2);
  EXPECT_EQ(run_cli({"batch", "--merge", work.file("out"), "-o", work.file("y")}), 2);
  EXPECT_EQ(run_cli({"batch", "--graph", graph, "--pool", pool(), "--tests", tests(), "-o", work.file("z")}), 2);
}

}  // namespace
}  // namespace gmg
