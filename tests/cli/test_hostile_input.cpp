// Hostile input: the 19 cases of the issue "bounded resources, no crash, no escape, nothing
// overwritten", each run through the gmg binary as a child process (tests/cli/hostile_input.h).
// Every case checks the exit code, that the one-line message names the file (or key) and the
// problem, that the child's peak memory stays under a bound, that it does not hang, and that no
// file is left or changed. The hostile inputs are generated here and are a few KB at most. The
// cases after them: test_hostile_speech.cpp, test_hostile_interrupt.cpp, test_hostile_outputs.cpp.
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

// 1: a hierarchy nested deeper than any skeleton is refused at the depth limit; the reader has
// no recursion, so 20,000 levels cannot overflow the stack (tests/motion/test_bvh.cpp parses
// 100,000 in memory).
TEST_F(HostileInput, Case01DeeplyNestedBvhIsRefusedNotACrash) {
  copy({"ref.wav"});
  std::string text = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n";
  for (int i = 0; i < 300; ++i) text += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 1 0\n";
  write_text(at("deep.bvh"), text);
  const auto before = snapshot(work_.path());
  expect_refused(gmg({"build", "--motion", "deep.bvh", "--audio", "ref.wav", "-o", "g.gmg"}), "deep.bvh",
                 "nested more than 256 deep");
  expect_unchanged(before);
}

// 2: "Frames: 10000000" in a 0.5 KB file allocates nothing: the claim is checked against the file.
TEST_F(HostileInput, Case02FrameCountHeaderAllocatesNothing) {
  for (const char* frames : {"10000000", "99999999"}) {
    write_text(at("lying.bvh"), small_bvh(frames, "0.0333333", 3));
    const auto before = snapshot(work_.path());
    const ChildRun r = gmg({"evaluate", "--generated", "lying.bvh"});
    expect_refused(r, "lying.bvh", std::string("'Frames: ") + frames + "'");
    EXPECT_TRUE(contains(r.err, "more than a file of")) << r.err;
    expect_unchanged(before);
  }
}

// 3: joints without channels are stored for every frame but cost nothing in the frame lines, so a
// small file could claim gigabytes: both the joint count and the memory per file byte are capped.
TEST_F(HostileInput, Case03JointsWithoutChannelsCannotClaimGigabytes) {
  auto many_joints = [](int joints, int frames) {
    std::string text = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n";
    for (int i = 0; i < joints; ++i) text += "JOINT " + std::to_string(i) + "\n{ OFFSET 0 1 0 }\n";
    text += "}\nMOTION\nFrames: " + std::to_string(frames) + "\nFrame Time: 0.0333333\n";
    for (int i = 0; i < frames; ++i) text += "0\n";
    return text;
  };
  write_text(at("wide.bvh"), many_joints(1100, 2000));
  expect_refused(gmg({"evaluate", "--generated", "wide.bvh"}), "wide.bvh", "more than 1024 joints");
  write_text(at("heavy.bvh"), many_joints(300, 800));  // 9 KB claiming 19 MB of frames
  const auto before = snapshot(work_.path());
  expect_refused(gmg({"evaluate", "--generated", "heavy.bvh"}), "heavy.bvh", "MB of memory, more than a file of");
  expect_unchanged(before);
}

// 4: a Frame Time of a microsecond (a million fps) or 1e-300 is refused when the BVH is read, not
// when a reenactment of 10 s becomes 10 M frames.
TEST_F(HostileInput, Case04FrameRateOutsideOneToThousandFpsIsRefused) {
  copy({"ref.wav"});
  for (const char* t : {"0.000001", "1e-300", "5"}) {
    write_text(at("fast.bvh"), small_bvh("3", t, 3));
    const auto before = snapshot(work_.path());
    expect_refused(gmg({"build", "--motion", "fast.bvh", "--audio", "ref.wav", "-o", "g.gmg"}), "fast.bvh",
                   "frames per second; gmg reads 1 to 1000 fps");
    expect_unchanged(before);
  }
}

// 5: a WAV at 10 MHz (or more) is refused when read: its resampling filter would need 10^8 taps.
TEST_F(HostileInput, Case05SampleRateAboveTheLimitIsRefused) {
  copy({"ref.gmg"});
  for (std::uint32_t rate : {10000019u, 100000007u, 2147483647u, 4294967295u}) {
    write_text(at("fast.wav"), small_wav(rate, 8));  // 60 bytes
    const auto before = snapshot(work_.path());
    expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "fast.wav", "-o", "out.bvh"}), "fast.wav",
                   "Hz is outside the 4000 to 192000 Hz gmg reads");
    expect_unchanged(before);
  }
}

// 6: 2,000 samples at 1 Hz would be 33 minutes of "speech" from 4 KB.
TEST_F(HostileInput, Case06SampleRateBelowTheLimitIsRefused) {
  copy({"ref.gmg"});
  write_text(at("slow.wav"), small_wav(1, 2000));
  const auto before = snapshot(work_.path());
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "slow.wav", "-o", "out.bvh"}), "slow.wav",
                 "sample rate 1 Hz is outside");
  expect_unchanged(before);
}

// 7: 1e309 in any JSON input is an error naming the file and the number.
TEST_F(HostileInput, Case07JsonNumberBeyondDoubleNamesTheFile) {
  copy({"ref.gmg", "new.wav", "ref.bvh"});
  write_text(at("t.json"), R"([{"alternatives": [{"words": [{"start_time": 1e309, "end_time": 2, "word": "x"}]}]}])");
  write_text(at("c.json"), R"({"l_pn": 1e309})");
  write_text(at("r.json"), R"({"totals": {"failures": 1e309}, "subsequences": []})");
  const auto before = snapshot(work_.path());
  const std::string problem = "the number 1e309 is out of range for a double";
  expect_refused(
      gmg({"reenact", "--graph", "ref.gmg", "--audio", "new.wav", "--transcript", "t.json", "-o", "out.bvh"}),
      "t.json: byte", problem);
  expect_refused(gmg({"config", "--config", "c.json"}), "c.json: byte", problem);
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "new.wav", "--config", "c.json", "-o", "out.bvh"}),
                 "c.json: byte", problem);
  expect_refused(gmg({"evaluate", "--generated", "ref.bvh", "--report", "r.json"}), "r.json: byte", problem);
  expect_unchanged(before);
}

// 8: what `gmg config` prints is a config file `--config` takes unchanged, also with a seed
// beyond 2^63 and changed keys.
TEST_F(HostileInput, Case08ConfigOutputIsAcceptedByConfig) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"config"},
        std::vector<std::string>{"config", "--seed", "18446744073709551615", "--set", "l_pn=3", "--set", "w_full=1,2",
                                 "--set", "l_feat=2", "--set", "lock_joints=a,b"}}) {
    const ChildRun first = gmg(args);
    ASSERT_EQ(first.code, 0) << first.err;
    write_text(at("c.json"), first.out);
    const ChildRun again = gmg({"config", "--config", "c.json"});
    EXPECT_EQ(again.code, 0) << again.err;
    EXPECT_EQ(again.out, first.out);
    expect_bounded(again);
  }
}

// 9: a graph file with a valid checksum and an impossible frame rate is refused when loaded (it
// would turn 2 s of speech into millions of frames, or blame the WAV for inf).
TEST_F(HostileInput, Case09GraphWithImpossibleFrameRateIsRefused) {
  copy({"new.wav"});
  for (double fps : {std::numeric_limits<double>::infinity(), 1e300, 1e6, 0.01}) {
    MotionGraph g = tiny_graph();
    g.motion.fps = fps;
    graph_save(at("bad.gmg"), g);
    const auto before = snapshot(work_.path());
    expect_refused(gmg({"reenact", "--graph", "bad.gmg", "--audio", "new.wav", "-o", "out.bvh"}), "bad.gmg",
                   "frame rate");
    expect_refused(gmg({"inspect", "bad.gmg"}), "bad.gmg", "is outside 1 to 1000 fps");
    expect_unchanged(before);
  }
  MotionGraph good = tiny_graph();  // the control: the same file with 30 fps loads
  graph_save(at("good.gmg"), good);
  EXPECT_EQ(gmg({"inspect", "good.gmg"}).code, 0);
}

// 10: clip frame counts that sum past 2^31 are refused (summed in 64 bits: no signed overflow,
// which the sanitizer build would turn into a crash).
TEST_F(HostileInput, Case10GraphClipCountsPastIntMaxAreRefused) {
  MotionGraph g = tiny_graph();
  g.clips = {{"a.bvh", 0, 4}, {"b.bvh", 4, 2147483647}, {"c.bvh", -2147483645, 6}};
  graph_save(at("clips.gmg"), g);
  const auto before = snapshot(work_.path());
  expect_refused(gmg({"inspect", "clips.gmg"}), "clips.gmg", "clip table inconsistent");
  expect_unchanged(before);
}

// 11a: a Latin-1 file name in the report is replaced by U+FFFD, never thrown on; and a report
// that cannot be written takes the BVH with it.
TEST_F(HostileInput, Case11NonUtf8TextInAReportIsReplaced) {
  copy({"ref.gmg"});
  fs::copy_file(fixtures_->path() / "new.wav", work_.path() / "caf\xE9.wav");
  const ChildRun r =
      gmg({"reenact", "--graph", "ref.gmg", "--audio", "caf\xE9.wav", "-o", "out.bvh", "--report", "out.json"});
  ASSERT_EQ(r.code, 0) << r.err;
  expect_bounded(r);
  const nlohmann::json report = nlohmann::json::parse(read_file_bytes(at("out.json")));
  EXPECT_EQ(report["inputs"]["audio"], "caf\xEF\xBF\xBD.wav");
  EXPECT_TRUE(fs::exists(at("out.bvh")));

  const auto before = snapshot(work_.path());
  const ChildRun bad = gmg({"reenact", "--graph", "ref.gmg", "--audio", "caf\xE9.wav", "-o", "again.bvh", "--report",
                            "no/such/folder/out.json"});
  // Refused before the work now (case 25); that a report failing at its write takes the BVH with
  // it is tests/core/test_files.cpp's TransactionCommitsEveryFileOrNone.
  expect_refused(bad, "no/such/folder/out.json", "--report: the folder no/such/folder does not exist");
  expect_unchanged(before);  // no again.bvh without its report
}

// 11b: a pool clip whose error message holds non-UTF-8 bytes fails its clips; the batch still
// writes summary.json (valid JSON, the bytes replaced) and exits 1, not 2.
TEST_F(HostileInput, Case11BatchWritesItsSummaryWhateverTheBytes) {
  fs::create_directories(at("pool"));
  fs::create_directories(at("tests"));
  for (const char* ext : {".bvh", ".wav", ".tsv"})
    fs::copy_file(fixtures_->path() / (std::string("ref") + ext), work_.path() / "pool" / (std::string("ref") + ext));
  write_text(at("pool/bad.bvh"), "\xFF\xFE\xE9 not a BVH\n");
  fs::copy_file(fixtures_->path() / "ref.wav", work_.path() / "pool/bad.wav");
  fs::copy_file(fixtures_->path() / "new.wav", work_.path() / "tests/new.wav");
  write_text(at("pairs.csv"), "test_stem,reference_stem\nnew,bad\n");
  const ChildRun r = gmg({"batch", "--pool", "pool", "--tests", "tests", "--manifest", "pairs.csv", "-o", "out",
                          "--progress", "none", "--jobs", "1"});
  EXPECT_EQ(r.code, 1) << r.err;
  expect_bounded(r);
  const nlohmann::json summary = nlohmann::json::parse(read_file_bytes(at("out/summary.json")));
  ASSERT_EQ(summary["clips"].size(), 1u);
  EXPECT_EQ(summary["clips"][0]["status"], "failed");
  const std::string error = summary["clips"][0]["error"];
  EXPECT_TRUE(contains(error, "bad.bvh")) << error;
  EXPECT_TRUE(contains(error, "'\\xff\\xfe\\xe9'")) << "the file's bytes, quoted escaped: " << error;
  EXPECT_FALSE(fs::exists(at("out/new.bvh")));
}

// 12: a test manifest stem "../escaped" would write outside -o: a setup error naming the line.
TEST_F(HostileInput, Case12BatchStemCannotLeaveTheOutputFolder) {
  fs::create_directories(at("pool"));
  for (const char* ext : {".bvh", ".wav"})
    fs::copy_file(fixtures_->path() / (std::string("ref") + ext), work_.path() / "pool" / (std::string("ref") + ext));
  copy({"new.wav"});
  write_text(at("tests.csv"), "stem,wav\n../escaped,new.wav\n");
  const auto before = snapshot(work_.path());
  const ChildRun r =
      gmg({"batch", "--pool", "pool", "--test-manifest", "tests.csv", "-o", "out", "--progress", "none"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "tests.csv: line 2: stem '../escaped' is not a plain file name")) << r.err;
  expect_bounded(r);
  EXPECT_FALSE(fs::exists(work_.path() / "escaped.bvh"));
  expect_unchanged(before);
}

// 13: a folder given as the transcript is an error, not an empty transcript.
TEST_F(HostileInput, Case13FolderAsTranscriptIsRefused) {
  copy({"ref.gmg", "new.wav"});
  fs::create_directories(at("words.tsv"));
  fs::create_directories(at("words"));
  const auto before = snapshot(work_.path());
  expect_refused(
      gmg({"reenact", "--graph", "ref.gmg", "--audio", "new.wav", "--transcript", "words.tsv", "-o", "out.bvh"}),
      "words.tsv", "is a folder, not a file");
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "new.wav", "--transcript", "words",
                      "--transcript-format", "tsv", "-o", "out.bvh"}),
                 "words", "is a folder, not a file");
  expect_unchanged(before);
}

// 14: a FIFO as BVH, WAV or graph is refused at once instead of waiting for a writer forever.
TEST_F(HostileInput, Case14FifoInputsAreRefusedNotWaitedOn) {
  copy({"ref.gmg", "ref.bvh", "ref.wav", "new.wav"});
  for (const char* name : {"pipe.bvh", "pipe.wav", "pipe.gmg", "pipe.flac", "pipe.npz"})
    ASSERT_EQ(::mkfifo(at(name).c_str(), 0644), 0);
  const auto before = snapshot(work_.path());
  const std::string fifo = "is a FIFO (named pipe), not a regular file";
  expect_refused(gmg({"build", "--motion", "pipe.bvh", "--audio", "ref.wav", "-o", "g.gmg"}, 20), "pipe.bvh", fifo);
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "pipe.wav", "-o", "out.bvh"}, 20), "pipe.wav", fifo);
  expect_refused(gmg({"inspect", "pipe.gmg"}, 20), "pipe.gmg", fifo);
  // Other audio formats (aubio) and npz motions are sniffed or opened by other code paths.
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "pipe.flac", "-o", "out.bvh"}, 20), "pipe.flac",
                 fifo);
  expect_refused(
      gmg({"build", "--motion", "pipe.npz", "--skeleton", "ref.bvh", "--audio", "ref.wav", "-o", "g.gmg"}, 20),
      "pipe.npz", fifo);
  expect_unchanged(before);
}

// 15: an output that is an input (by name, or through a symbolic link) is refused before any
// work, and so are two outputs that are one file.
// (Outputs of the right extension: a wrong one is refused first, from the command line alone.)
TEST_F(HostileInput, Case15OutputEqualToAnInputIsRefused) {
  copy({"ref.bvh", "ref.wav", "ref.gmg", "new.wav"});
  fs::create_symlink("ref.bvh", at("link.gmg"));
  fs::create_symlink("new.wav", at("link.bvh"));
  fs::create_symlink("ref.gmg", at("link.dot"));
  write_text(at("x.bvh"), "");
  fs::create_symlink("x.bvh", at("x.json"));
  const auto before = snapshot(work_.path());
  expect_refused(gmg({"reenact", "--reference-motion", "ref.bvh", "--reference-audio", "ref.wav", "--audio", "new.wav",
                      "-o", "ref.bvh"}),
                 "ref.bvh", "-o would overwrite the input given as --reference-motion");
  expect_refused(gmg({"build", "--motion", "ref.bvh", "--audio", "ref.wav", "-o", "link.gmg"}), "link.gmg",
                 "-o would overwrite the input given as --motion (ref.bvh)");
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "new.wav", "-o", "link.bvh"}), "link.bvh",
                 "would overwrite the input given as --audio");
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "new.wav", "-o", "x.bvh", "--report", "x.json"}),
                 "x.json", "given as both -o and --report");
  expect_refused(gmg({"inspect", "ref.gmg", "--dot", "link.dot"}), "link.dot", "would overwrite the input");
  expect_unchanged(before);
}

// 16: SIGINT at any moment of a reenactment (reading, searching, writing) leaves no temporary
// file, and the BVH and its report are there together or not at all.
TEST_F(HostileInput, Case16InterruptLeavesNoTemporaryFile) {
  copy({"ref.gmg", "new.wav"});
  int interrupted = 0;
  for (int delay_ms = 0; delay_ms <= 60; delay_ms += 4) {
    const ChildRun r =
        run_gmg({"reenact", "--graph", "ref.gmg", "--audio", "new.wav", "-o", "out.bvh", "--report", "out.json"},
                work_.path(), 60, delay_ms);
    EXPECT_TRUE(r.code == 0 || r.code == 128 + SIGINT) << r.code << ": " << r.err;
    if (r.code != 0) ++interrupted;
    for (const auto& e : fs::directory_iterator(work_.path()))
      EXPECT_FALSE(contains(e.path().filename().string(), ".tmp")) << "left: " << e.path();
    EXPECT_EQ(fs::exists(at("out.bvh")), fs::exists(at("out.json")));
    fs::remove(at("out.bvh"));
    fs::remove(at("out.json"));
  }
  EXPECT_GT(interrupted, 0);  // some runs were interrupted (the first at 0 ms surely)
}

// 17: a beam of 10^9 paths is refused naming the key and its range.
TEST_F(HostileInput, Case17HugeBeamWidthNamesTheKey) {
  copy({"ref.gmg", "new.wav"});
  const auto before = snapshot(work_.path());
  // A --set out of range is a usage error (case 26).
  expect_usage_error(
      gmg({"reenact", "--graph", "ref.gmg", "--audio", "new.wav", "-o", "out.bvh", "--set", "l_npaths=1000000000"}),
      "config key 'l_npaths': 1000000000 is out of range (1 to 1000)");
  expect_unchanged(before);
}

// 18: a second batch into a folder in use is refused, and so is a re-run with another seed into a
// folder holding the first run's outputs.
TEST_F(HostileInput, Case18BatchFolderIsLockedAndSettingsDoNotMix) {
  fs::create_directories(at("pool"));
  fs::create_directories(at("tests"));
  for (const char* ext : {".bvh", ".wav", ".tsv"})
    fs::copy_file(fixtures_->path() / (std::string("ref") + ext), work_.path() / "pool" / (std::string("ref") + ext));
  fs::copy_file(fixtures_->path() / "new.wav", work_.path() / "tests/new.wav");
  const std::vector<std::string> batch = {"batch", "--pool", "pool",       "--tests", "tests",
                                          "-o",    "out",    "--progress", "none"};
  auto with_seed = [&](const char* seed) {
    std::vector<std::string> a = batch;
    a.insert(a.end(), {"--seed", seed});
    return a;
  };
  {  // Another batch holds the folder's lock.
    fs::create_directories(at("out"));
    const int fd = ::open(at("out/.gmg-batch.lock").c_str(), O_RDWR | O_CREAT, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_EX), 0);
    const auto before = snapshot(work_.path());
    const ChildRun r = gmg(with_seed("1"));
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_TRUE(contains(r.err, "out: another gmg batch")) << r.err;
    expect_unchanged(before);
    ::close(fd);
  }
  const ChildRun first = gmg(with_seed("1"));
  ASSERT_EQ(first.code, 0) << first.err;
  const auto made = snapshot(work_.path());
  const ChildRun other = gmg(with_seed("2"));
  EXPECT_EQ(other.code, 2) << other.err;
  EXPECT_TRUE(contains(other.err, "out: holds outputs of a run with seed 1, not 2")) << other.err;
  expect_bounded(other);
  expect_unchanged(made);
  const ChildRun same = gmg(with_seed("1"));  // the same settings resume (nothing to do)
  EXPECT_EQ(same.code, 0) << same.err;
  const ChildRun forced = gmg([&] {
    auto a = with_seed("2");
    a.push_back("--force");
    return a;
  }());
  EXPECT_EQ(forced.code, 0) << forced.err;
  EXPECT_EQ(nlohmann::json::parse(read_file_bytes(at("out/batch.json")))["seed"], 2);
}

// 19: evaluating a 1-frame motion names the file and the precondition.
TEST_F(HostileInput, Case19EvaluateOfOneFrameNamesTheFile) {
  write_text(at("one.bvh"), small_bvh("1", "0.0333333", 1));
  const auto before = snapshot(work_.path());
  expect_refused(gmg({"evaluate", "--generated", "one.bvh"}), "one.bvh", "the metrics need at least 4");
  expect_unchanged(before);
}

}  // namespace
}  // namespace gmg::hostile
