// Benchmark: graph construction and reenactment speed and memory. Prints figures; asserts
// nothing about time (machines are shared and noisy). Run: build/bench_graph
//
//  1. graph of beat2_scott/2_scott_0_1_1 (1906 frames), when ../shared/data is present;
//  2. graph of a synthetic 427 s reference (12,810 frames, the paper's longest), 25 joints;
//  3. reenacting a synthetic 77 s test speech from that graph (the paper's longest test clip).
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <sys/resource.h>

#include "audio/wav.h"
#include "engine/app/pipeline.h"
#include "engine/app/synth/synth.h"
#include "graph/build.h"
#include "graph/stats.h"
#include "tests/test_support.h"

using namespace gmg;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

void print_graph(const char* what, const MotionGraph& g, double secs) {
  const GraphStats s = graph_stats(g);
  std::printf(
      "%s: %d frames, %d joints: graph built in %.3f s; %ld transitions, %d onset / %d keyword / %d break nodes; "
      "peak RSS so far %.1f MB\n",
      what, s.frames, g.motion.joint_count(), secs, s.unnatural_edges, s.onset_nodes, s.keyword_nodes, s.break_nodes,
      peak_rss_mb());
}

// Graph construction alone (features + continuity analysis), from clips already in memory.
MotionGraph timed_build(const SynthClip& clip, const char* what, const Config& cfg) {
  ClipEvents c;
  c.name = what;
  c.motion = clip.motion;
  const text::Lexicon lexicon = lexicon_for(cfg.graph);
  const SpeechEvents ev =
      speech_events(clip.audio, &clip.words, what, clip.motion.fps, clip.motion.frame_count, cfg.graph, lexicon);
  c.onset_frames = ev.onset_frames;
  c.keyword_frames = ev.keyword_frames;
  const auto t0 = std::chrono::steady_clock::now();
  MotionGraph g = graph_build({c}, cfg.graph);
  print_graph(what, g, seconds_since(t0));
  return g;
}

// A 25-joint (GENEA-sized) synthetic speaker of the given length.
SynthClip synthetic_clip(double seconds, std::uint64_t seed) {
  SynthSpec spec;
  spec.duration_s = seconds;
  spec.seed = seed;
  spec.joint_count_hint = 25;
  return synth_speaker(spec);
}

// Builds and reports the graph of a synthetic reference, with the growth of peak memory.
MotionGraph synthetic_graph(double seconds, const Config& cfg) {
  const SynthClip clip = synthetic_clip(seconds, 3);
  const double before = peak_rss_mb();
  char name[64];
  std::snprintf(name, sizeof name, "synthetic %.1f s", seconds);
  MotionGraph g = timed_build(clip, name, cfg);
  std::printf("  peak RSS grew by %.1f MB during the build\n", peak_rss_mb() - before);
  return g;
}

}  // namespace

int main() {
  const Config cfg;
  const std::string data = gmg::testing::shared_data_dir();
  if (!data.empty()) {
    const auto t0 = std::chrono::steady_clock::now();
    const MotionGraph g = graph_build_from_files(
        {{data + "/beat2_scott/2_scott_0_1_1.bvh",
          {data + "/beat2_scott/2_scott_0_1_1.wav", data + "/beat2_scott/2_scott_0_1_1.TextGrid"}}},
        cfg);
    print_graph("2_scott_0_1_1 (including BVH, WAV, TextGrid reading and onset detection)", g, seconds_since(t0));
  } else {
    std::printf("../shared/data is absent: skipping the 2_scott_0_1_1 figure\n");
  }

  // Memory must grow linearly with frames: a half-length reference first (so its peak is
  // already counted when the full one is measured), then the full one.
  synthetic_graph(213.5, cfg);
  const MotionGraph g = synthetic_graph(427.0, cfg);

  const SynthClip speech = synthetic_clip(77.0, 4);
  const text::Lexicon lexicon = lexicon_for(cfg.graph);
  auto t0 = std::chrono::steady_clock::now();
  const SpeechEvents ev = speech_events(speech.audio, &speech.words, "test", g.motion.fps, -1, cfg.graph, lexicon);
  const double analyse = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const Reenactment r = reenact_events(g, ev, cfg);
  const double search = seconds_since(t0);
  std::printf(
      "reenact 77 s (%d frames, %zu subsequences) from the 427 s graph: speech analysis %.3f s, "
      "search + blending %.3f s, total %.3f s (one core)\n",
      ev.total_frames, r.plan.segments.size(), analyse, search, analyse + search);
  std::printf("  fallbacks: %s, failures %d\n", r.report["totals"]["fallbacks"].dump().c_str(), r.plan.failure_count());
  return 0;
}
