// Benchmark: graph construction and reenactment speed and memory. Prints figures; asserts
// nothing about time (machines are shared and noisy). Run: build/bench_graph [--runs N] [--quick]
// or build/bench_graph --onsets FILE.wav [--onset-runs N] for the WAV reader and the onset analysis
// alone on any recording (e.g. a 1 h one from `gmg synth`).
//
// Whole commands (the gmg binary run as a child process, wall and CPU time and peak memory from
// wait4's rusage, min / median / max over N runs, 3 by default):
//  1. gmg build of beat2_scott/2_scott_0_1_1 (1,906 frames), when ../shared/data is present;
//  2. gmg build of a synthetic 427 s speaker (12,810 frames, the paper's longest reference);
//  3. gmg build of a synthetic 1 h speaker (108,000 frames) and gmg reenact of a 77 s speech
//     (the paper's longest test clip) from its graph (left out with --quick).
// Onset analysis alone (audio::detect_onsets on the 64 s 2_scott_0_1_1.wav, already read, 21
// runs), then whole `gmg reenact` commands from the BEAT2 graph, when ../shared/data is present.
// In memory (one run each): the graph build alone (features and transitions, clips already read)
// at half and full 427 s, so memory growth can be seen, and reenacting 77 s from the 427 s graph.
// The synthetic speakers are written with `gmg synth` (25 joints) into a temporary folder first.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "audio/onset.h"
#include "audio/wav.h"
#include "engine/pipeline/pipeline.h"
#include "engine/synth/synth.h"
#include "graph/build.h"
#include "graph/stats.h"
#include "tests/benchmark_support.h"
#include "tests/test_support.h"

using namespace gmg;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

using bench::CommandRun;
using bench::peak_rss_mb;
using bench::run_command;
using bench::spread;
using bench::Spread;
using bench::thread_cpu_seconds;

// Runs a command `runs` times and prints min / median / max of its wall, CPU and memory.
void whole_command(const char* what, const std::vector<std::string>& args, int runs) {
  std::vector<double> wall, cpu, rss;
  for (int i = 0; i < runs; ++i) {
    const CommandRun r = run_command(args);
    wall.push_back(r.wall);
    cpu.push_back(r.cpu);
    rss.push_back(r.rss_mb);
  }
  const Spread w = spread(wall), c = spread(cpu), m = spread(rss);
  std::printf(
      "%s (%d runs, min / median / max):\n  wall %.2f / %.2f / %.2f s, CPU %.2f / %.2f / %.2f s, "
      "peak RSS %.0f / %.0f / %.0f MiB\n",
      what, runs, w.min, w.median, w.max, c.min, c.median, c.max, m.min, m.median, m.max);
  std::fflush(stdout);
}

// `gmg build` of a clip into `graph`, timed; then the graph's counts (one more, untimed build is
// not needed: the last run's file is there).
void bench_build(const char* what, const std::string& stem, const std::string& transcript, const std::string& graph,
                 int runs) {
  whole_command(what,
                {GMG_BINARY, "build", "--motion", stem + ".bvh", "--audio", stem + ".wav", "--transcript", transcript,
                 "-o", graph, "--progress", "none"},
                runs);
}

void print_graph(const char* what, const MotionGraph& g, double secs) {
  const GraphStats s = graph_stats(g);
  std::printf(
      "%s: %d frames, %d joints: graph built in %.3f s; %ld transitions, %d onset / %d keyword / %d break nodes; "
      "peak RSS so far %.1f MB\n",
      what, s.frames, g.motion.joint_count(), secs, s.unnatural_edges, s.onset_nodes, s.keyword_nodes, s.break_nodes,
      peak_rss_mb());
}

// A 25-joint (GENEA-sized) synthetic speaker of the given length.
SynthClip synthetic_clip(double seconds, std::uint64_t seed) {
  SynthSpec spec;
  spec.duration_s = seconds;
  spec.seed = seed;
  spec.joint_count_hint = 25;
  return synth_speaker(spec);
}

// Graph construction alone (features + continuity analysis), from a clip already in memory.
MotionGraph timed_build(const SynthClip& clip, const char* what, const Config& cfg) {
  ClipEvents c;
  c.name = what;
  c.motion = clip.motion;
  const text::Lexicon lexicon = lexicon_for(cfg.graph);
  const SpeechEvents ev =
      speech_events(clip.audio, &clip.words, what, clip.motion.fps, clip.motion.frame_count, cfg.graph, lexicon);
  c.onset_frames = ev.onset_frames;
  c.keyword_frames = ev.keyword_frames;
  const double before = peak_rss_mb();
  const auto t0 = std::chrono::steady_clock::now();
  MotionGraph g = graph_build({c}, cfg.graph);
  print_graph(what, g, seconds_since(t0));
  std::printf("  peak RSS grew by %.1f MB during the build\n", peak_rss_mb() - before);
  return g;
}

void in_memory_figures(const Config& cfg) {
  timed_build(synthetic_clip(213.5, 3), "in memory, synthetic 213.5 s", cfg);
  const MotionGraph g = timed_build(synthetic_clip(427.0, 3), "in memory, synthetic 427 s", cfg);
  const SynthClip speech = synthetic_clip(77.0, 4);
  const text::Lexicon lexicon = lexicon_for(cfg.graph);
  auto t0 = std::chrono::steady_clock::now();
  const SpeechEvents ev = speech_events(speech.audio, &speech.words, "test", g.motion.fps, -1, cfg.graph, lexicon);
  const double analyse = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const Reenactment r = reenact_events(g, ev, cfg);
  const double search = seconds_since(t0);
  std::printf(
      "in memory, reenact 77 s (%d frames, %zu subsequences) from the 427 s graph: speech analysis %.3f s, "
      "search + blending %.3f s, total %.3f s (one core)\n",
      ev.total_frames, r.plan.segments.size(), analyse, search, analyse + search);
}

// audio::read_wav alone: min / median / max milliseconds.
void read_figures(const std::string& wav, int runs) {
  std::vector<double> cpu;
  for (int i = 0; i < runs; ++i) {
    const double c0 = thread_cpu_seconds();
    const audio::Audio audio = audio::read_wav(wav);
    cpu.push_back((thread_cpu_seconds() - c0) * 1000.0);
  }
  const Spread c = spread(cpu);
  std::printf("read_wav alone, %s (%d runs, min / median / max):\n  CPU %.1f / %.1f / %.1f ms\n",
              std::filesystem::path(wav).filename().c_str(), runs, c.min, c.median, c.max);
  std::fflush(stdout);
}

// audio::detect_onsets alone on a clip already in memory: min / median / max milliseconds.
void onset_figures(const std::string& wav, int runs = 21) {
  const audio::Audio audio = audio::read_wav(wav);
  std::vector<double> wall, cpu;
  std::size_t onsets = 0;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = thread_cpu_seconds();
    const audio::OnsetAnalysis a = audio::detect_onsets(audio, audio::OnsetParams{});
    cpu.push_back((thread_cpu_seconds() - c0) * 1000.0);
    wall.push_back(seconds_since(t0) * 1000.0);
    onsets = a.onset_frames.size();
  }
  const Spread w = spread(wall), c = spread(cpu);
  std::printf(
      "onset analysis alone, %s (%.1f s at %d Hz, %zu onsets; %d runs, min / median / max):\n"
      "  CPU %.1f / %.1f / %.1f ms, wall %.1f / %.1f / %.1f ms\n",
      std::filesystem::path(wav).filename().c_str(), static_cast<double>(audio.samples.size()) / audio.sample_rate,
      audio.sample_rate, onsets, runs, c.min, c.median, c.max, w.min, w.median, w.max);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3, onset_runs = 21;
  bool quick = false;
  std::string onsets_of;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
    if (std::strcmp(argv[i], "--quick") == 0) quick = true;
    if (std::strcmp(argv[i], "--onsets") == 0 && i + 1 < argc) onsets_of = argv[++i];
    if (std::strcmp(argv[i], "--onset-runs") == 0 && i + 1 < argc) onset_runs = std::max(1, std::atoi(argv[++i]));
  }
  if (!onsets_of.empty()) {
    try {
      read_figures(onsets_of, onset_runs);
      onset_figures(onsets_of, onset_runs);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench_graph: %s\n", e.what());
      return 1;
    }
    return 0;
  }
  const gmg::testing::TempDir dir;
  const std::string d = dir.path().string();
  const std::string data = gmg::testing::shared_data_dir();
  if (!data.empty()) {
    bench_build("gmg build 2_scott_0_1_1 (1,906 frames)", data + "/beat2_scott/2_scott_0_1_1",
                data + "/beat2_scott/2_scott_0_1_1.TextGrid", d + "/beat2.gmg", runs);
    onset_figures(data + "/beat2_scott/2_scott_0_1_1.wav");
    whole_command(
        "gmg reenact 2_scott_0_2_2 (60 s) from the 2_scott_0_1_1 graph",
        {GMG_BINARY, "reenact", "--graph", d + "/beat2.gmg", "--audio", data + "/beat2_scott/2_scott_0_2_2.wav",
         "--transcript", data + "/beat2_scott/2_scott_0_2_2.TextGrid", "-o", d + "/beat2_0_2_2.bvh"},
        runs);
  } else {
    std::printf("../shared/data is absent: skipping the 2_scott_0_1_1 figure\n");
  }
  // The same speakers as `gmg synth --joints 25 --seed 3 --duration S` (and seed 4 for the speech).
  synth_write(synthetic_clip(427.0, 3), d, "s427");
  bench_build("gmg build synthetic 427 s (12,810 frames)", d + "/s427", d + "/s427.tsv", d + "/s427.gmg", runs);
  if (!quick) {
    synth_write(synthetic_clip(3600.0, 3), d, "s3600");
    bench_build("gmg build synthetic 1 h (108,000 frames)", d + "/s3600", d + "/s3600.tsv", d + "/s3600.gmg", runs);
    synth_write(synthetic_clip(77.0, 4), d, "t77");
    whole_command("gmg reenact 77 s from the 1 h graph",
                  {GMG_BINARY, "reenact", "--graph", d + "/s3600.gmg", "--audio", d + "/t77.wav", "--transcript",
                   d + "/t77.tsv", "-o", d + "/t77.bvh"},
                  runs);
  }
  in_memory_figures(Config{});
  return 0;
}
