// Control over a reenactment (engine/pipeline/control.h): --keep/--range keep an earlier output's
// frames byte for byte, --pin plays the reference's stretch at a moment, and bad requests are
// refused before any output is written.
#include <cmath>
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/assemble/layers.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/motion/bvh.h"
#include "engine/motion/rotation.h"
#include "engine/pipeline/control.h"
#include "engine/synth/synth.h"
#include "graph/graph_io.h"
#include "tests/cli/cli_run.h"
#include "tests/test_support.h"
#include "text/transcript.h"

namespace gmg {
namespace {

using namespace gmg::testing;

// The frame lines of a BVH text (everything after "Frame Time:").
std::vector<std::string> frame_lines(const std::string& path) {
  std::istringstream in(read_file_bytes(path));
  std::vector<std::string> lines;
  std::string line;
  bool frames = false;
  while (std::getline(in, line)) {
    if (frames) lines.push_back(line);
    if (line.rfind("Frame Time:", 0) == 0) frames = true;
  }
  return lines;
}

// The largest distance between m's joints (frames [m0, m0 + n)) and r's (frames [r0, r0 + n)),
// each relative to its root and turned into its root's heading (Y-up), over the joints `mask` marks.
double largest_heading_gap(const Motion& m, int m0, const Motion& r, int r0, int n) {
  const Eigen::MatrixXd pm = motion_forward_kinematics(m), pr = motion_forward_kinematics(r);
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const glm::dquat hm = glm::inverse(heading_of(m.rotation(m0 + i, 0))),
                     hr = glm::inverse(heading_of(r.rotation(r0 + i, 0)));
    const glm::dvec3 rootm(pm(m0 + i, 0), pm(m0 + i, 1), pm(m0 + i, 2)),
        rootr(pr(r0 + i, 0), pr(r0 + i, 1), pr(r0 + i, 2));
    for (int j = 1; j < m.joint_count(); ++j) {
      const glm::dvec3 a = hm * (glm::dvec3(pm(m0 + i, 3 * j), pm(m0 + i, 3 * j + 1), pm(m0 + i, 3 * j + 2)) - rootm);
      const glm::dvec3 b = hr * (glm::dvec3(pr(r0 + i, 3 * j), pr(r0 + i, 3 * j + 1), pr(r0 + i, 3 * j + 2)) - rootr);
      worst = std::max(worst, glm::length(a - b));
    }
  }
  return worst;
}

class Control : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    SynthSpec ref;
    ref.duration_s = 40;
    ref.seed = 11;
    synth_write(synth_speaker(ref), dir_->path().string(), "ref");
    SynthSpec test;
    test.duration_s = 15;
    test.seed = 12;
    synth_write(synth_speaker(test), dir_->path().string(), "test");
    ASSERT_EQ(run_gmg({"build", "--motion", file("ref.bvh"), "--audio", file("ref.wav"), "--transcript",
                       file("ref.tsv"), "-o", file("ref.gmg")})
                  .code,
              0);
    ASSERT_EQ(reenact({"--seed", "1", "-o", file("a.bvh")}).code, 0);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string file(const std::string& name) { return dir_->file(name); }
  static CliRun reenact(std::vector<std::string> more) {
    std::vector<std::string> args = {"reenact",        "--graph",      file("ref.gmg"), "--audio",
                                     file("test.wav"), "--transcript", file("test.tsv")};
    args.insert(args.end(), more.begin(), more.end());
    return run_gmg(args);
  }
  static TempDir* dir_;
};
TempDir* Control::dir_ = nullptr;

TEST_F(Control, KeptFramesAreByteIdenticalAndRangesPlannedAfresh) {
  const CliRun r = reenact({"--keep", file("a.bvh"), "--range", "5:8", "--range", "11.5:12", "--seed", "2", "-o",
                            file("b.bvh"), "--report", file("b.json")});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<std::string> a = frame_lines(file("a.bvh")), b = frame_lines(file("b.bvh"));
  ASSERT_EQ(a.size(), b.size());
  int changed = 0;
  for (std::size_t f = 0; f < a.size(); ++f) {
    const bool inside = (f >= 150 && f < 240) || (f >= 345 && f < 360);
    if (!inside) {
      EXPECT_EQ(a[f], b[f]) << "frame " << f << " is outside the ranges";
    }
    changed += inside && a[f] != b[f];
  }
  EXPECT_GT(changed, 60) << "the range 5:8 s is planned with another seed";
  const nlohmann::json rep = nlohmann::json::parse(read_file_bytes(file("b.json")));
  EXPECT_EQ(rep["control"]["kept"], nlohmann::json::parse("[[0,150],[240,345],[360,450]]"));
  EXPECT_EQ(rep["control"]["planned"], nlohmann::json::parse("[[150,240],[345,360]]"));
  EXPECT_EQ(rep["inputs"]["keep"], file("a.bvh"));
  int kept = 0, planned = 0;
  for (const auto& s : rep["subsequences"]) {
    const int start = s["start_frame"], end = start + s["target_length"].get<int>();
    const bool touches = (start < 240 && end > 150) || (start < 360 && end > 345);
    EXPECT_EQ(s["control"], touches ? "planned" : "kept") << "subsequence at frame " << start;
    (touches ? planned : kept) += 1;
  }
  EXPECT_GT(kept, 0);
  EXPECT_GT(planned, 0);
}

TEST_F(Control, TheSameSeedPlansTheRangeAsBefore) {
  // The same seed plans the range as before and the joins have nothing to take up: every value of
  // the output is the earlier one's, to the file's rounding.
  ASSERT_EQ(reenact({"--keep", file("a.bvh"), "--range", "3:9", "--seed", "1", "-o", file("same.bvh")}).code, 0);
  const Motion a = bvh_read(file("a.bvh")), same = bvh_read(file("same.bvh"));
  ASSERT_EQ(a.frame_count, same.frame_count);
  double worst = 0.0;
  for (std::size_t i = 0; i < a.rotations.size(); ++i) {
    worst = std::max(worst, rotation_angle_between(a.rotations[i], same.rotations[i]));
    worst = std::max(worst, glm::length(a.translations[i] - same.translations[i]));
  }
  EXPECT_LT(worst, 1e-5);
}

TEST_F(Control, APinInsideARangeIsPlayedAndTheRestKept) {
  const MotionGraph g = graph_load(file("ref.gmg"));
  ASSERT_EQ(
      reenact({"--keep", file("a.bvh"), "--range", "2:8", "--pin", "4=10:12", "--seed", "2", "-o", file("kp.bvh")})
          .code,
      0);
  const std::vector<std::string> a = frame_lines(file("a.bvh")), kp = frame_lines(file("kp.bvh"));
  ASSERT_EQ(a.size(), kp.size());
  for (std::size_t f = 0; f < a.size(); ++f)
    if (f < 60 || f >= 240) {
      EXPECT_EQ(a[f], kp[f]) << f;
    }
  EXPECT_LT(largest_heading_gap(bvh_read(file("kp.bvh")), 126, g.motion, 306, 48), 1.0);
}

// The pinned stretch plays the reference's body (root-relative, in the root's heading) within 1 cm
// from 0.2 s after its start to 0.2 s before its end; pins at the very start and end too.
TEST_F(Control, PinsPlayTheReferenceStretch) {
  const MotionGraph g = graph_load(file("ref.gmg"));
  struct Case {
    std::string pin;
    int at, from, frames;
  };
  for (const Case& c :
       {Case{"6=10:12", 180, 300, 60}, Case{"0=20:21.5", 0, 600, 45}, Case{"13.5=30:31.5", 405, 900, 45}}) {
    SCOPED_TRACE(c.pin);
    const CliRun r = reenact({"--pin", c.pin, "--seed", "3", "-o", file("p.bvh"), "--report", file("p.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    const Motion m = bvh_read(file("p.bvh"));
    ASSERT_EQ(m.frame_count, 450);
    const int settle = 6;  // 0.2 s
    const int lead = c.at == 0 ? 0 : settle, tail = c.at + c.frames == 450 ? 0 : settle;
    EXPECT_LT(largest_heading_gap(m, c.at + lead, g.motion, c.from + lead, c.frames - lead - tail), 1.0);
    const nlohmann::json rep = nlohmann::json::parse(read_file_bytes(file("p.json")));
    EXPECT_EQ(rep["control"]["pinned"][0]["start_frame"], c.at);
    EXPECT_EQ(rep["control"]["pinned"][0]["graph_frame"], c.from);
    EXPECT_EQ(rep["control"]["pinned"][0]["frames"], c.frames);
    int pinned = 0;
    for (const auto& s : rep["subsequences"]) pinned += s["control"] == "pinned";
    EXPECT_EQ(pinned, 1);
  }
}

TEST_F(Control, PinByWordStartsAtTheWord) {
  const std::vector<text::Word> words = text::read_transcript(file("test.tsv"));
  ASSERT_GT(words.size(), 4u);
  ASSERT_EQ(reenact({"--pin-word", "4=10:11", "-o", file("w.bvh"), "--report", file("w.json")}).code, 0);
  const nlohmann::json rep = nlohmann::json::parse(read_file_bytes(file("w.json")));
  EXPECT_EQ(rep["control"]["pinned"][0]["start_frame"], std::lround(words[4].start * 30));
  const CliRun past = reenact({"--pin-word", "100000=10:11", "-o", file("w2.bvh")});
  EXPECT_EQ(past.code, 1);
  EXPECT_NE(past.err.find("past its last word"), std::string::npos) << past.err;
}

TEST_F(Control, RefusalsNameTheProblemAndWriteNothing) {
  // A clip of another skeleton (finger chains), and the earlier output cut short.
  SynthSpec other;
  other.duration_s = 15;
  other.joint_count_hint = 40;
  synth_write(synth_speaker(other), dir_->path().string(), "other");
  const Motion a = bvh_read(file("a.bvh"));
  bvh_write(file("short.bvh"), motion_slice(a, 0, 400));
  struct Case {
    std::vector<std::string> args;
    int code;
    std::string says;
  };
  const std::vector<Case> cases = {
      {{"--pin", "2=10:12", "--pin", "3=20:21"}, 1, "overlap"},
      {{"--pin", "14=10:12"}, 1, "ends after the audio"},
      {{"--pin", "2=39:41"}, 1, "outside the graph"},
      {{"--pin", "2=nope@1:2"}, 1, "names no clip"},
      {{"--pin", "2=12:10"}, 2, "FROM before TO"},
      {{"--pin", "2"}, 2, "expected T=FROM:TO"},
      {{"--keep", file("other.bvh"), "--range", "2:3"}, 1, "not in the graph's skeleton"},
      {{"--keep", file("short.bvh"), "--range", "2:3"}, 1, "400 frames, the audio needs 450"},
      {{"--keep", file("a.bvh"), "--range", "14:16"}, 1, "ends after the output"},
      {{"--keep", file("a.bvh")}, 2, "--keep and --range go together"},
      {{"--range", "2:3"}, 2, "--keep and --range go together"},
      {{"--keep", file("a.bvh"), "--range", "2:5", "--pin", "4=10:12"}, 1, "is not inside a --range"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = c.args;
    args.insert(args.end(), {"-o", file("refused.bvh"), "--report", file("refused.json")});
    const CliRun r = reenact(args);
    EXPECT_EQ(r.code, c.code) << c.says << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(file("refused.bvh"))) << c.says;
    EXPECT_FALSE(std::filesystem::exists(file("refused.json"))) << c.says;
  }
}

TEST(ControlSplice, ContinuesTheBaseAtBothEndsAndPlaysTheInsertBetween) {
  const Skeleton s = synth_skeleton();
  Motion base = motion_rest(s, 30, 100), insert = motion_rest(s, 30, 60);
  for (int f = 0; f < 60; ++f)
    for (int j = 0; j < s.joint_count(); ++j)
      insert.rotations[insert.index(f, j)] = glm::angleAxis(0.5, glm::dvec3(0, 0, 1));
  const Motion before = base;
  splice_motion(base, insert, 20, 80, 2.0, {});
  for (int f : {0, 19, 20, 79, 80, 99})
    for (int j = 0; j < s.joint_count(); ++j)
      EXPECT_NEAR(rotation_angle_between(base.rotation(f, j), before.rotation(f, j)), 0.0, 1e-12) << f;
  // Settled after 4.79 half-lives (under 1 % of the 0.5 rad offset) and up to as long before the end.
  for (int f = 30; f < 70; ++f)
    EXPECT_LT(rotation_angle_between(base.rotation(f, 3), insert.rotation(f - 20, 3)), 0.005) << f;
}

TEST(ControlParse, PinsAndRanges) {
  const PinRequest p = parse_pin("40=27:28.6", "--pin", false);
  EXPECT_EQ(p.at, 40.0);
  EXPECT_EQ(p.from, 27.0);
  EXPECT_EQ(p.to, 28.6);
  EXPECT_EQ(p.clip, "");
  const PinRequest c = parse_pin("1.5=take@2:3", "--pin", false);
  EXPECT_EQ(c.clip, "take");
  EXPECT_EQ(c.at, 1.5);
  const PinRequest w = parse_pin("7=2:3", "--pin-word", true);
  EXPECT_EQ(w.word, 7);
  EXPECT_THROW(parse_pin("1.5=2:3", "--pin-word", true), Error);
  EXPECT_THROW(parse_pin("-1=2:3", "--pin", false), Error);
  EXPECT_EQ(parse_range("20:30", "--range"), TimeRange(20.0, 30.0));
  EXPECT_THROW(parse_range("30:20", "--range"), Error);
  EXPECT_THROW(parse_range("20", "--range"), Error);
}

}  // namespace
}  // namespace gmg
