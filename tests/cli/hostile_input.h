// The hostile-input tests' harness (tests/cli/test_hostile_*.cpp): gmg run as a child process
// with its exit code, output, peak memory and a time limit; the checks every case makes (a
// refusal or usage error of one line naming the file and the problem, bounded resources, nothing
// left or changed); small generated inputs; and the fixture that makes the shared reference files
// once.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "audio/wav.h"
#include "engine/config/config.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"
#include "engine/motion/bvh.h"
#include "engine/pipeline/pipeline.h"
#include "engine/synth/synth.h"
#include "graph/graph_builder.h"
#include "graph/graph_io.h"
#include "tests/test_support.h"

#if defined(__SANITIZE_ADDRESS__)
#define GMG_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GMG_TEST_SANITIZED 1
#endif
#endif

namespace gmg::hostile {

namespace fs = std::filesystem;
using gmg::testing::TempDir;
using gmg::testing::write_text;

// The child's peak resident memory must stay under this. gmg on the small fixtures needs about
// 30 MB; the failures of the issue took 1 to 2.6 GB. Under AddressSanitizer the resident size
// also counts shadow memory and the quarantine of freed blocks, so the bound is not checked there.
[[maybe_unused]] inline constexpr long kPeakBoundKb = 200L * 1024;  // (unused in sanitized builds)

struct ChildRun {
  int code = -1;           // exit status; 128 + n when killed by signal n
  bool signalled = false;  // ended by a signal (not by exit)
  bool timed_out = false;  // killed after the time limit
  std::string out, err;    // what it printed
  long peak_kb = 0;        // ru_maxrss
};

// Runs `gmg args...` in `cwd`. With interrupt_after_ms >= 0 it sends `signal` after that long,
// and, when `signal_once` is given, not before that file exists (the child has reached a step).
inline ChildRun run_gmg(const std::vector<std::string>& args, const fs::path& cwd, double timeout_s = 60,
                        int interrupt_after_ms = -1, int signal = SIGINT, const fs::path& signal_once = {}) {
  TempDir io;
  const std::string out_path = io.file("out"), err_path = io.file("err");
  write_text(out_path, "");  // here, not in the child: an early interrupt may stop it before its opens
  write_text(err_path, "");
  std::vector<std::string> argv_text = {GMG_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  argv.reserve(argv_text.size() + 1);
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out < 0 || err < 0 || ::chdir(cwd.c_str()) != 0) ::_exit(126);
    ::dup2(out, 1);
    ::dup2(err, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ChildRun r;
  const auto start = std::chrono::steady_clock::now();
  bool interrupted = false;
  int status = 0;
  rusage usage{};
  while (true) {
    const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::error_code ec;
    if (interrupt_after_ms >= 0 && !interrupted && elapsed * 1000 >= interrupt_after_ms &&
        (signal_once.empty() || fs::exists(signal_once, ec))) {
      ::kill(pid, signal);
      interrupted = true;
    }
    if (elapsed > timeout_s && !r.timed_out) {
      ::kill(pid, SIGKILL);
      r.timed_out = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.signalled = WIFSIGNALED(status);
  r.peak_kb = usage.ru_maxrss;
  r.out = read_file_bytes(out_path);
  r.err = read_file_bytes(err_path);
  return r;
}

inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Every line the child printed on standard error is gmg's own ("gmg: warning: ...", "gmg: error:
// ...", a progress line), never a library's raw line, and holds no byte a terminal acts on.
inline void expect_own_lines_only(const ChildRun& r) {
  for (const std::string& line : split_lines(r.err)) {
    EXPECT_TRUE(line.rfind("gmg: ", 0) == 0 || line.rfind("build: ", 0) == 0 || line.rfind("batch: ", 0) == 0)
        << "a line that is not gmg's: " << line;
    for (char c : line) EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7F) << "raw byte in: " << line;
  }
}

// No file in `dir` is a temporary of gmg's.
inline void expect_no_temporaries(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(temporary_file_owner(e.path().filename().string()), 0) << "left: " << e.path();
}

// Whether the ffmpeg tool runs (the cases that decode MP3 or FLAC, or render, need it).
inline bool have_ffmpeg() { return std::system("ffmpeg -version > /dev/null 2>&1") == 0; }

// Every file below `dir` with its bytes (the fixtures are small).
inline std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_symlink()) {
      files[fs::relative(e.path(), dir).string()] = "-> " + fs::read_symlink(e.path()).string();
    } else if (e.is_regular_file()) {
      files[fs::relative(e.path(), dir).string()] = read_file_bytes(e.path().string());
    } else if (e.is_directory()) {
      files[fs::relative(e.path(), dir).string() + "/"] = "";
    } else {
      files[fs::relative(e.path(), dir).string()] = "(special)";
    }
  }
  return files;
}

inline void expect_bounded(const ChildRun& r) {
  EXPECT_FALSE(r.timed_out) << "gmg hung: " << r.err;
#ifndef GMG_TEST_SANITIZED
  EXPECT_LT(r.peak_kb, kPeakBoundKb) << "peak memory " << r.peak_kb / 1024 << " MB";
#endif
}

// A refusal: exit 1, one line "gmg: error: ..." naming `file` and saying `problem`, bounded.
inline void expect_refused(const ChildRun& r, const std::string& file, const std::string& problem) {
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(r.err.rfind("gmg: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(contains(r.err, file)) << "message should name " << file << ": " << r.err;
  EXPECT_TRUE(contains(r.err, problem)) << "message should say " << problem << ": " << r.err;
  expect_bounded(r);
}

// A usage error: exit 2, one line "gmg: error: ..." saying `problem`, nothing written.
inline void expect_usage_error(const ChildRun& r, const std::string& problem) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("gmg: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(contains(r.err, problem)) << "message should say " << problem << ": " << r.err;
  expect_bounded(r);
}

// A one-joint BVH whose header says `frames` and `frame_time`, with `lines` frame lines.
inline std::string small_bvh(const std::string& frames, const std::string& frame_time, int lines) {
  std::string text =
      "HIERARCHY\nROOT hips\n{\n\tOFFSET 0 0 0\n\tCHANNELS 3 Zrotation Xrotation Yrotation\n"
      "\tEnd Site\n\t{\n\t\tOFFSET 0 1 0\n\t}\n}\nMOTION\nFrames: " +
      frames + "\nFrame Time: " + frame_time + "\n";
  for (int i = 0; i < lines; ++i) text += std::to_string(i % 7) + " 0 " + std::to_string(i % 3) + "\n";
  return text;
}

// A mono 16-bit PCM WAV of `samples` samples at `rate` Hz.
inline std::string small_wav(std::uint32_t rate, std::uint32_t samples) {
  auto le = [](std::string& s, std::uint32_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) s += static_cast<char>((v >> (8 * i)) & 0xFF);
  };
  std::string w = "RIFF";
  le(w, 36 + 2 * samples, 4);
  w += "WAVEfmt ";
  le(w, 16, 4);
  le(w, 1, 2);
  le(w, 1, 2);
  le(w, rate, 4);
  le(w, rate * 2, 4);
  le(w, 2, 2);
  le(w, 16, 2);
  w += "data";
  le(w, 2 * samples, 4);
  for (std::uint32_t i = 0; i < samples; ++i) le(w, (i * 2654435761u) & 0x3FFF, 2);
  return w;
}

// A hand-made graph of 8 frames of a 2-joint skeleton in one clip, with natural edges: a few
// hundred bytes, for the cases that damage what the checksum cannot see.
inline MotionGraph tiny_graph() {
  MotionGraph g;
  Skeleton sk;
  Joint root;
  root.name = "hips";
  root.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition,
                   Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  root.rotation_order = rotation_order_from_channels(root.channels);
  Joint head;
  head.name = "head";
  head.parent = 0;
  head.offset = glm::dvec3(0, 10, 0);
  head.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  head.rotation_order = rotation_order_from_channels(head.channels);
  sk.joints = {root, head};
  g.motion = motion_rest(sk, 30.0, 8);
  g.clips = {{"tiny.bvh", 0, 8}};
  GraphBuilder b(8);
  for (int f = 0; f + 1 < 8; ++f) b.add_edge(f, f + 1, EdgeInfo{0.0});
  b.node(7).kinds = kBreakNode;
  b.finish(g);
  return g;
}

// Made once: ref.{bvh,wav,tsv} (4 s, 8 kHz), new.{wav,tsv} (2 s) and ref.gmg built from ref.
class HostileInput : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    fixtures_ = std::make_unique<TempDir>();
    const fs::path dir = fixtures_->path();
    SynthSpec ref;
    ref.duration_s = 4.0;
    ref.sample_rate = 8000;
    synth_write(synth_speaker(ref), dir.string(), "ref");
    SynthSpec speech;
    speech.duration_s = 2.0;
    speech.sample_rate = 8000;
    speech.seed = 2;
    synth_write(synth_speaker(speech), dir.string(), "new");
    fs::remove(dir / "new.bvh");
    const MotionGraph g = graph_build_from_files(
        {{(dir / "ref.bvh").string(), {(dir / "ref.wav").string(), (dir / "ref.tsv").string()}}}, Config{});
    graph_save((dir / "ref.gmg").string(), g);
  }
  static void TearDownTestSuite() { fixtures_.reset(); }

  // Copies fixtures into the test's own folder.
  void copy(std::initializer_list<const char*> names) const {
    for (const char* n : names) fs::copy_file(fixtures_->path() / n, work_.path() / n);
  }
  std::string at(const std::string& name) const { return work_.file(name); }
  ChildRun gmg(const std::vector<std::string>& args, double timeout_s = 60) const {
    return run_gmg(args, work_.path(), timeout_s);
  }
  // The work folder is exactly as before the command.
  void expect_unchanged(const std::map<std::string, std::string>& before) const {
    EXPECT_EQ(snapshot(work_.path()), before) << "a file was left, removed or changed";
  }

  TempDir work_;
  static inline std::unique_ptr<TempDir> fixtures_;
};

}  // namespace gmg::hostile
