// One exit-code rule for every subcommand, and messages that say what is wrong with the value
// given: 2 when the command line is wrong, decided from its text before any file is read (a value
// out of range or of the wrong form, an output whose extension names no format); 1 when a file
// cannot be read or is refused, or the work fails (batch: 1 a clip failed, 2 it could not start).
#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/synth/synth.h"
#include "tests/cli/cli_run.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A reference clip (ref.bvh, ref.wav, ref.tsv, its graph ref.gmg and ref.npz) and a new speech
// (new.wav), made once.
class Messages : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>();
    SynthSpec s;
    s.duration_s = 8.0;
    s.seed = 3;
    synth_write(synth_speaker(s), dir_->path().string(), "ref");
    s.seed = 4;
    synth_write(synth_speaker(s), dir_->path().string(), "new");
    ASSERT_EQ(gmg({"build", "--motion", at("ref.bvh"), "--audio", at("ref.wav"), "-o", at("ref.gmg")}).code, 0);
    ASSERT_EQ(gmg({"convert", at("ref.bvh"), at("ref.npz")}).code, 0);
  }
  static void TearDownTestSuite() { dir_.reset(); }
  static std::string at(const std::string& name) { return dir_->file(name); }
  static testing::CliRun gmg(const std::vector<std::string>& args) { return testing::run_gmg(args); }

  // `gmg args` exits with `code`, one line naming `problem`, and writes nothing into the work folder.
  void expect(const std::vector<std::string>& args, int code, const std::string& problem) {
    std::string line;
    for (const std::string& a : args) line += a + " ";
    const testing::CliRun r = gmg(args);
    EXPECT_EQ(r.code, code) << line << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("gmg: error: ", 0), 0u) << line << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << line << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, problem)) << line << "\nshould say: " << problem << "\n" << r.err;
    EXPECT_LT(r.err.size(), 400u) << line << "\n" << r.err;
    EXPECT_TRUE(fs::is_empty(work.path())) << line;
  }
  std::string out(const std::string& name) const { return work.file(name); }

  TempDir work;
  static std::unique_ptr<TempDir> dir_;
};

std::unique_ptr<TempDir> Messages::dir_;

// Each subcommand: a wrong output extension is 2 even when every input is missing (no file was
// read), a bad value is 2, and a missing or refused file is 1.
TEST_F(Messages, EverySubcommandExitsTwoForTheCommandLineAndOneForAFile) {
  const std::string missing = out("missing");
  const std::string ext = "(its extension chooses the format)";
  expect({"build", "--motion", missing + ".bvh", "--audio", missing + ".wav", "-o", out("g.txt")}, 2,
         out("g.txt") + ": -o must be a .gmg file " + ext);
  expect({"build", "--motion", missing + ".bvh", "--audio", at("ref.wav"), "--transcript-format", "xml", "-o",
          out("g.gmg")},
         2, "--transcript-format: unknown transcript format \"xml\"");
  expect({"build", "--motion", missing + ".bvh", "--audio", at("ref.wav"), "-o", out("g.gmg")}, 1, missing + ".bvh");

  expect({"inspect", missing + ".gmg", "--dot", out("g.txt")}, 2, "--dot must be a .dot or .gv file " + ext);
  expect({"inspect", missing + ".gmg"}, 1, missing + ".gmg: cannot open");

  expect({"reenact", "--graph", missing + ".gmg", "--audio", missing + ".wav", "-o", out("o.txt")}, 2,
         "-o must be a .bvh or .npz file " + ext);
  expect({"reenact", "--graph", missing + ".gmg", "--audio", missing + ".wav", "-o", out("o.bvh"), "--report",
          out("r.bvh")},
         2, "--report must be a .json file " + ext);
  expect({"reenact", "--graph", at("ref.gmg"), "--audio", missing + ".wav", "-o", out("o.bvh")}, 1,
         missing + ".wav: cannot open");

  expect({"evaluate", "--generated", missing + ".bvh", "-o", out("m.csv")}, 2, "-o must be a .json file " + ext);
  expect({"evaluate", "--generated", missing + ".bvh", "--plot", out("p.jpg")}, 2,
         "--plot must be a .png or .svg file " + ext);
  expect({"evaluate", "--generated", at("ref.bvh"), "--hist-width", "0"}, 2,
         "--hist-width: '0' is not a number above 0");
  expect({"evaluate", "--generated", missing + ".bvh"}, 1, missing + ".bvh: cannot open");

  expect({"ablation", "--motion", missing + ".bvh", "--audio", missing + ".wav", "--csv", out("t.txt")}, 2,
         "--csv must be a .csv file " + ext);
  expect({"ablation", "--motion", at("ref.bvh"), "--audio", at("ref.wav"), "--folds", "1"}, 2,
         "--folds: '1' is not a whole number from 2 to 1000");
  expect({"ablation", "--motion", at("ref.bvh"), "--audio", at("ref.wav"), "--hist-width", "-1"}, 2,
         "--hist-width: '-1' is not a number above 0");
  expect({"ablation", "--motion", missing + ".bvh", "--audio", at("ref.wav")}, 1, missing + ".bvh: cannot open");

  expect({"analyse", "--audio", missing + ".wav", "-o", out("a.txt")}, 2, "-o must be a .json or .csv file " + ext);
  expect({"analyse", "--audio", at("new.wav"), "--fps", "0"}, 2,
         "--fps: '0' is not a frame rate above 0 and at most 1000");
  expect({"analyse", "--audio", missing + ".wav"}, 1, missing + ".wav: cannot open");

  expect({"convert", missing + ".bvh", out("o.txt")}, 2, "OUT must be a .bvh or .npz file " + ext);
  expect({"convert", missing + ".bvh", out("o.npz")}, 1, missing + ".bvh: cannot open");

  expect({"render", missing + ".bvh", "-o", out("v.avi")}, 2, "-o must be a .mp4, .mkv or .mov file " + ext);
  expect({"render", missing + ".bvh", "-o", out("v.png")}, 2, "(a .png is one frame: --still SECONDS)");
  expect({"render", missing + ".bvh", "--still", "1", "-o", out("v.mp4")}, 2, "-o must be a .png file " + ext);
  expect({"render", missing + ".bvh", "-o", out("v.mp4")}, 1, missing + ".bvh");

  expect({"synth", "-o", out("s"), "--style", "2"}, 2, "--style: '2' is not a number from 0 to 1");
  expect({"synth", "-o", at("ref.bvh")}, 1, "-o is a file, not a folder");

  expect({"config", "--set", "l_pn=0"}, 2, "--set: config key 'l_pn': 0 is out of range (1 to 10000)");
  expect({"config", "--config", missing + ".json"}, 1, missing + ".json: cannot open");

  expect({"batch", "--pool", missing, "--tests", missing, "-o", out("b"), "--jobs", "-1"}, 2,
         "--jobs: '-1' is not a whole number 0 or above");
  expect({"batch", "--pool", missing, "--tests", missing, "-o", out("b")}, 2, missing);
}

// A clip that fails in a batch that could start is 1: the batch's own rule.
TEST_F(Messages, ABatchWithAFailedClipExitsOne) {
  fs::create_directories(work.path() / "tests");
  fs::copy_file(at("new.wav"), work.path() / "tests" / "a.wav");
  testing::write_text(work.file("tests/b.tsv"), "0.1\t0.5\thello\n");  // a transcript without its audio
  const testing::CliRun r = gmg(
      {"batch", "--graph", at("ref.gmg"), "--tests", work.file("tests"), "-o", work.file("out"), "--progress", "none"});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_TRUE(fs::exists(work.file("out/a.bvh")));
}

TEST_F(Messages, BadValuesAreQuotedWithReadableBounds) {
  // Not CLI11's "Value -1 not in range 0.000000 to 1797693134862315708145274237317043567980...".
  expect({"render", at("ref.bvh"), "--still", "-1", "-o", out("s.png")}, 2,
         "--still: '-1' is not a time in seconds, 0 or above");
  // Not "--from nan --to -1: ...", a --to nobody gave.
  const testing::CliRun nan = gmg({"render", at("ref.bvh"), "--from", "nan", "-o", out("v.mp4")});
  EXPECT_EQ(nan.code, 2);
  EXPECT_TRUE(contains(nan.err, "--from: 'nan' is not a time in seconds, 0 or above")) << nan.err;
  EXPECT_FALSE(contains(nan.err, "--to")) << nan.err;
  expect({"render", at("ref.bvh"), "--to", "inf", "-o", out("v.mp4")}, 2,
         "--to: 'inf' is not a time in seconds, 0 or above");
  // Not "is not a frame number (0 or above)" for a number too large.
  expect({"inspect", at("ref.gmg"), "--dot", out("g.dot"), "--frames", "0:999999999999"}, 2,
         "--frames: 999999999999 in '0:999999999999' is beyond the 100000000 frames a graph can have");
  expect({"inspect", at("ref.gmg"), "--dot", out("g.dot"), "--frames", "0:x"}, 2,
         "--frames: 'x' in '0:x' is not a frame number (a whole number, 0 or above)");
  // A long value is quoted cut.
  expect({"synth", "-o", out("s"), "--style", std::string(5000, '9')}, 2, "--style: '99999");
}

TEST_F(Messages, AConfigValueOfTheWrongTypeIsRefusedByEveryCommand) {
  testing::write_text(work.file("c.json"), R"({"variety": [0.3]})");
  const std::string problem = "c.json: config key 'variety': expected a number, got an array ([0.3])";
  for (const std::vector<std::string>& args : {std::vector<std::string>{"config", "--config", work.file("c.json")},
                                               {"reenact", "--graph", at("ref.gmg"), "--audio", at("new.wav"), "-o",
                                                work.file("o.bvh"), "--config", work.file("c.json")},
                                               {"build", "--motion", at("ref.bvh"), "--audio", at("ref.wav"), "-o",
                                                work.file("g.gmg"), "--config", work.file("c.json")}}) {
    const testing::CliRun r = gmg(args);
    EXPECT_EQ(r.code, 1) << args[0] << ": " << r.err;
    EXPECT_TRUE(contains(r.err, problem)) << args[0] << ": " << r.err;
  }
  const testing::CliRun r = gmg({"batch", "--graph", at("ref.gmg"), "--tests", dir_->path().string(), "-o",
                                 work.file("out"), "--config", work.file("c.json")});
  EXPECT_EQ(r.code, 2) << r.err;  // a batch that cannot start
  EXPECT_TRUE(contains(r.err, problem)) << r.err;
}

TEST_F(Messages, ASkeletonTemplateThatDoesNotFitIsNamed) {
  // A two-joint template for the 22 joints of ref.npz.
  testing::write_text(work.file("small.bvh"),
                      "HIERARCHY\nROOT Hips\n{\n\tOFFSET 0 0 0\n\tCHANNELS 6 Xposition Yposition Zposition Zrotation "
                      "Xrotation Yrotation\n\tJOINT Spine\n\t{\n\t\tOFFSET 0 10 0\n\t\tCHANNELS 3 Zrotation Xrotation "
                      "Yrotation\n\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0 5 0\n\t\t}\n\t}\n}\nMOTION\nFrames: 1\nFrame "
                      "Time: 0.0333333\n0 0 0 0 0 0 0 0 0\n");
  const std::string problem =
      "ref.npz: poses.npy: 22 joints a frame, but the skeleton template " + work.file("small.bvh") + " has 2 joints";
  const testing::CliRun convert =
      gmg({"convert", at("ref.npz"), work.file("o.bvh"), "--skeleton", work.file("small.bvh")});
  EXPECT_EQ(convert.code, 1);
  EXPECT_TRUE(contains(convert.err, problem)) << convert.err;
  const testing::CliRun reenact =
      gmg({"reenact", "--reference-motion", at("ref.npz"), "--skeleton", work.file("small.bvh"), "--reference-audio",
           at("ref.wav"), "--audio", at("new.wav"), "-o", work.file("o.bvh")});
  EXPECT_EQ(reenact.code, 1);
  EXPECT_TRUE(contains(reenact.err, problem)) << reenact.err;
}

}  // namespace
}  // namespace gmg
