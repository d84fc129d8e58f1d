// Hostile input, cases 25 to 28 (tests/cli/hostile_input.h): outputs of the wrong kind, usage
// errors, messages that name the file and lead with the cause, full and read-only disks.
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/hostile_input.h"

namespace gmg::hostile {
namespace {

// ---- Outputs of the wrong kind -------------------------------------------------------------

// 25: an output whose extension names another format (a usage error, exit 2), or that is a folder,
// is refused before any input is read (here the graph does not even exist), and nothing is written.
TEST_F(HostileInput, Case25OutputsOfTheWrongKindAreRefusedUpFront) {
  copy({"new.wav", "ref.bvh", "ref.wav"});
  fs::create_directories(at("folder.bvh"));
  const auto before = snapshot(work_.path());
  const std::string motion = ": -o must be a .bvh or .npz file (its extension chooses the format)";
  for (const char* out : {"out.txt", "x.fbx", "out"})
    expect_usage_error(gmg({"reenact", "--graph", "missing.gmg", "--audio", "new.wav", "-o", out}), out + motion);
  expect_refused(gmg({"reenact", "--graph", "missing.gmg", "--audio", "new.wav", "-o", "folder.bvh"}), "folder.bvh",
                 "-o is a folder, not a file");
  expect_usage_error(
      gmg({"reenact", "--graph", "missing.gmg", "--audio", "new.wav", "-o", "o.bvh", "--report", "r.txt"}),
      "r.txt: --report must be a .json file");
  expect_refused(gmg({"reenact", "--graph", "missing.gmg", "--audio", "new.wav", "-o", "no/such/o.bvh"}),
                 "no/such/o.bvh", "-o: the folder no/such does not exist");
  expect_usage_error(gmg({"build", "--motion", "ref.bvh", "--audio", "ref.wav", "-o", "g.graph"}),
                     "g.graph: -o must be a .gmg file");
  expect_usage_error(gmg({"evaluate", "--generated", "ref.bvh", "--plot", "p.jpg"}),
                     "p.jpg: --plot must be a .png or .svg file");
  expect_usage_error(gmg({"evaluate", "--generated", "ref.bvh", "-o", "m.csv"}), "m.csv: -o must be a .json file");
  expect_usage_error(gmg({"render", "ref.bvh", "-o", "v.avi"}), "v.avi: -o must be a .mp4, .mkv or .mov file");
  expect_usage_error(gmg({"inspect", "missing.gmg", "--dot", "g.png"}), "g.png: --dot must be a .dot or .gv file");
  expect_refused(gmg({"synth", "-o", "ref.bvh"}), "ref.bvh", "-o is a file, not a folder");
  expect_unchanged(before);
}

// ---- Usage errors --------------------------------------------------------------------------

// 26: what cannot mean anything exits 2 with the nearest name when there is one; a joint
// lock_joints names that the graph lacks is an input error naming the graph and the joint.
TEST_F(HostileInput, Case26UsageErrorsExitTwoWithTheNearestName) {
  copy({"ref.gmg", "new.wav"});
  const auto before = snapshot(work_.path());
  const std::vector<std::string> reenact = {"reenact", "--graph", "ref.gmg", "--audio", "new.wav", "-o", "out.bvh"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = reenact;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  expect_usage_error(gmg({"biuld"}), "unknown command 'biuld' (did you mean 'build'?)");
  expect_usage_error(gmg({"frobnicate"}), "unknown command 'frobnicate' (see 'gmg --help' for the commands)");
  expect_usage_error(gmg({"reenact", "--grpah", "ref.gmg", "--audio", "new.wav", "-o", "out.bvh"}),
                     "reenact: unknown option '--grpah' (did you mean '--graph'?) (see 'gmg reenact --help')");
  expect_usage_error(gmg(with({"--allow-silense"})),
                     "unknown option '--allow-silense' (did you mean '--allow-silence'?)");
  expect_usage_error(gmg({"batch", "--pool", "p", "--tests", "t", "-o", "o", "--jbos", "2"}),
                     "batch: unknown option '--jbos' (did you mean '--jobs'?)");
  expect_usage_error(gmg(with({"--set", "nonsense=3"})), "unknown config key 'nonsense'");
  expect_usage_error(gmg(with({"--set", "l_pm=3"})), "unknown config key 'l_pm' (did you mean 'l_pn'?)");
  expect_usage_error(gmg(with({"--set", "l_pn=abc"})), "config key 'l_pn': 'abc' is not a whole number");
  expect_usage_error(gmg(with({"--set", "planner=papr"})), "'papr' is not natural or paper (did you mean 'paper'?)");
  expect_usage_error(gmg(with({"--seed", "-1"})), "--seed: '-1' is not a whole number 0 or above");
  expect_usage_error(gmg(with({"--seed", "18446744073709551616"})),  // 2^64: refused, not saturated
                     "--seed: 18446744073709551616 is out of range (0 to 18446744073709551615)");
  expect_usage_error(gmg(with({"--set", "l_pn"})), "gmg: error: --set expects key=value, got 'l_pn'");
  expect_usage_error(gmg({"build", "--motion", "m.bvh", "--audio", "a.wav", "-o", "g.gmg", "--jobs", "99999999999"}),
                     "--jobs: 99999999999 is out of range (0 to 1024)");
  expect_usage_error(gmg({"render", "m.bvh", "-o", "v.mp4", "--size", "0x0"}),
                     "--size: 0x0 is not an even size from 160x120 to 3840x2160");
  expect_usage_error(gmg({"synth", "-o", "s", "--duration", "1e9"}), "--duration: 1e+09 s is more than the day");
  expect_usage_error(gmg({"inspect", "ref.gmg", "--dot", "g.dot", "--frames", "300:100"}),
                     "--frames: 300:100 is empty: FROM (300) must be below TO (100)");
  expect_usage_error(gmg({"inspect", "ref.gmg", "--dot", "g.dot", "--frames=-5:10"}), "is not a frame number");
  expect_usage_error(gmg({"synth", "-o", "s", "--duration", "0"}), "--duration: '0' is not a number above 0");
  expect_usage_error(gmg({"synth", "-o", "s", "--stem", "a/b"}), "--stem 'a/b' is not a plain file name");
  expect_refused(gmg(with({"--set", "lock_joints=RightHnd"})), "ref.gmg",
                 "lock_joints names 'RightHnd', which is not a joint of its skeleton (did you mean 'RightHand'?)");
  // A --config file that breaks a rule is the file's problem: exit 1, naming it.
  write_text(at("c.json"), R"({"smooth_window": 4})");
  expect_refused(gmg(with({"--config", "c.json"})), "c.json", "smooth_window must be odd");
  fs::remove(at("c.json"));
  expect_unchanged(before);
  // The lock on a graph that has the joint only warns that it changes nothing there.
  const ChildRun noted = gmg(with({"--set", "lock_joints=RightHand"}));
  EXPECT_EQ(noted.code, 0) << noted.err;
  EXPECT_TRUE(contains(noted.err, "gmg: warning: ref.gmg: lock_joints has no effect on a built graph")) << noted.err;
}

// ---- Messages ------------------------------------------------------------------------------

// 27: each message names the file and leads with the cause, and quotes a file's bytes escaped.
TEST_F(HostileInput, Case27MessagesNameTheFileAndLeadWithTheCause) {
  copy({"ref.gmg", "ref.bvh", "ref.wav"});
  write_text(at("words.wav"), "0.5\t0.9\thello\n");
  write_text(at("take.wav"), read_file_bytes(at("ref.bvh")));
  write_text(at("binary.bvh"), "HIERARCHY\n\x1b[2J\x07\xff\xfe\x01 ROOT\n{\n");
  write_text(at("binary.tsv"), "\x1b]0;x\x07\t1\tword\n\x89PNG\r\n\x1a\n");
  fs::create_directories(at("empty_pool"));
  fs::create_directories(at("tests"));
  fs::copy_file(at("ref.wav"), at("tests/t.wav"));
  const auto before = snapshot(work_.path());
  const std::string hint = " (give the speech as WAV, FLAC, MP3, OGG, M4A, ...)";
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "words.wav", "-o", "out.bvh"}), "words.wav",
                 "words.wav: is not audio: it is a text file" + hint);
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "take.wav", "-o", "out.bvh"}), "take.wav",
                 "take.wav: is not audio: it is a BVH motion file");
  for (const ChildRun& r :
       {gmg({"evaluate", "--generated", "binary.bvh"}),
        gmg({"reenact", "--graph", "ref.gmg", "--audio", "ref.wav", "--transcript", "binary.tsv", "-o", "out.bvh"})}) {
    EXPECT_EQ(r.code, 1) << r.err;
    expect_own_lines_only(r);
    EXPECT_TRUE(contains(r.err, "\\x1b")) << "the escape byte shown as such: " << r.err;
  }
  const ChildRun pool = gmg({"batch", "--pool", "empty_pool", "--tests", "tests", "-o", "out", "--progress", "none"});
  EXPECT_EQ(pool.code, 2) << pool.err;
  EXPECT_TRUE(contains(pool.err, "gmg: error: empty_pool: the pool holds no reference clip")) << pool.err;
  expect_refused(gmg({"ablation", "--motion", "ref.bvh", "--audio", "ref.wav", "--folds", "3", "--seeds", "1"}),
                 "ref.bvh", "folds of 120 frames leave a part of 40 frames");
  const ChildRun duration = gmg({"synth", "-o", "s", "--duration", "0"});
  EXPECT_LT(duration.err.size(), 120u) << "a short message, not a range of 300 digits: " << duration.err;
  expect_unchanged(before);
}

// 28: a full disk and a read-only folder: each message names the output the user gave (not a
// temporary) and leads with the cause; nothing is left behind, not even an empty folder.
TEST_F(HostileInput, Case28FullAndReadOnlyDisksNameTheOutputAndTheCause) {
  copy({"ref.bvh", "ref.wav", "ref.gmg", "new.wav"});
  {
    // 16 KB of which a file takes 12: less room than a 4 s video or a BVH of 2 s needs.
    testing::SmallDisk full(16, false,
                            [](const fs::path& d) { write_text((d / "filler").string(), std::string(12288, 'x')); });
    if (!full.ok()) GTEST_SKIP() << full.why();
    const std::string video = full.file("video.mp4");
    if (have_ffmpeg()) {
      const ChildRun r = gmg({"render", "ref.bvh", "--audio", "ref.wav", "-o", video});
      expect_refused(r, video, video + ": cannot write the video (No space left on device)");
      EXPECT_FALSE(fs::exists(video)) << "a video cut short by the full disk";
      EXPECT_FALSE(contains(r.err, ".tmp")) << r.err;
    }
    const ChildRun s = gmg({"synth", "-o", full.file("clip"), "--duration", "30"});
    expect_refused(s, full.file("clip"), "No space left on device");
    EXPECT_FALSE(fs::exists(full.file("clip"))) << "synth left its folder on the full disk";
    const ChildRun b =
        gmg({"reenact", "--graph", "ref.gmg", "--audio", "new.wav", "-o", full.file("big.bvh"), "--set", "l_blend=0"});
    if (b.code != 0) expect_refused(b, full.file("big.bvh"), "No space left on device");
    expect_no_temporaries(full.path());
  }
  testing::SmallDisk ro(64, /*read_only=*/true, [](const fs::path& d) { fs::create_directories(d / "outs"); });
  if (!ro.ok()) GTEST_SKIP() << ro.why();
  const std::string reason = "(Read-only file system)";
  if (have_ffmpeg()) {
    const ChildRun r = gmg({"render", "ref.bvh", "-o", ro.file("video.mp4")});
    expect_refused(r, ro.file("video.mp4"), "cannot write into the folder " + ro.path().string() + " " + reason);
    EXPECT_FALSE(contains(r.err, ".tmp")) << r.err;
  }
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "new.wav", "-o", ro.file("out.bvh")}),
                 ro.file("out.bvh"), reason);
  const ChildRun b = gmg({"batch", "--graph", "ref.gmg", "--tests", ".", "-o", ro.file("batch"), "--progress", "none"});
  EXPECT_EQ(b.code, 2) << b.err;
  EXPECT_TRUE(contains(b.err, ro.file("batch")) && contains(b.err, reason)) << b.err;
  const ChildRun m = gmg({"batch", "--graph", "ref.gmg", "--tests", ".", "-o", ro.file("outs"), "--progress", "none"});
  EXPECT_EQ(m.code, 2) << m.err;
  EXPECT_TRUE(contains(m.err, ro.file("outs")) && contains(m.err, reason)) << m.err;
  expect_refused(gmg({"synth", "-o", ro.file("clip")}), ro.file("clip"), reason);
}

}  // namespace
}  // namespace gmg::hostile
