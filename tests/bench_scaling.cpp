// Benchmark: how graph building grows with the reference's length. Prints figures; asserts nothing
// about time (machines are shared and noisy).
//
//   build/bench_scaling [--hours 0.25,1,2,4] [--joints 25] [--runs 1] [--cliff] [--reenact]
//                       [--set KEY=VALUE ...]
//
// For each length, one synthetic speaker (`gmg synth --joints J --seed 3 --duration S`, written
// into a temporary folder, not timed) is built with the `gmg` binary as a child process: wall and
// CPU time and peak memory (wait4's rusage; min / median / max over --runs), then the graph's
// transitions and mean out-degree (`gmg inspect --json`). Lengths over 1 h are written as clips of
// at most 1 h (seeds 3, 4, 5, ...) and built with `gmg build --clips`. Under the table: the growth
// exponent of the build's CPU time and of the edges between the shortest and the longest length
// (1 = linear), the out-degree of the longest over the shortest, and what its growth is made of:
// the share of frames with a transition, and the transitions of each such frame.
// --cliff builds 14,970 and 15,030 frames (either side of the default exact_frames) and prints
// their transitions. --reenact also reenacts 77 s of synthetic speech (seed 99) from each graph.
// --set (repeatable) hands a parameter to every `gmg build`, to measure how another setting grows
// (`--set max_transitions=3`, `--set neighbours=approximate`) against the defaults' table.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/benchmark_support.h"
#include "tests/test_support.h"

namespace {

using gmg::bench::CommandRun;
using gmg::bench::median;
using gmg::bench::run_command;

// A number after "key": in a one-line JSON object.
double json_number(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\":");
  return at == std::string::npos ? std::nan("") : std::atof(json.c_str() + at + key.size() + 3);
}

struct Row {
  double seconds = 0;
  double frames = 0, edges = 0, degree = 0, file_mb = 0;
  double share = 0;  // of the frames with at least one transition
  std::vector<double> wall, cpu, rss;
  CommandRun reenact;
};

// Writes the speaker of `seconds` into dir/clips_<tag>/ as clips of at most an hour.
std::string write_speaker(const std::string& dir, const std::string& tag, double seconds, int joints) {
  std::string clips = dir + "/clips_" + tag;
  std::filesystem::create_directories(clips);
  int part = 0;
  for (double left = seconds; left > 1e-9; left -= 3600.0, ++part) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "part%03d", part);
    run_command({GMG_BINARY, "synth", "-o", clips, "--stem", stem, "--joints", std::to_string(joints), "--seed",
                 std::to_string(3 + part), "--duration", std::to_string(std::min(left, 3600.0))});
  }
  return clips;
}

Row measure(const std::string& dir, double seconds, int joints, int runs, bool reenact,
            const std::vector<std::string>& sets) {
  Row row;
  row.seconds = seconds;
  char tag[32];
  std::snprintf(tag, sizeof tag, "%.0f", seconds);
  const std::string clips = write_speaker(dir, tag, seconds, joints);
  const std::string graph = dir + "/g" + tag + ".gmg";
  std::vector<std::string> build = {GMG_BINARY, "build", "--clips", clips, "-o", graph, "--progress", "none"};
  for (const std::string& s : sets) build.insert(build.end(), {"--set", s});
  for (int i = 0; i < runs; ++i) {
    const CommandRun r = run_command(build);
    row.wall.push_back(r.wall);
    row.cpu.push_back(r.cpu);
    row.rss.push_back(r.rss_mb);
  }
  const std::string json_path = dir + "/inspect.json";
  run_command({GMG_BINARY, "inspect", "--json", graph}, json_path);
  std::ostringstream json;
  json << std::ifstream(json_path).rdbuf();
  row.frames = json_number(json.str(), "frames");
  row.edges = json_number(json.str(), "unnatural_edges");
  row.degree = json_number(json.str(), "mean_out_degree");
  row.share = json_number(json.str(), "share_with_transition");
  row.file_mb = static_cast<double>(std::filesystem::file_size(graph)) / (1024.0 * 1024.0);
  if (reenact) {
    if (!std::filesystem::exists(dir + "/t77.wav"))
      run_command({GMG_BINARY, "synth", "-o", dir, "--stem", "t77", "--joints", std::to_string(joints), "--seed", "99",
                   "--duration", "77", "--no-motion"});
    row.reenact = run_command({GMG_BINARY, "reenact", "--graph", graph, "--audio", dir + "/t77.wav", "--transcript",
                               dir + "/t77.tsv", "-o", dir + "/t77.bvh"});
  }
  std::filesystem::remove_all(clips);
  std::filesystem::remove(graph);
  return row;
}

void print_row(const Row& r, bool reenact) {
  std::printf("| %.0f s | %.0f | %.2f / %.2f s | %.0f MiB | %.0f | %.2f | %.0f MiB |", r.seconds, r.frames,
              median(r.cpu), median(r.wall), median(r.rss), r.edges, r.degree, r.file_mb);
  if (reenact) std::printf(" %.2f s, %.0f MiB |", r.reenact.cpu, r.reenact.rss_mb);
  std::printf("\n");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> hours = {0.25, 1, 2, 4};
  int joints = 25, runs = 1;
  bool cliff = false, reenact = false;
  std::vector<std::string> sets;  // --set KEY=VALUE, handed to every build
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--hours" && i + 1 < argc) {
      hours.clear();
      std::stringstream list(argv[++i]);
      for (std::string h; std::getline(list, h, ',');) hours.push_back(std::atof(h.c_str()));
    } else if (a == "--joints" && i + 1 < argc) {
      joints = std::max(22, std::atoi(argv[++i]));
    } else if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--cliff") {
      cliff = true;
    } else if (a == "--reenact") {
      reenact = true;
    } else if (a == "--set" && i + 1 < argc && std::strchr(argv[i + 1], '=') != nullptr) {
      sets.emplace_back(argv[++i]);
    } else {
      std::fprintf(stderr,
                   "usage: bench_scaling [--hours 0.25,1,2,4] [--joints 25] [--runs 1] [--cliff] [--reenact] "
                   "[--set KEY=VALUE ...]\n");
      return 2;
    }
  }
  const gmg::testing::TempDir dir;
  const std::string d = dir.path().string();
  std::printf("gmg build of synthetic speakers, %d joints, %d run(s) each (CPU and wall: median)", joints, runs);
  for (const std::string& s : sets) std::printf(", --set %s", s.c_str());
  std::printf("\n\n");
  std::printf("| length | frames | build CPU / wall | peak RSS | transitions | mean out-degree | graph file |%s\n",
              reenact ? " reenact 77 s: CPU, peak RSS |" : "");
  std::printf("| --- | --- | --- | --- | --- | --- | --- |%s\n", reenact ? " --- |" : "");
  std::vector<Row> rows;
  for (const double h : hours) {
    rows.push_back(measure(d, h * 3600.0, joints, runs, reenact, sets));
    print_row(rows.back(), reenact);
  }
  if (rows.size() >= 2) {
    const Row &a = rows.front(), &b = rows.back();
    const double span = std::log(b.frames / a.frames);
    std::printf(
        "\nfrom %.0f to %.0f frames: build CPU grows as frames^%.2f, transitions as frames^%.2f; "
        "mean out-degree %.2f x the shortest's\n",
        a.frames, b.frames, std::log(median(b.cpu) / median(a.cpu)) / span, std::log(b.edges / a.edges) / span,
        b.degree / a.degree);
    // The out-degree's growth split: more frames with a transition at all, or more transitions for
    // those that have one (at most max_transitions).
    auto per_frame = [](const Row& r) { return r.edges / (r.frames * r.share); };
    if (a.share > 0 && b.share > 0)
      std::printf("frames with a transition: %.1f %% and %.1f %%; transitions of each: %.2f and %.2f (%.2f x)\n",
                  100.0 * a.share, 100.0 * b.share, per_frame(a), per_frame(b), per_frame(b) / per_frame(a));
  }
  if (cliff) {
    std::printf("\neither side of exact_frames (15,000):\n");
    const Row below = measure(d, 14970.0 / 30.0, joints, 1, false, sets);
    const Row above = measure(d, 15030.0 / 30.0, joints, 1, false, sets);
    std::printf("  %.0f frames: %.0f transitions, %.2f s CPU; %.0f frames: %.0f transitions, %.2f s CPU (%+.1f %%)\n",
                below.frames, below.edges, median(below.cpu), above.frames, above.edges, median(above.cpu),
                100.0 * (above.edges / below.edges - 1.0));
  }
  return 0;
}
