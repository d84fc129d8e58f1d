// A graph file that is cut short while `gmg reenact` reads it (the graph is served from its
// mapping, so it is read all through the command): every run ends in success (the cut came after
// the graph was used) or in one line "gmg: error: FILE: ..." with exit 1, never in a signal death
// (SIGBUS, exit 135, was what the unprotected mapping gave). scripts/truncation_stress.sh does the
// same 200 times.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "engine/core/files.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using testing::TempDir;

struct Ended {
  int code = -1;  // exit status; 128 + n when killed by signal n
  std::string err;
};

// Runs `gmg args...` with stderr to a file; after `cut_after_ms` truncates `victim` to `cut_to`.
Ended run_and_cut(const std::vector<std::string>& args, const std::string& victim, int cut_after_ms, off_t cut_to,
                  const std::string& err_path) {
  std::vector<std::string> text = {GMG_BINARY};
  text.insert(text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  argv.reserve(text.size() + 1);
  for (std::string& a : text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (null < 0 || err < 0) ::_exit(126);
    ::dup2(null, 1);
    ::dup2(err, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(cut_after_ms));
  EXPECT_EQ(::truncate(victim.c_str(), cut_to), 0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  Ended e;
  e.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  e.err = read_file_bytes(err_path);
  return e;
}

TEST(GraphInUse, CutShortWhileReenactingIsAnErrorNeverASignal) {
  TempDir dir;
  const std::string gmg = GMG_BINARY;
  const auto run = [&](const std::vector<std::string>& args) {
    std::vector<std::string> text = {gmg};
    text.insert(text.end(), args.begin(), args.end());
    std::string line;
    for (const std::string& a : text) line += "'" + a + "' ";
    ASSERT_EQ(std::system((line + ">/dev/null 2>&1").c_str()), 0) << line;
  };
  run({"synth", "-o", dir.path().string(), "--stem", "ref", "--duration", "60", "--seed", "1"});
  run({"synth", "-o", dir.path().string(), "--stem", "new", "--duration", "30", "--seed", "2", "--no-motion"});
  run({"build", "--motion", dir.file("ref.bvh"), "--audio", dir.file("ref.wav"), "-o", dir.file("ref.gmg")});
  const std::string graph = read_file_bytes(dir.file("ref.gmg"));
  // How long one reenactment takes, so the cuts are spread over it.
  const auto t0 = std::chrono::steady_clock::now();
  run({"reenact", "--graph", dir.file("ref.gmg"), "--audio", dir.file("new.wav"), "-o", dir.file("out.bvh")});
  const int span_ms =
      1 + static_cast<int>(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  constexpr int kRuns = 24;
  int finished = 0, refused = 0;
  for (int i = 0; i < kRuns; ++i) {
    const std::string victim = dir.file("cut.gmg");
    testing::write_text(victim, graph);
    const Ended e = run_and_cut(
        {"reenact", "--graph", victim, "--audio", dir.file("new.wav"), "-o", dir.file("cut.bvh")}, victim,
        i * span_ms / kRuns, static_cast<off_t>(graph.size() / static_cast<std::size_t>(kRuns) * i), dir.file("err"));
    ASSERT_LT(e.code, 128) << "run " << i << " was killed by signal " << e.code - 128;
    if (e.code == 0) {
      ++finished;
      continue;
    }
    EXPECT_EQ(e.code, 1) << e.err;
    EXPECT_EQ(e.err.rfind("gmg: error: " + victim + ": ", 0), 0u) << e.err;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << e.err;
    ++refused;
  }
  // Most cuts fall while the graph is in use (each would have been a SIGBUS).
  EXPECT_GT(refused, kRuns / 3) << finished << " runs finished before the cut";
}

}  // namespace
}  // namespace gmg
