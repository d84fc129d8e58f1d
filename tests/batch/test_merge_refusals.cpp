// gmg batch refusing what cannot make a batch, before anything is written: a merge into one of its
// parts, a merge whose part misses an output, parts of different setups, an empty --shard, a
// --graph that is not a graph.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/files.h"
#include "engine/synth/synth.h"
#include "tests/cli/cli_run.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Every file under dir (relative path -> bytes), to show a refused command changed nothing.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out[fs::relative(e.path(), dir).string()] = read_file_bytes(e.path().string());
  return out;
}

// Two references and three test speeches, and the two parts of their batch (--shard 1/2, 2/2),
// made once; each test copies the parts it changes.
class MergeRefusals : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>();
    fs::create_directories(dir_->path() / "pool");
    fs::create_directories(dir_->path() / "tests");
    for (int i = 0; i < 2; ++i) {
      SynthSpec s;
      s.duration_s = 10.0;
      s.seed = 10 + static_cast<std::uint64_t>(i);
      synth_write(synth_speaker(s), at("pool"), "ref_" + std::to_string(i));
    }
    for (int i = 1; i <= 3; ++i) {
      SynthSpec s;
      s.duration_s = 4.0;
      s.seed = 40 + static_cast<std::uint64_t>(i);
      synth_write(synth_speaker(s), at("tests"), "t" + std::to_string(i));
      fs::remove(fs::path(at("tests")) / ("t" + std::to_string(i) + ".bvh"));  // speech only
    }
    for (const char* k : {"1", "2"})
      ASSERT_EQ(gmg({"batch", "--pool", at("pool"), "--tests", at("tests"), "-o", at(std::string("parts/p") + k),
                     "--shard", std::string(k) + "/2", "--progress", "none"})
                    .code,
                0);
    ASSERT_EQ(
        gmg({"build", "--motion", at("pool/ref_0.bvh"), "--audio", at("pool/ref_0.wav"), "-o", at("ref_0.gmg")}).code,
        0);
  }
  static void TearDownTestSuite() { dir_.reset(); }
  static std::string at(const std::string& name) { return dir_->file(name); }
  static testing::CliRun gmg(const std::vector<std::string>& args) { return testing::run_gmg(args); }

  // The parts copied into work/parts.
  void copy_parts() { fs::copy(at("parts"), work.file("parts"), fs::copy_options::recursive); }

  // A refused batch: exit 2 and one line saying `problem`.
  static void expect_refused(const testing::CliRun& r, const std::string& problem) {
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("gmg: error: ", 0), 0u) << r.err;
    EXPECT_TRUE(contains(r.err, problem)) << "should say " << problem << ": " << r.err;
  }

  TempDir work;
  static std::unique_ptr<TempDir> dir_;
};

std::unique_ptr<TempDir> MergeRefusals::dir_;

TEST_F(MergeRefusals, AnOutputThatIsHoldsOrLiesInAPartIsRefusedAndNothingChanges) {
  copy_parts();
  const std::string p1 = work.file("parts/p1"), p2 = work.file("parts/p2");
  const auto before = snapshot(work.path());
  const std::vector<std::pair<std::string, std::string>> cases = {
      {p1, "-o " + p1 + " is the part folder " + p1},           {p1 + "/", "is the part folder " + p1},
      {work.file("parts/x/../p2"), "is the part folder " + p2}, {work.file("parts"), "holds the part folder " + p1},
      {p1 + "/merged", "lies inside the part folder " + p1},
  };
  for (const auto& [out, problem] : cases) {
    const testing::CliRun r = gmg({"batch", "--merge", p1, p2, "-o", out});
    expect_refused(r, problem);
    EXPECT_TRUE(contains(r.err, "the merged batch goes into a folder of its own")) << r.err;
  }
  EXPECT_EQ(snapshot(work.path()), before);
  // Through a symbolic link to a part, too.
  fs::create_directory_symlink(p2, work.file("link"));
  expect_refused(gmg({"batch", "--merge", p1, p2, "-o", work.file("link")}), "is the part folder " + p2);
  EXPECT_EQ(snapshot(work.file("parts")), snapshot(at("parts")));
}

TEST_F(MergeRefusals, AMergeRefusedForAMissingOutputWritesNothing) {
  copy_parts();
  fs::path missing;
  for (const auto& e : fs::directory_iterator(work.file("parts/p2")))
    if (e.path().extension() == ".bvh") missing = e.path();
  ASSERT_FALSE(missing.empty());
  fs::remove(missing);
  const testing::CliRun r =
      gmg({"batch", "--merge", work.file("parts/p1"), work.file("parts/p2"), "-o", work.file("m")});
  expect_refused(r, missing.string() + " is missing");
  EXPECT_FALSE(fs::exists(work.file("m"))) << "the refused merge created its output folder";
  // Into a folder that exists: it keeps what it held, and gets nothing.
  fs::create_directories(work.file("kept"));
  write_file_atomically(work.file("kept/note.txt"), [](std::ostream& os) { os << "mine"; });
  expect_refused(gmg({"batch", "--merge", work.file("parts/p1"), work.file("parts/p2"), "-o", work.file("kept")}),
                 "is missing");
  EXPECT_EQ(snapshot(work.file("kept")), (std::map<std::string, std::string>{{"note.txt", "mine"}}));
  // With every output there, the merge writes the whole batch.
  fs::copy_file(at("parts/p2") + "/" + missing.filename().string(), missing);
  const testing::CliRun ok =
      gmg({"batch", "--merge", work.file("parts/p1"), work.file("parts/p2"), "-o", work.file("m")});
  ASSERT_EQ(ok.code, 0) << ok.err;
  for (const char* f : {"t1.bvh", "t2.bvh", "t3.bvh", "summary.csv", "summary.json", "pairs.csv"})
    EXPECT_TRUE(fs::exists(work.file(std::string("m/") + f))) << f;
}

TEST_F(MergeRefusals, PartsOfDifferentSetupsAreRefusedNamingTheDifference) {
  const std::string graph_part = work.file("g2"), params_part = work.file("s2");
  ASSERT_EQ(gmg({"batch", "--graph", at("ref_0.gmg"), "--tests", at("tests"), "-o", graph_part, "--shard", "2/2",
                 "--progress", "none"})
                .code,
            0);
  ASSERT_EQ(gmg({"batch", "--pool", at("pool"), "--tests", at("tests"), "-o", params_part, "--shard", "2/2",
                 "--progress", "none", "--set", "l_pn=7"})
                .code,
            0);
  expect_refused(gmg({"batch", "--merge", at("parts/p1"), graph_part, "-o", work.file("m")}),
                 graph_part + " (part 2/2) was made with the graph " + at("ref_0.gmg") + ", " + at("parts/p1") +
                     " (part 1/2) with a pool of 2 reference clips");
  expect_refused(gmg({"batch", "--merge", at("parts/p1"), params_part, "-o", work.file("m")}),
                 params_part + " (part 2/2) was made with parameter l_pn = 7.0, not 10.0 as " + at("parts/p1") +
                     " (part 1/2) was");
  EXPECT_FALSE(fs::exists(work.file("m")));
  EXPECT_EQ(gmg({"batch", "--merge", at("parts/p1"), at("parts/p2"), "-o", work.file("m")}).code, 0);
}

TEST_F(MergeRefusals, AnEmptyShardIsRefusedLikeAnyOtherThatIsNotKOfN) {
  for (const char* shard : {"", "0/0", "3/2"}) {
    expect_refused(gmg({"batch", "--pool", at("pool"), "--tests", at("tests"), "-o", work.file("out"), "--shard", shard,
                        "--progress", "none"}),
                   std::string("--shard expects K/N with 1 <= K <= N, got '") + shard + "'");
    EXPECT_FALSE(fs::exists(work.file("out"))) << shard;
  }
}

TEST_F(MergeRefusals, AGraphThatCannotBeUsedStopsTheBatchBeforeAnyClip) {
  write_file_atomically(work.file("bad.gmg"), [](std::ostream& os) { os << "not a graph"; });
  expect_refused(gmg({"batch", "--graph", work.file("bad.gmg"), "--tests", at("tests"), "-o", work.file("out")}),
                 work.file("bad.gmg") + ": not a gmg graph file");
  expect_refused(gmg({"batch", "--graph", at("ref_0.gmg"), "--tests", at("tests"), "-o", work.file("out"), "--set",
                      "lock_joints=NoSuchJoint"}),
                 "lock_joints names 'NoSuchJoint', which is not a joint of its skeleton");
  EXPECT_FALSE(fs::exists(work.file("out")));
}

}  // namespace
}  // namespace gmg
