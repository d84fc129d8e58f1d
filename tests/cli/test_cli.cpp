// engine/cli/cli: cli_main driven in-process: every subcommand is registered with its options,
// parse errors and engine errors map to the documented exit codes.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/cli/cli.h"
#include "engine/config/config.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"
#include "engine/motion/motion_file.h"
#include "engine/motion/npz.h"
#include "tests/cli/cli_run.h"
#include "tests/test_support.h"
#include "text/transcript.h"

namespace gmg {
namespace {

using testing::CliRun;

CliRun run(std::vector<std::string> args) { return testing::run_gmg(std::move(args)); }

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(Cli, EverySubcommandsHelpExitsZeroAndListsItsOptions) {
  // One option each subcommand must have (its own, not a shared one).
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"build", "--motion"},    {"inspect", "--graphml"},     {"reenact", "--reference-motion"},
      {"evaluate", "--truth"},  {"batch", "--pool-manifest"}, {"ablation", "--folds"},
      {"synth", "--no-motion"}, {"config", "--keys"},         {"convert", "--npz-dtype"},
      {"render", "--still"}};
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
  // A --set that names no key is a usage error (2), not an input's (tests/cli/test_hostile_input.cpp).
  const CliRun bad_set = run({"config", "--set", "nope=1"});
  EXPECT_EQ(bad_set.code, 2);
  EXPECT_EQ(bad_set.err, "gmg: error: --set: unknown config key 'nope' (run 'gmg config --keys' for the list)\n");
}

TEST(Cli, UsageErrorsPrintOneErrorLineAndExitTwo) {
  const std::vector<std::vector<std::string>> usages = {
      {},                                                    // a subcommand is required
      {"frobnicate"},                                        // an unknown subcommand
      {"config", "--no-such-option"},                        // an unknown option
      {"reenact", "--graph", "g.gmg"},                       // required --audio and -o
      {"synth", "-o", "x", "--style", "2"},                  // outside 0..1
      {"render", "m.bvh", "-o", "v.mp4", "--view", "back"},  // not a view
      {"build", "--motion", "a.bvh", "--motion", "b.bvh", "--audio", "a.wav", "-o", "g.gmg"},  // 2 motions, 1 audio
      {"reenact", "--graph", "g.gmg", "--reference-motion", "r.bvh", "--audio", "a.wav", "-o", "o.bvh"},
  };
  for (const std::vector<std::string>& args : usages) {
    const CliRun r = run(args);
    std::string line;
    for (const std::string& a : args) line += a + " ";
    EXPECT_EQ(r.code, 2) << line << r.err;
    EXPECT_EQ(r.err.rfind("gmg: error: ", 0), 0u) << line << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << line << r.err;
    EXPECT_TRUE(r.out.empty()) << line << r.out;
  }
  const CliRun mismatch = run({"build", "--motion", "a.bvh", "--motion", "b.bvh", "--audio", "a.wav", "-o", "g.gmg"});
  EXPECT_TRUE(contains(mismatch.err, "2 --motion but 1 --audio")) << mismatch.err;
  // CLI11's own message, with where to look.
  EXPECT_EQ(run({"reenact", "--graph", "g.gmg", "-o", "x.bvh"}).err,
            "gmg: error: --audio is required (see 'gmg reenact --help')\n");
}

TEST(Cli, EveryHelpShowsTheDefaultsAndTheExitCodes) {
  const std::vector<std::pair<std::string, std::string>> defaults = {
      {"build", "--transcript-format TEXT=auto"},
      {"reenact", "--transcript-format TEXT=auto"},
      {"reenact", "(default: the config's seed, 20231009)"},
      {"evaluate", "--hist-width FLOAT=1"},
      {"batch", "--progress TEXT:{auto,lines,none}=auto"},
      {"batch", "(default: the config's seed, 20231009)"},
      {"ablation", "--folds INT=6"},
      {"synth", "--stem TEXT=synth"},
      {"config", "(default: the config's seed, 20231009)"},
      {"render", "--size TEXT=640x480"},
      {"render", "--tier TEXT"},
      {"build", "--skeleton TEXT"},
  };
  for (const auto& [name, text] : defaults) {
    const CliRun r = run({name, "--help"});
    EXPECT_EQ(r.code, 0) << name;
    EXPECT_TRUE(contains(r.out, text)) << name << ": " << text << "\n" << r.out;
    EXPECT_FALSE(contains(r.out, "=[]")) << name << ":\n" << r.out;            // an empty list is no default to show
    EXPECT_FALSE(contains(r.out, "--seed UINT=0")) << name << ":\n" << r.out;  // batch's seed is not 0 by default
    // Every --help states the exit codes, the interrupt contract included.
    EXPECT_TRUE(contains(r.out, "Exit codes: 0 success; 2 the command line is wrong, found before any file is read"))
        << r.out;
    EXPECT_TRUE(contains(r.out, "1 an input file cannot be read or is refused")) << r.out;
    EXPECT_TRUE(contains(r.out, "batch: 1 some clip failed, 2 the batch could not start")) << r.out;
    EXPECT_TRUE(contains(r.out, "interrupted by Ctrl-C (SIGINT) 130, by SIGTERM 143, by SIGHUP 129")) << r.out;
  }
}

TEST(Cli, ConfigKeysPrintShortestRoundTripNumbers) {
  const CliRun keys = run({"config", "--keys", "--set", "lambda_occ=0.1", "--set", "variety=0.30000000000000004"});
  ASSERT_EQ(keys.code, 0) << keys.err;
  EXPECT_TRUE(contains(keys.out, "\nlambda_occ = 0.1  # ")) << keys.out;
  EXPECT_TRUE(contains(keys.out, "\nvariety = 0.30000000000000004  # ")) << keys.out;  // 0.1 + 0.2, every bit kept
  EXPECT_FALSE(contains(keys.out, "0000000001")) << keys.out;
  const CliRun json = run({"config", "--set", "lambda_occ=0.1"});
  EXPECT_TRUE(contains(json.out, "\"lambda_occ\": 0.1,")) << json.out;
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
  EXPECT_TRUE(contains(b.err, "gmg: error: " + dir.path().string() + ": the pool holds no reference clip")) << b.err;
}

// ---- What the field's users have: SMPL-X .npz, FLAC, Whisper JSON, TextGrids with other tiers ----

// One synthetic clip (BVH, WAV, TSV) and its graph's counts, made once; each test feeds the same
// clip in another form and expects the same graph.
class CliFieldInputs : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<testing::TempDir>();
    const CliRun s = run({"synth", "-o", dir_->path().string(), "--stem", "clip", "--duration", "12", "--seed", "4"});
    ASSERT_EQ(s.code, 0) << s.err;
    baseline_ = counts({"--motion", file("clip.bvh"), "--audio", file("clip.wav"), "--transcript", file("clip.tsv")});
    words_ = text::read_tsv(file("clip.tsv"));
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static std::string file(const std::string& name) { return dir_->file(name); }

  // `gmg build` with these inputs, then the counts `gmg inspect --json` prints.
  static nlohmann::json counts(std::vector<std::string> inputs, const std::string& graph = "g.gmg") {
    inputs.insert(inputs.begin(), "build");
    inputs.insert(inputs.end(), {"-o", file(graph)});
    const CliRun b = run(inputs);
    EXPECT_EQ(b.code, 0) << b.err;
    const CliRun i = run({"inspect", file(graph), "--json"});
    EXPECT_EQ(i.code, 0) << i.err;
    return i.code == 0 ? nlohmann::json::parse(i.out) : nlohmann::json();
  }

  static std::unique_ptr<testing::TempDir> dir_;
  static nlohmann::json baseline_;
  static std::vector<text::Word> words_;
};

std::unique_ptr<testing::TempDir> CliFieldInputs::dir_;
nlohmann::json CliFieldInputs::baseline_;
std::vector<text::Word> CliFieldInputs::words_;

TEST_F(CliFieldInputs, InspectJsonKeysAreSnakeCaseAndTheTextKeepsItsLabels) {
  ASSERT_TRUE(baseline_.is_object());
  for (auto it = baseline_.begin(); it != baseline_.end(); ++it)
    EXPECT_TRUE(std::all_of(it.key().begin(), it.key().end(), [](char c) {
      return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
    })) << it.key();
  EXPECT_TRUE(baseline_.contains("onset_nodes"));
  EXPECT_TRUE(baseline_.contains("mean_out_degree"));
  const CliRun text = run({"inspect", file("g.gmg")});
  EXPECT_TRUE(contains(text.out, "\nonset nodes: " + baseline_["onset_nodes"].dump() + "\n")) << text.out;
  EXPECT_TRUE(contains(text.out, "\nmean out-degree: ")) << text.out;
}

TEST_F(CliFieldInputs, AnNpzMotionWithItsSkeletonBuildsTheSameGraphAndReenactWritesNpz) {
  motion_write(file("clip.npz"), motion_read(file("clip.bvh")));
  const CliRun no_template =
      run({"build", "--motion", file("clip.npz"), "--audio", file("clip.wav"), "-o", file("n.gmg")});
  EXPECT_EQ(no_template.code, 1);
  EXPECT_TRUE(contains(no_template.err, "needs a skeleton template")) << no_template.err;
  const nlohmann::json n = counts({"--motion", file("clip.npz"), "--skeleton", file("clip.bvh"), "--audio",
                                   file("clip.wav"), "--transcript", file("clip.tsv")},
                                  "n.gmg");
  for (const char* k : {"frames", "joints", "fps", "onset_nodes", "keyword_nodes"}) EXPECT_EQ(n[k], baseline_[k]) << k;

  const CliRun r = run({"reenact", "--graph", file("n.gmg"), "--audio", file("clip.wav"), "-o", file("out.npz")});
  ASSERT_EQ(r.code, 0) << r.err;
  const CliRun e = run({"evaluate", "--generated", file("out.npz"), "--skeleton", file("clip.bvh"), "--json"});
  ASSERT_EQ(e.code, 0) << e.err;
  EXPECT_EQ(nlohmann::json::parse(e.out)["frames"], motion_read(file("out.npz"), file("clip.bvh")).frame_count);
}

TEST_F(CliFieldInputs, ConvertGoesBetweenBvhAndNpzExactlyAndRefusesWhatItCannotMean) {
  // BVH -> npz (float64) -> BVH gives gmg's BVH back byte for byte.
  const CliRun norm = run({"convert", file("clip.bvh"), file("norm.bvh")});
  ASSERT_EQ(norm.code, 0) << norm.err;
  EXPECT_TRUE(contains(norm.out, "wrote " + file("norm.bvh") + ": 360 frames at 30 fps, 22 joints")) << norm.out;
  ASSERT_EQ(run({"convert", file("norm.bvh"), file("c.npz"), "--npz-dtype", "float64"}).code, 0);
  const CliRun back = run({"convert", file("c.npz"), file("back.bvh"), "--skeleton", file("clip.bvh")});
  ASSERT_EQ(back.code, 0) << back.err;
  EXPECT_EQ(read_file_bytes(file("back.bvh")), read_file_bytes(file("norm.bvh")));
  // Usage errors exit 2; an npz without a template, or an output that is the input, exit 1.
  EXPECT_EQ(run({"convert", file("clip.bvh"), file("x.npz"), "--skeleton", file("clip.bvh")}).code, 2);
  EXPECT_EQ(run({"convert", file("clip.bvh"), file("x.npz"), "--npz-dtype", "float16"}).code, 2);
  EXPECT_EQ(run({"convert", file("clip.bvh")}).code, 2);
  const CliRun no_template = run({"convert", file("c.npz"), file("x.bvh")});
  EXPECT_EQ(no_template.code, 1);
  EXPECT_TRUE(contains(no_template.err, "needs a skeleton template")) << no_template.err;
  EXPECT_EQ(run({"convert", file("norm.bvh"), file("norm.bvh")}).code, 1);
  EXPECT_FALSE(std::filesystem::exists(file("x.bvh")));
}

TEST_F(CliFieldInputs, ReenactBetasGiveTheNpzOutputItsShapeAndTheReportSaysWhere) {
  // An .npy of betas (numpy.save's format 1.0, written here by hand: magic, version, header, data).
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (3,), }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string npy = std::string("\x93NUMPY\x01\x00", 8) + static_cast<char>(header.size()) + '\0' + header;
  for (const double v : {0.5, -1.25, 2.0}) npy.append(reinterpret_cast<const char*>(&v), sizeof v);
  testing::write_text(file("betas.npy"), npy);
  const CliRun r =
      run({"reenact", "--reference-motion", file("clip.bvh"), "--reference-audio", file("clip.wav"), "--audio",
           file("clip.wav"), "--betas", file("betas.npy"), "-o", file("b.npz"), "--report", file("b.json")});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string bytes = read_file_bytes(file("b.npz"));
  EXPECT_EQ(read_betas_file(file("b.npz")), (std::vector<double>{0.5, -1.25, 2.0}));
  const nlohmann::json report = nlohmann::json::parse(read_file_bytes(file("b.json")));
  EXPECT_EQ(report["body"]["betas"], file("betas.npy"));
  EXPECT_EQ(report["body"]["face"], "none");
  // A betas file that cannot be read stops the command before any work, with no output.
  const CliRun bad = run({"reenact", "--reference-motion", file("clip.bvh"), "--reference-audio", file("clip.wav"),
                          "--audio", file("clip.wav"), "--betas", file("clip.wav"), "-o", file("no_betas.npz")});
  EXPECT_EQ(bad.code, 1);
  EXPECT_TRUE(contains(bad.err, file("clip.wav") + ": not a .npy array")) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(file("no_betas.npz")));
}

TEST_F(CliFieldInputs, AblationReadsAnNpzWithItsSkeleton) {
  NpzFloats exact = NpzFloats::Float64;  // the same rotations as the BVH's, so the same table
  npz_write(file("abl.npz"), motion_read(file("clip.bvh")), {}, exact);
  const std::vector<std::string> rest = {
      "--audio", file("clip.wav"), "--transcript", file("clip.tsv"), "--folds", "2", "--seeds",
      "1",       "--set",          "l_npaths=20"};
  std::vector<std::string> from_bvh = {"ablation", "--motion", file("clip.bvh")};
  from_bvh.insert(from_bvh.end(), rest.begin(), rest.end());
  std::vector<std::string> from_npz = {"ablation", "--motion", file("abl.npz"), "--skeleton", file("clip.bvh")};
  from_npz.insert(from_npz.end(), rest.begin(), rest.end());
  const CliRun a = run(from_bvh), b = run(from_npz);
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_EQ(b.out, a.out);
  from_npz.erase(from_npz.begin() + 3, from_npz.begin() + 5);  // without --skeleton
  const CliRun c = run(from_npz);
  EXPECT_EQ(c.code, 1);
  EXPECT_TRUE(contains(c.err, "needs a skeleton template")) << c.err;
}

TEST_F(CliFieldInputs, FlacAudioBuildsTheSameGraph) {
  if (std::system("ffmpeg -version > /dev/null 2>&1") != 0) GTEST_SKIP() << "the ffmpeg tool is absent";
  const std::string cmd =
      "ffmpeg -hide_banner -loglevel error -y -i '" + file("clip.wav") + "' '" + file("clip.flac") + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(counts({"--motion", file("clip.bvh"), "--audio", file("clip.flac"), "--transcript", file("clip.tsv")}),
            baseline_);
}

TEST_F(CliFieldInputs, WhisperJsonBuildsTheSameGraph) {
  nlohmann::json segment = {{"start", 0.0}, {"end", words_.empty() ? 0.0 : words_.back().end}};
  for (const text::Word& w : words_)
    segment["words"].push_back({{"word", " " + w.text}, {"start", w.start}, {"end", w.end}});
  testing::write_text(file("clip.json"), nlohmann::json{{"segments", {segment}}, {"language", "en"}}.dump());
  EXPECT_EQ(counts({"--motion", file("clip.bvh"), "--audio", file("clip.wav"), "--transcript", file("clip.json")}),
            baseline_);
}

TEST_F(CliFieldInputs, ATextGridTierIsChosenWithTier) {
  // Two interval tiers, neither named "words": the reader cannot guess, --tier says which.
  std::string grid = "File type = \"ooTextFile\"\nObject class = \"TextGrid\"\n\nxmin = 0\nxmax = 12\n";
  grid += "tiers? <exists>\nsize = 2\nitem []:\n";
  const std::pair<const char*, bool> tiers[] = {{"ortho", true}, {"notes", false}};
  for (const auto& [name, with_words] : tiers) {
    grid += std::string("    item []:\n        class = \"IntervalTier\"\n        name = \"") + name +
            "\"\n        xmin = 0\n        xmax = 12\n";
    const std::size_t n = with_words ? words_.size() : 1;
    grid += "        intervals: size = " + std::to_string(n) + "\n";
    for (std::size_t i = 0; i < n; ++i) {
      const text::Word w = with_words ? words_[i] : text::Word{0.0, 12.0, "x"};
      grid += "        intervals []:\n            xmin = " + format_number(w.start) +
              "\n            xmax = " + format_number(w.end) + "\n            text = \"" + w.text + "\"\n";
    }
  }
  testing::write_text(file("clip.TextGrid"), grid);
  const CliRun guess = run({"build", "--motion", file("clip.bvh"), "--audio", file("clip.wav"), "--transcript",
                            file("clip.TextGrid"), "-o", file("t.gmg")});
  EXPECT_EQ(guess.code, 1);
  EXPECT_TRUE(contains(guess.err, "\"ortho\" (IntervalTier), \"notes\" (IntervalTier)); choose one with --tier"))
      << guess.err;
  EXPECT_EQ(counts({"--motion", file("clip.bvh"), "--audio", file("clip.wav"), "--transcript", file("clip.TextGrid"),
                    "--tier", "ortho"}),
            baseline_);
}

}  // namespace
}  // namespace gmg
