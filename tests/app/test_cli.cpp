// engine/app/cli: cli_main driven in-process: every subcommand is registered with its options,
// parse errors and engine errors map to the documented exit codes.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/app/cli.h"
#include "engine/app/config.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

struct CliRun {
  int code = -1;
  std::string out, err;
};

// Runs `gmg args...` through cli_main, capturing what it prints.
CliRun run(std::vector<std::string> args) {
  args.insert(args.begin(), "gmg");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  CliRun r;
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  r.code = cli_main(static_cast<int>(args.size()), argv.data());
  r.out = ::testing::internal::GetCapturedStdout();
  r.err = ::testing::internal::GetCapturedStderr();
  return r;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(Cli, EverySubcommandsHelpExitsZeroAndListsItsOptions) {
  // One option each subcommand must have (its own, not a shared one).
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"build", "--motion"},    {"inspect", "--graphml"},     {"reenact", "--reference-motion"},
      {"evaluate", "--truth"},  {"batch", "--pool-manifest"}, {"ablation", "--folds"},
      {"synth", "--no-motion"}, {"config", "--keys"}};
  for (const auto& [name, option] : commands) {
    const CliRun r = run({name, "--help"});
    EXPECT_EQ(r.code, 0) << name << ": " << r.err;
    EXPECT_TRUE(contains(r.out, option)) << name << ":\n" << r.out;
  }
  const CliRun top = run({"--help"});
  EXPECT_EQ(top.code, 0);
  for (const auto& [name, option] : commands) EXPECT_TRUE(contains(top.out, name)) << top.out;
}

TEST(Cli, VersionExitsZero) {
  const CliRun r = run({"--version"});
  EXPECT_EQ(r.code, 0);
  EXPECT_TRUE(contains(r.out, "gmg 0.1.0")) << r.out;
}

TEST(Cli, ParseErrorsExitNonZero) {
  const CliRun unknown = run({"config", "--no-such-option"});
  EXPECT_NE(unknown.code, 0);
  EXPECT_TRUE(contains(unknown.err, "--no-such-option")) << unknown.err;
  EXPECT_TRUE(unknown.out.empty()) << unknown.out;  // the callback did not run
  EXPECT_NE(run({"build", "--no-such-option", "x"}).code, 0);
  EXPECT_NE(run({}).code, 0);                                    // a subcommand is required
  EXPECT_NE(run({"frobnicate"}).code, 0);                        // an unknown subcommand
  EXPECT_NE(run({"reenact", "--graph", "g.gmg"}).code, 0);       // required --audio and -o missing
  EXPECT_NE(run({"synth", "-o", "x", "--style", "2"}).code, 0);  // outside 0..1
}

TEST(Cli, EngineErrorsPrintOneLineAndExitOne) {
  testing::TempDir dir;
  const std::string missing = dir.file("missing.gmg");
  const CliRun r = run({"inspect", missing});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err.rfind("gmg: error: " + missing, 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const CliRun bad_set = run({"config", "--set", "nope=1"});
  EXPECT_EQ(bad_set.code, 1);
  EXPECT_EQ(bad_set.err, "gmg: error: unknown config key 'nope' (run 'gmg config' for the list)\n");
  const CliRun mismatch = run({"build", "--motion", "a.bvh", "--motion", "b.bvh", "--audio", "a.wav", "-o", "g.gmg"});
  EXPECT_EQ(mismatch.code, 1);
  EXPECT_TRUE(contains(mismatch.err, "2 --motion but 1 --audio")) << mismatch.err;
}

TEST(Cli, ConfigPrintsWhatConfigReadsBack) {
  testing::TempDir dir;
  const CliRun printed = run({"config", "--set", "l_pn=2", "--seed", "11"});
  ASSERT_EQ(printed.code, 0) << printed.err;
  const nlohmann::json j = nlohmann::json::parse(printed.out);
  EXPECT_EQ(j["l_pn"], 2);
  EXPECT_EQ(j["seed"], 11);
  const std::string file = dir.file("c.json");
  testing::write_text(file, printed.out);
  const CliRun again = run({"config", "--config", file});
  EXPECT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(again.out, printed.out);
  const CliRun keys = run({"config", "--keys", "--set", "init=random"});
  EXPECT_EQ(keys.code, 0);
  EXPECT_TRUE(contains(keys.out, "\ninit = random  # ")) << keys.out;
  EXPECT_EQ(static_cast<std::size_t>(std::count(keys.out.begin(), keys.out.end(), '\n')), config_keys().size());
}

TEST(Cli, SynthWritesTheClipAndBatchReportsSetupErrorsWithExitTwo) {
  testing::TempDir dir;
  const CliRun s = run({"synth", "-o", dir.path().string(), "--stem", "clip", "--duration", "2", "--no-motion"});
  EXPECT_EQ(s.code, 0) << s.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "clip.wav"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "clip.tsv"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "clip.bvh"));
  // batch maps its own errors: a pool without BVH files is a setup error (2).
  const CliRun b = run({"batch", "--pool", dir.path().string(), "--tests", dir.path().string(), "-o", dir.file("out"),
                        "--progress", "none"});
  EXPECT_EQ(b.code, 2);
  EXPECT_TRUE(contains(b.err, "gmg: error: batch: the pool holds no reference clip")) << b.err;
}

}  // namespace
}  // namespace gmg
