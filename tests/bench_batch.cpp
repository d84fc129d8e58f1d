// Benchmark of `gmg batch` at the paper's scale (section 5.1.1): 70 test clips of 62 s on average
// against reference clips of about 170 s, on all cores. Synthetic speakers (engine/synth.h) stand
// in for GENEA data; generating them is not timed.
//
//   random_pool70:          pool of 70 references, seeded random pairing (the paper's protocol;
//                           about 44 distinct references get drawn, each graph built once)
//   one_reference_per_clip: test i paired with reference i by a manifest, so 70 graphs are built
//                           (the worst case, as with a large pool such as GENEA's training set)
//
// Counters: total_s (wall time of batch_run), clips_per_s, clip_mean_s (a clip's own work: speech
// analysis, search, blending, writing), graphs (built), graph_mean_s / graph_total_s (build
// times; builds run on the workers, so they overlap), fallbacks_per_clip, failed, setup_s.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "engine/batch/batch.h"
#include "engine/core/parallel.h"
#include "engine/synth/synth.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kClips = 70;
constexpr int kReferences = 70;

struct BenchData {
  testing::TempDir dir;
  std::string pool, tests, pairs_one_to_one;
  double setup_s = 0, ref_mean_s = 0, test_mean_s = 0;
};

std::string stem(const char* prefix, int i) {
  std::ostringstream os;
  os << prefix << (i < 10 ? "0" : "") << i;
  return os.str();
}

// Generated once, on all cores: references of 160-180 s (mean 170) in a GENEA-style pool folder,
// test clips of 55-69 s (mean 62) as flat WAV + TSV.
const BenchData& bench_data() {
  static const std::unique_ptr<BenchData> data = [] {
    auto d = std::make_unique<BenchData>();
    const Clock::time_point t0 = Clock::now();
    d->pool = (d->dir.path() / "pool").string();
    d->tests = (d->dir.path() / "tests").string();
    for (const char* sub : {"bvh", "wav", "tsv"}) fs::create_directories(fs::path(d->pool) / sub);
    fs::create_directories(d->tests);
    fs::create_directories(fs::path(d->pool) / "scratch");
    std::mutex m;
    double ref_total = 0, test_total = 0;
    const std::size_t items = kReferences + kClips;
    parallel_for(items, worker_count(0, items), [&](std::size_t item, int) {
      const int k = static_cast<int>(item);
      SynthSpec s;
      if (k < kReferences) {
        s.duration_s = 160.0 + 20.0 * ((k * 37) % kReferences) / (kReferences - 1);
        s.seed = 1000 + static_cast<std::uint64_t>(k);
        s.style = (k % 11) / 10.0;
        const std::string name = stem("ref_", k);
        synth_write(synth_speaker(s), (fs::path(d->pool) / "scratch").string(), name);
        for (const char* ext : {"bvh", "wav", "tsv"})
          fs::rename(fs::path(d->pool) / "scratch" / (name + "." + ext), fs::path(d->pool) / ext / (name + "." + ext));
        std::lock_guard<std::mutex> lock(m);
        ref_total += s.duration_s;
      } else {
        const int i = k - kReferences;
        s.duration_s = 55.0 + 14.0 * ((i * 29) % kClips) / (kClips - 1);
        s.seed = 5000 + static_cast<std::uint64_t>(i);
        s.style = ((i + 5) % 11) / 10.0;
        const std::string name = stem("test_", i);
        synth_write(synth_speaker(s), d->tests, name);
        fs::remove(fs::path(d->tests) / (name + ".bvh"));  // a test clip is speech only
        std::lock_guard<std::mutex> lock(m);
        test_total += s.duration_s;
      }
    });
    fs::remove_all(fs::path(d->pool) / "scratch");
    d->pairs_one_to_one = (d->dir.path() / "pairs_one_to_one.csv").string();
    {
      std::string csv = "test_stem,reference_stem\n";
      for (int i = 0; i < kClips; ++i) csv += stem("test_", i) + "," + stem("ref_", i % kReferences) + "\n";
      testing::write_text(d->pairs_one_to_one, csv);
    }
    d->ref_mean_s = ref_total / kReferences;
    d->test_mean_s = test_total / kClips;
    d->setup_s = std::chrono::duration<double>(Clock::now() - t0).count();
    return d;
  }();
  return *data;
}

void BM_Batch(benchmark::State& state, bool one_reference_per_clip) {
  const BenchData& d = bench_data();
  for (auto _ : state) {
    testing::TempDir out;
    BatchOptions o;
    o.pool_dirs = {d.pool};
    o.test_dirs = {d.tests};
    o.output_dir = out.path().string();
    o.seed = 20231009;
    o.jobs = 0;  // all cores
    o.progress = BatchProgress::Quiet;
    if (one_reference_per_clip) o.pairs_manifest = d.pairs_one_to_one;
    const Clock::time_point t0 = Clock::now();
    const BatchSummary s = batch_run(o, Config{}, std::cerr);
    const double total = std::chrono::duration<double>(Clock::now() - t0).count();
    state.SetIterationTime(total);

    double clip_total = 0;
    long fallbacks = 0;
    for (const BatchClipResult& c : s.clips) {
      clip_total += c.seconds;
      fallbacks += c.fallbacks;
    }
    int graphs = 0;
    for (const BatchReferenceResult& r : s.references)
      if (r.frames > 0) ++graphs;
    state.counters["total_s"] = total;
    state.counters["clips_per_s"] = s.clips.size() / total;
    state.counters["clip_mean_s"] = clip_total / std::max<std::size_t>(1, s.clips.size());
    state.counters["graphs"] = graphs;
    state.counters["graph_total_s"] = s.graph_seconds;
    state.counters["graph_mean_s"] = s.graph_seconds / std::max(1, graphs);
    state.counters["fallbacks_per_clip"] = static_cast<double>(fallbacks) / std::max<std::size_t>(1, s.clips.size());
    state.counters["failed"] = s.failed;
    state.counters["jobs"] = s.jobs;
    state.counters["setup_s"] = d.setup_s;
    state.counters["ref_mean_len_s"] = d.ref_mean_s;
    state.counters["test_mean_len_s"] = d.test_mean_s;
    if (s.failed > 0 || s.ok != kClips) state.SkipWithError("some clips failed");
  }
}

BENCHMARK_CAPTURE(BM_Batch, random_pool70, false)->UseManualTime()->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_Batch, one_reference_per_clip, true)->UseManualTime()->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace gmg

BENCHMARK_MAIN();
