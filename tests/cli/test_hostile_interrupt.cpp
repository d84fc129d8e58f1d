// Hostile input, cases 23 and 24 (tests/cli/hostile_input.h): the interrupt contract, every
// command ended by its signal with no temporary file left, and a killed render's ffmpeg.
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

// ---- The interrupt contract ----------------------------------------------------------------

// The process `pid` has ended (gone, or a zombie no one has reaped yet) within `seconds`.
bool ends_within(pid_t pid, double seconds) {
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds) {
    const std::string stat_path = "/proc/" + std::to_string(pid) + "/stat";
    std::string stat;
    try {
      stat = read_file_bytes(stat_path);
    } catch (const Error&) {
      return true;  // gone
    }
    const std::size_t paren = stat.rfind(')');
    if (paren != std::string::npos && paren + 2 < stat.size() && stat[paren + 2] == 'Z') return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// A stand-in for ffmpeg that records its process id and then is ffmpeg (exec keeps the id).
std::string ffmpeg_recording_its_pid(const fs::path& dir) {
  std::string path = (dir / "ffmpeg_wrapper.sh").string();
  write_text(path, "#!/bin/sh\necho $$ > '" + (dir / "ffmpeg.pid").string() + "'\nexec ffmpeg \"$@\"\n");
  fs::permissions(path, fs::perms::owner_all);
  return path;
}

// Points TMPDIR, for the gmg processes started meanwhile, at a folder of its own, to show what gmg
// leaves in the temporary directory.
class PrivateTmpdir {
 public:
  PrivateTmpdir() {
    const char* was = std::getenv("TMPDIR");
    had_ = was != nullptr;
    if (had_) was_ = was;
    ::setenv("TMPDIR", dir_.path().c_str(), 1);
  }
  ~PrivateTmpdir() {
    if (had_) {
      ::setenv("TMPDIR", was_.c_str(), 1);
    } else {
      ::unsetenv("TMPDIR");
    }
  }
  PrivateTmpdir(const PrivateTmpdir&) = delete;
  PrivateTmpdir& operator=(const PrivateTmpdir&) = delete;
  std::vector<std::string> left() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_.path())) names.push_back(e.path().filename().string());
    return names;
  }

 private:
  TempDir dir_;
  bool had_ = false;
  std::string was_;
};

// 23: every command ends by the signal it got, after removing its temporaries: SIGINT 130,
// SIGTERM 143, SIGHUP 129, as a shell reports a process killed by it (so a loop around gmg stops
// on Ctrl-C). render also stops its ffmpeg; batch first writes its summary.
TEST_F(HostileInput, Case23InterruptsEndEveryCommandByTheirSignal) {
  if (!have_ffmpeg()) GTEST_SKIP() << "the ffmpeg tool is absent: render cannot run";
  SynthSpec spec;  // long enough that each command is still at work when the signal comes
  spec.duration_s = 240.0;
  spec.seed = 5;
  synth_write(synth_speaker(spec), work_.path().string(), "long");
  fs::create_directories(at("pool"));
  fs::create_directories(at("tests"));
  for (const char* ext : {".bvh", ".wav"})
    fs::copy_file(at(std::string("long") + ext), at(std::string("pool/long") + ext));
  fs::copy_file(at("long.wav"), at("tests/speech.wav"));
  const std::string ffmpeg = ffmpeg_recording_its_pid(work_.path());
  const std::vector<std::vector<std::string>> commands = {
      {"build", "--motion", "long.bvh", "--audio", "long.wav", "-o", "long.gmg"},
      {"reenact", "--reference-motion", "long.bvh", "--reference-audio", "long.wav", "--audio", "long.wav", "-o",
       "out.bvh", "--report", "out.json"},
      {"batch", "--pool", "pool", "--tests", "tests", "-o", "batch_out", "--progress", "none", "--jobs", "1"},
      {"render", "long.bvh", "--audio", "long.wav", "-o", "video.mp4", "--ffmpeg", ffmpeg}};
  for (const auto& args : commands)
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
      if (sig == SIGHUP && args[0] != "render") continue;  // one command is enough for the third
      fs::remove(at("ffmpeg.pid"));
      // batch and render: once their graceful handling runs (the pairing is on record, ffmpeg has
      // started); the others die at once whenever the signal comes.
      const fs::path once = args[0] == "batch"    ? at("batch_out/pairs.csv")
                            : args[0] == "render" ? at("ffmpeg.pid")
                                                  : "";
      const PrivateTmpdir tmp;
      const ChildRun r = run_gmg(args, work_.path(), 120, args[0] == "render" ? 300 : 150, sig, once);
      const std::string what = args[0] + " with " + std::to_string(sig);
      EXPECT_EQ(r.code, 128 + sig) << what << ": " << r.err;
      EXPECT_TRUE(r.signalled) << what << ": ended by exit(" << r.code << "), not by the signal";
      expect_no_temporaries(work_.path());
      EXPECT_EQ(tmp.left(), std::vector<std::string>{}) << what;
      if (fs::exists(at("batch_out"))) expect_no_temporaries(at("batch_out"));
      EXPECT_FALSE(fs::exists(at("long.gmg")) || fs::exists(at("out.bvh")) || fs::exists(at("video.mp4"))) << what;
      if (args[0] == "render") {
        EXPECT_TRUE(contains(r.err, "gmg: error: video.mp4: interrupted by ")) << r.err;
        ASSERT_TRUE(fs::exists(at("ffmpeg.pid"))) << "render had not started ffmpeg: " << r.err;
        EXPECT_TRUE(ends_within(std::stoi(read_file_bytes(at("ffmpeg.pid"))), 5.0)) << "ffmpeg outlived gmg";
      }
      if (args[0] == "batch") {
        EXPECT_TRUE(fs::exists(at("batch_out/summary.json"))) << r.err;
        fs::remove_all(at("batch_out"));
      }
    }
}

// 24: a render killed by SIGKILL (which nothing can catch) takes its ffmpeg with it (the kernel
// kills it: PR_SET_PDEATHSIG), and the next render into the folder removes the partial video.
TEST_F(HostileInput, Case24KilledRenderTakesFfmpegAndIsCleanedUpAfter) {
  if (!have_ffmpeg()) GTEST_SKIP() << "the ffmpeg tool is absent: render cannot run";
  SynthSpec spec;
  spec.duration_s = 120.0;
  spec.seed = 6;
  synth_write(synth_speaker(spec), work_.path().string(), "long");
  const std::string ffmpeg = ffmpeg_recording_its_pid(work_.path());
  const PrivateTmpdir tmp;
  const ChildRun killed = run_gmg({"render", "long.bvh", "--audio", "long.wav", "-o", "video.mp4", "--ffmpeg", ffmpeg},
                                  work_.path(), 120, 1500, SIGKILL, at("ffmpeg.pid"));
  // ffmpeg's messages went to a file in the temporary directory that gmg unlinks once it is open.
  EXPECT_EQ(tmp.left(), std::vector<std::string>{}) << "a killed render left files in the temporary directory";
  ASSERT_EQ(killed.code, 128 + SIGKILL) << killed.err;
  ASSERT_TRUE(fs::exists(at("ffmpeg.pid")));
  EXPECT_TRUE(ends_within(std::stoi(read_file_bytes(at("ffmpeg.pid"))), 5.0)) << "ffmpeg outlived a killed gmg";
  int partial = 0;
  for (const auto& e : fs::directory_iterator(work_.path()))
    if (temporary_file_owner(e.path().filename().string()) != 0) ++partial;
  EXPECT_EQ(partial, 1) << "the killed render's partial video";
  copy({"ref.bvh"});
  const ChildRun next = gmg({"render", "ref.bvh", "-o", "other.mp4"});
  EXPECT_EQ(next.code, 0) << next.err;
  expect_no_temporaries(work_.path());
  EXPECT_FALSE(fs::exists(at("video.mp4")));
}

}  // namespace
}  // namespace gmg::hostile
