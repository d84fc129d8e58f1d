// Benchmark: the graph build's candidate search (graph/neighbours.h) with our k-d tree against
// FLANN (libflann-dev), and against hnswlib's graphs (libhnswlib-dev, when found; --hnsw), at equal
// recall. Prints figures; asserts nothing about time (machines are shared and noisy). Built only
// when FLANN is found (see CMakeLists.txt).
//
// Run: build/bench_flann [--hours 1,2,4] [--queries 20480] [--block 128] [--repeat 3] [--brute 32]
//                        [--ours-checks 2000,1000,500]
//                        [--kprime 192,256] [--checks 256,...,4096] [--spaces full,proj]
//                        [--indexes kd4,kd8,kmeans,hier (or space:index, e.g. proj:hier)]
//                        [--cluster-hours 1] [--autotune-hours 0]
//                        [--hnsw full,proj] [--hnsw-graphs 16x100 (M x ef_construction)]
//                        [--ef 256,384,512,768,1024] [--propagate 0,1]
//
// For each length: a synthetic speaker (engine/synth, 25 joints, seed 3, as bench_graph; audio at
// 8 kHz, which the motion does not depend on, and dropped at once), its pose features computed a
// piece at a time as graph_build does (clip_features), breaks from capture jumps as the build marks
// them, theta from continuity_thresholds, GraphParams defaults (k = 4 * 32 = 128, l_pn 10).
//
// Query frames: `queries` frames in blocks of `block` consecutive frames at random non-overlapping
// places (seeded, the same for every method of a length); our search is asked for each frame of a
// block, the block's frames spread over the workers. Every index is built over all frames.
//
// 1. Ours: CandidateSearch (Approximate) with ann_checks 0 (exact: the reference K_l),
//    2000, 1000, 500 (--ours-checks), on 1 worker. (With a budget, find searches the frame with
//    the other 15 frames of its leaf, as the build does; asked frame by frame, as here, each leaf
//    is walked once per frame asked, so the budgeted rows' query times are an upper bound.) The
//    exact reference is checked against a brute-force scan of all frames (in double) for `brute`
//    of the query frames. With --propagate widths, each budgeted row is followed by its lists handed
//    on between consecutive query frames (propagate), chained and from the neighbours' own lists,
//    and by the rows of a lean pass of the second kind, timed as a build would make it.
// 2. FLANN: d = lp ||dp|| + lv ||dv|| is a sum of two norms, which FLANN cannot search. It indexes
//    one Euclidean space whose norm N bounds d from below:
//      full: the features [lp (p - mean_p); lv (v - mean_v)] (rows that are 0 in every frame, the
//            root's, left out): d / sqrt(2) <= N <= d;
//      proj: the principal-axis projections of graph/pose_space.h scaled by lp and lv (at most 16
//            numbers): N <= d.
//    knnSearch with k' neighbours and `checks` (for each index and k', checks ascending until the
//    recall reaches 0.95), then every result r refined as K_l is defined: allowed (r != l, l + 1,
//    |r - l| > l_pn), N <= theta_l (a cheap reject: N <= d), d(l, r) <= theta_l, the k nearest
//    by (d, r), with our finder's own gathering (graph/candidate_gathering.h: d screened in float,
//    decided in double near theta and the k-th), so the result is exact over FLANN's candidates.
//    The refinement is part of the query time (and its column); its pose space of the build.
// 3. hnswlib (--hnsw, in the same spaces): an HNSW graph over all frames per M x ef_construction,
//    built on 2 threads (its CPU time in the build column), searched for k' with each ef >= k' until
//    the recall reaches 0.95, refined as FLANN's are. Not in the repeated fastest (step 4).
// Times: index build (for ours the finder's construction: pose space and tree), queries in CPU
// seconds of the process (every thread) and wall seconds. The fastest setting of each with recall
// >= 0.95 (by build + query CPU scaled to all frames) is then timed `repeat` more times, on 1 and
// 2 workers (ours) or cores (FLANN, OpenMP): median and spread printed.
//
// The searches compared: tests/bench_flann_methods.h; the lists handed on between frames:
// tests/bench_flann_propagate.h.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include <flann/flann.hpp>
#ifdef GMG_HAVE_HNSWLIB
#include <hnswlib/hnswlib.h>
#endif

#include "engine/core/parallel.h"
#include "engine/synth/synth.h"
#include "graph/breaks.h"
#include "graph/candidate_gathering.h"
#include "graph/continuity.h"
#include "graph/features.h"
#include "graph/neighbours.h"
#include "graph/params.h"
#include "graph/pose_space.h"
#include "tests/bench_flann_methods.h"
#include "tests/bench_flann_propagate.h"
#include "tests/benchmark_support.h"

using namespace gmg;

namespace {

using bench::median;
using bench::peak_rss_mb;
using bench::Timer;
using namespace flann_bench;

std::vector<int> parse_ints(const char* s) {
  std::vector<int> out;
  for (const char* p = s; *p;) {
    out.push_back(std::atoi(p));
    while (*p && *p != ',') ++p;
    if (*p == ',') ++p;
  }
  return out;
}

std::vector<std::string> parse_words(const char* s) {
  std::vector<std::string> out;
  std::string cur;
  for (const char* p = s;; ++p) {
    if (*p == ',' || *p == 0) {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
      if (*p == 0) break;
    } else {
      cur += *p;
    }
  }
  return out;
}

bool has(const std::vector<std::string>& v, const std::string& w) {
  return std::find(v.begin(), v.end(), w) != v.end();
}

struct Options {
  std::vector<double> hours{1, 2, 4};
  int queries = 20480, block = 128, repeat = 3, brute = 32;
  std::vector<int> ours_checks{2000, 1000, 500};  // besides 0 (the exact reference)
  std::vector<int> kprime{192, 256};
  std::vector<int> checks{256, 512, 1024, 2048, 4096};
  std::vector<std::string> spaces{"full", "proj"};
  std::vector<std::string> indexes{"kd4", "kd8", "kmeans", "hier"};
  double cluster_hours = 1;   // k-means and hierarchical indexes up to this length only
  double autotune_hours = 0;  // FLANN's autotuned index up to this length (0: never)
  // hnswlib (when built with it): graphs as M x ef_construction, searched with each ef >= k'
  // until the recall reaches 0.95; none by default.
  std::vector<std::string> hnsw_spaces;
  std::vector<std::pair<int, int>> hnsw_graphs{{16, 100}};
  std::vector<int> ef{256, 384, 512, 768, 1024};
  // After each budgeted row of ours, the same lists passed on between consecutive frames (see
  // propagate) with these widths; none by default.
  std::vector<int> propagate;
};

void print_header() {
  std::printf("%-6s %9s  %-7s %-58s %8s %9s %9s %8s %7s\n", "length", "frames", "method", "parameters", "build s",
              "query CPU", "query wall", "refine", "recall");
  std::fflush(stdout);
}

void print_row(double hours, int frames, const Row& r) {
  char refine[32] = "";
  if (r.refine_s >= 0) std::snprintf(refine, sizeof refine, "%.2f", r.refine_s);
  std::printf("%-6s %9d  %-7s %-58s %8.2f %9.2f %9.2f %8s %7.4f\n", (std::to_string(hours).substr(0, 4) + " h").c_str(),
              frames, r.method.c_str(), r.params.c_str(), r.build_s, r.cpu_s, r.wall_s, refine, r.recall);
  std::fflush(stdout);
}

struct FlannSetting {
  std::string space, index;
  flann::IndexParams params;
};

std::string describe(const FlannSetting& f, int kprime, int checks, int cores) {
  return f.space + " " + f.index + ", k' " + std::to_string(kprime) + ", checks " + std::to_string(checks) +
         ", cores " + std::to_string(cores);
}

struct Best {
  bool found = false;
  Row row;
  // how to redo it
  int checks = 0, workers = 1, kprime = 0;
  FlannSetting setting;
};

// A whole build's search time estimated from a row: the index build plus the query CPU scaled
// from the query frames to all frames.
double projected(const Row& r, const Reference& ref) {
  return r.build_s + r.cpu_s * static_cast<double>(ref.features.frame_count()) / static_cast<double>(ref.frames.size());
}

// The reference of `hours` (synthetic, 25 joints, seed 3), its thresholds and the query frames.
Reference make_reference(double hours, const Options& o) {
  Reference ref;
  {
    SynthSpec spec;
    spec.duration_s = hours * 3600.0;
    spec.seed = 3;
    spec.joint_count_hint = 25;
    spec.sample_rate = 8000;  // the motion does not depend on it (its own random stream)
    Timer t;
    SynthClip clip = synth_speaker(spec);
    clip.audio = {};
    const double synth_s = t.wall();
    Timer tf;
    ref.features = clip_features(clip.motion);
    double load[3] = {0, 0, 0};
    getloadavg(load, 3);
    std::printf("\n%.2f h: %d frames, %d joints; synthesis %.1f s, features %.1f s; load average %.2f %.2f %.2f\n",
                hours, clip.motion.frame_count, clip.motion.joint_count(), synth_s, tf.wall(), load[0], load[1],
                load[2]);
  }
  const int n = ref.features.frame_count();
  {
    // Run ends as graph_build marks them: capture jumps and the clip's last frame.
    std::vector<int> breaks = capture_jump_frames(ref.features, ref.params);
    breaks.push_back(n - 1);
    std::vector<int> run_end(static_cast<std::size_t>(n));
    std::size_t b = 0;
    for (int f = 0; f < n; ++f) {
      while (breaks[b] < f) ++b;
      run_end[static_cast<std::size_t>(f)] = breaks[b];
    }
    Timer t;
    ref.theta = continuity_thresholds(ref.features, run_end, ref.params);
    std::printf("  %zu break frames (capture jumps + last); theta in %.1f s; k = %d\n", breaks.size(), t.wall(),
                candidate_limit(ref.params));
  }
  // Query blocks: `queries / block` random slots of `block` frames (seed 1).
  ref.block = o.block;
  const int slots = n / o.block;
  const int want = std::min(slots, std::max(1, o.queries / o.block));
  std::vector<int> slot(static_cast<std::size_t>(slots));
  std::iota(slot.begin(), slot.end(), 0);
  std::mt19937_64 rng(1);
  std::shuffle(slot.begin(), slot.end(), rng);
  slot.resize(static_cast<std::size_t>(want));
  std::sort(slot.begin(), slot.end());
  for (const int s : slot) {
    ref.block_starts.push_back(s * o.block);
    for (int f = s * o.block; f < std::min(n, (s + 1) * o.block); ++f) ref.frames.push_back(f);
  }
  std::printf("  query frames: %zu (%d blocks of %d at random places), the same for every method\n", ref.frames.size(),
              want, o.block);
  return ref;
}

// The fastest of each at recall >= 0.95 again, `repeat` more runs each, 1 and 2 workers / cores.
void repeat_fastest(const Options& o, const Reference& ref, const Lists& exact, const Best& ours_best,
                    const Best& flann_best, const neighbours::PoseSpace& space, double space_s) {
  const int n = ref.features.frame_count();
  if (o.repeat > 0)
    std::printf(
        "  fastest with recall >= 0.95 (by build + query CPU scaled to all frames), %d more runs each, "
        "median [min, max]:\n",
        o.repeat);
  auto summary = [&](const char* what, const std::vector<Row>& rows) {
    std::vector<double> b, c, w, p, pw;
    const double scale = static_cast<double>(n) / static_cast<double>(ref.frames.size());
    for (const Row& r : rows) {
      b.push_back(r.build_s), c.push_back(r.cpu_s), w.push_back(r.wall_s);
      p.push_back(r.build_s + r.cpu_s * scale), pw.push_back(r.build_s + r.wall_s * scale);
    }
    auto lo = [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); };
    auto hi = [](const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); };
    std::printf(
        "  %s: recall %.4f\n    build %.2f s [%.2f, %.2f], query CPU %.2f s [%.2f, %.2f], wall %.2f s "
        "[%.2f, %.2f];\n    all %d frames projected: build + CPU %.1f s [%.1f, %.1f], build + wall %.1f s "
        "[%.1f, %.1f]\n",
        what, rows.front().recall, median(b), lo(b), hi(b), median(c), lo(c), hi(c), median(w), lo(w), hi(w), n,
        median(p), lo(p), hi(p), median(pw), lo(pw), hi(pw));
    std::fflush(stdout);
  };
  if (o.repeat == 0) {
    // (no repeats asked for)
  } else if (ours_best.found) {
    for (const int workers : {1, 2}) {
      std::vector<Row> rows;
      for (int i = 0; i < o.repeat; ++i) {
        Row r;
        const Lists found = run_ours(ref, ours_best.checks, workers, r);
        r.recall = candidate_recall(found, exact);
        rows.push_back(r);
      }
      summary(("ours " + rows.front().params).c_str(), rows);
    }
  } else {
    std::printf("  ours: no setting reached recall 0.95\n");
  }
  if (o.repeat == 0) {
    // (no repeats asked for)
  } else if (flann_best.found) {
    const Space s = flann_best.setting.space == "full" ? full_space(ref) : proj_space(ref);
    const flann::Matrix<float> data(const_cast<float*>(s.data.data()), static_cast<std::size_t>(n),
                                    static_cast<std::size_t>(s.dims));
    for (const int cores : {1, 2}) {
      std::vector<Row> rows;
      for (int i = 0; i < o.repeat; ++i) {
        flann::seed_random(1);
        Timer tb;
        FlannIndex index(data, flann_best.setting.params);
        index.buildIndex();
        Row r;
        r.build_s = space_s + s.build_s + tb.wall();
        const Lists found = run_flann(ref, space, s, index, flann_best.kprime, flann_best.checks, cores, r);
        r.recall = candidate_recall(found, exact);
        rows.push_back(r);
      }
      summary(("flann " + describe(flann_best.setting, flann_best.kprime, flann_best.checks, cores)).c_str(), rows);
    }
  } else {
    std::printf("  flann: no setting reached recall 0.95\n");
  }
}

// Checks `count` of the exact search's lists, spread over the query frames, against brute force.
void check_against_brute_force(const Reference& ref, const Lists& exact, int count) {
  std::vector<int> pick;
  std::vector<std::size_t> at;
  for (int i = 0; i < count; ++i) {
    const std::size_t j = static_cast<std::size_t>(i) * ref.frames.size() / static_cast<std::size_t>(count);
    pick.push_back(ref.frames[j]);
    at.push_back(j);
  }
  Timer t;
  const Lists bf = brute_force(ref, pick);
  int same = 0;
  for (std::size_t i = 0; i < pick.size(); ++i) same += bf[i] == exact[at[i]] ? 1 : 0;
  std::printf("  brute-force check of the exact reference: %d of %zu frames identical (%.1f s)\n", same, pick.size(),
              t.wall());
}

#ifdef GMG_HAVE_HNSWLIB
// One hnswlib graph searched for each k' with ascending ef until the recall reaches 0.95; rows printed.
void search_hnsw(double hours, const Options& o, const Reference& ref, const Lists& exact,
                 const neighbours::PoseSpace& space, const Space& s, HnswIndex& index, double build_s) {
  const int n = ref.features.frame_count();
  for (const int kprime : o.kprime) {
    for (const int ef : o.ef) {
      if (ef < kprime) continue;
      Row r;
      const Lists found = run_hnsw(ref, space, s, index, kprime, ef, 1, r);
      r.build_s = build_s;
      r.recall = candidate_recall(found, exact);
      print_row(hours, n, r);
      if (r.recall < 0.95) continue;
      std::printf("    projected to all %d frames: build + query CPU %.1f s\n", n, projected(r, ref));
      break;
    }
  }
}

// hnswlib's graphs (o.hnsw_spaces x o.hnsw_graphs): each a graph over all frames (its build CPU, on
// 2 threads, in the build column, with the space and the refinement's pose space), searched on 1 core.
void compare_hnsw(double hours, const Options& o, const Reference& ref, const Lists& exact,
                  const neighbours::PoseSpace& space, double space_s) {
  for (const std::string& space_name : o.hnsw_spaces) {
    const Space s = space_name == "full" ? full_space(ref) : proj_space(ref);
    hnswlib::L2Space l2(static_cast<std::size_t>(s.dims));
    for (const auto& [m, ef_construction] : o.hnsw_graphs) {
      double build_cpu = 0;
      const std::unique_ptr<HnswIndex> index = build_hnsw(l2, s, m, ef_construction, 2, build_cpu);
      search_hnsw(hours, o, ref, exact, space, s, *index, space_s + s.build_s + build_cpu);
    }
  }
}
#endif

// How much of the next frame's exact K_l the frame's own gives, shifted a frame on (r + 1), and
// within `near` frames of a shifted one: how good a seed a frame's candidates are for the next
// frame's search. Over the consecutive query frames (the blocks), pooled.
void print_temporal_coherence(const Reference& ref, const Lists& exact) {
  constexpr int kNear = 2;
  std::size_t total = 0, shifted = 0, near = 0;
  for (std::size_t i = 0; i + 1 < ref.frames.size(); ++i) {
    if (ref.frames[i + 1] != ref.frames[i] + 1) continue;
    const std::vector<int>& now = exact[i];  // ascending
    for (const int r : exact[i + 1]) {
      ++total;
      const auto at = std::lower_bound(now.begin(), now.end(), r - 1 - kNear);
      if (at == now.end() || *at > r - 1 + kNear) continue;
      ++near;
      shifted += std::binary_search(now.begin(), now.end(), r - 1) ? 1 : 0;
    }
  }
  if (total == 0) return;
  std::printf(
      "  next frame's exact K_l found in this frame's shifted a frame on: %.1f%%, within %d frames of one: %.1f%%\n",
      100.0 * static_cast<double>(shifted) / static_cast<double>(total), kNear,
      100.0 * static_cast<double>(near) / static_cast<double>(total));
}

// The rows of a budgeted search's lists handed on (propagate), for each width, both ways.
void print_propagated(double hours, const Options& o, const Reference& ref, const Lists& exact, const Lists& found,
                      const Row& walk) {
  if (o.propagate.empty()) return;
  neighbours::PoseSpace space(ref.features, ref.params);
  space.set_order({});
  for (const int width : o.propagate)
    for (const bool chained : {true, false}) {
      Row p = walk;
      double fresh = 0;
      const Lists passed = propagate(ref, space, found, width, chained, p, fresh);
      p.recall = candidate_recall(passed, exact);
      char note[80];
      std::snprintf(note, sizeof note, ", %s +-%d (%.0f new)", chained ? "passed on" : "neighbours'", width, fresh);
      p.params += note;
      print_row(hours, ref.features.frame_count(), p);
    }
  Row lean = walk;
  const Lists passed = propagate_lean(ref, space, found, lean);
  lean.recall = candidate_recall(passed, exact);
  lean.params += ", neighbours' +-0, lean";
  print_row(hours, ref.features.frame_count(), lean);
}

void run_length(double hours, const Options& o) {
  Timer total;
  const Reference ref = make_reference(hours, o);
  const int n = ref.features.frame_count();
  print_header();

  // 1. Ours.
  Row exact_row;
  const Lists exact = run_ours(ref, 0, 1, exact_row);
  exact_row.recall = 1.0;
  print_row(hours, n, exact_row);
  const std::size_t bound = static_cast<std::size_t>(candidate_limit(ref.params));
  std::size_t members = 0, full = 0;
  for (const auto& k : exact) members += k.size(), full += k.size() == bound ? 1 : 0;
  std::printf("  exact K_l: %.1f members per query frame on average, %.1f%% of frames have the full %zu\n",
              static_cast<double>(members) / static_cast<double>(exact.size()),
              100.0 * static_cast<double>(full) / static_cast<double>(exact.size()), bound);
  print_temporal_coherence(ref, exact);
  if (o.brute > 0) check_against_brute_force(ref, exact, o.brute);
  std::fflush(stdout);

  Best ours_best;
  for (const int checks : o.ours_checks) {
    Row r;
    const Lists found = run_ours(ref, checks, 1, r);
    r.recall = candidate_recall(found, exact);
    print_row(hours, n, r);
    if (r.recall >= 0.95 && (!ours_best.found || projected(r, ref) < projected(ours_best.row, ref)))
      ours_best = {true, r, checks, 1, 0, {}};
    if (checks > 0) print_propagated(hours, o, ref, exact, found, r);
  }

  // 2. FLANN. The refinement's pose space (float features, as our finder makes it) is made once;
  // its time is added to every FLANN build.
  Timer tps;
  neighbours::PoseSpace space(ref.features, ref.params);
  space.set_order({});
  const double space_s = tps.wall();
  std::printf("  refinement pose space made in %.2f s (included in FLANN's build column)\n", space_s);
  Best flann_best;
  for (const std::string& space_name : o.spaces) {
    const Space s = space_name == "full" ? full_space(ref) : proj_space(ref);
    std::printf("  space %s: %d dims, made in %.2f s (included in the build column)\n", s.name.c_str(), s.dims,
                s.build_s);
    const flann::Matrix<float> data(const_cast<float*>(s.data.data()), static_cast<std::size_t>(n),
                                    static_cast<std::size_t>(s.dims));
    std::vector<FlannSetting> settings;
    // An index name alone is tried in every space; "space:index" in that space only.
    auto wanted = [&](const char* index) { return has(o.indexes, index) || has(o.indexes, s.name + ":" + index); };
    if (wanted("kd4")) settings.push_back({s.name, "kdtree 4", flann::KDTreeIndexParams(4)});
    if (wanted("kd8")) settings.push_back({s.name, "kdtree 8", flann::KDTreeIndexParams(8)});
    if (hours <= o.cluster_hours && wanted("kmeans"))
      settings.push_back({s.name, "kmeans 32", flann::KMeansIndexParams(32, 5)});
    if (hours <= o.cluster_hours && wanted("hier"))
      settings.push_back({s.name, "hier 32x4", flann::HierarchicalClusteringIndexParams(32)});
    if (hours <= o.autotune_hours)
      settings.push_back({s.name, "autotuned", flann::AutotunedIndexParams(0.95f, 0.01f, 0.0f, 0.05f)});
    for (const FlannSetting& setting : settings) {
      flann::seed_random(1);
      Timer tb;
      FlannIndex index(data, setting.params);
      index.buildIndex();
      const double build_s = space_s + s.build_s + tb.wall();
      if (setting.index == "autotuned") {
        std::printf("  autotuned chose (built in %.1f s):\n", build_s);
        std::fflush(stdout);
        flann::print_params(index.getParameters());
        std::fflush(stdout);
      }
      for (const int kprime : o.kprime) {
        for (const int checks : o.checks) {
          Row r;
          const Lists found = run_flann(ref, space, s, index, kprime, checks, 1, r);
          r.build_s = build_s;
          r.recall = candidate_recall(found, exact);
          r.params = describe(setting, kprime, checks, 1);
          print_row(hours, n, r);
          if (r.recall >= 0.95 && (!flann_best.found || projected(r, ref) < projected(flann_best.row, ref)))
            flann_best = {true, r, checks, 1, kprime, setting};
          if (r.recall >= 0.95) break;  // more checks only cost more
        }
      }
    }
  }

#ifdef GMG_HAVE_HNSWLIB
  // 3. hnswlib.
  compare_hnsw(hours, o, ref, exact, space, space_s);
#endif

  // 4. The fastest of each at recall >= 0.95, again.
  if (o.repeat > 0) repeat_fastest(o, ref, exact, ours_best, flann_best, space, space_s);
  double load[3] = {0, 0, 0};
  getloadavg(load, 3);
  std::printf("  %.2f h done in %.0f s of wall; peak RSS so far %.0f MiB; load average %.2f %.2f %.2f\n", hours,
              total.wall(), peak_rss_mb(), load[0], load[1], load[2]);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const char* key = argv[i];
    const char* value = argv[i + 1];
    if (std::strcmp(key, "--hours") == 0) {
      o.hours.clear();
      for (const std::string& w : parse_words(value)) o.hours.push_back(std::atof(w.c_str()));
    } else if (std::strcmp(key, "--queries") == 0) {
      o.queries = std::max(1, std::atoi(value));
    } else if (std::strcmp(key, "--block") == 0) {
      o.block = std::max(1, std::atoi(value));
    } else if (std::strcmp(key, "--repeat") == 0) {
      o.repeat = std::max(0, std::atoi(value));
    } else if (std::strcmp(key, "--brute") == 0) {
      o.brute = std::max(0, std::atoi(value));
    } else if (std::strcmp(key, "--ours-checks") == 0) {
      o.ours_checks = parse_ints(value);
    } else if (std::strcmp(key, "--kprime") == 0) {
      o.kprime = parse_ints(value);
    } else if (std::strcmp(key, "--checks") == 0) {
      o.checks = parse_ints(value);
    } else if (std::strcmp(key, "--spaces") == 0) {
      o.spaces = parse_words(value);
    } else if (std::strcmp(key, "--indexes") == 0) {
      o.indexes = parse_words(value);
    } else if (std::strcmp(key, "--cluster-hours") == 0) {
      o.cluster_hours = std::atof(value);
    } else if (std::strcmp(key, "--autotune-hours") == 0) {
      o.autotune_hours = std::atof(value);
    } else if (std::strcmp(key, "--hnsw") == 0) {
      o.hnsw_spaces = parse_words(value);
    } else if (std::strcmp(key, "--hnsw-graphs") == 0) {
      o.hnsw_graphs.clear();
      for (const std::string& w : parse_words(value)) {
        const std::size_t x = w.find('x');
        if (x == std::string::npos) {
          std::fprintf(stderr, "bench_flann: --hnsw-graphs wants MxEFC, e.g. 16x100, not %s\n", w.c_str());
          return 2;
        }
        o.hnsw_graphs.emplace_back(std::atoi(w.substr(0, x).c_str()), std::atoi(w.substr(x + 1).c_str()));
      }
    } else if (std::strcmp(key, "--propagate") == 0) {
      o.propagate = parse_ints(value);
    } else if (std::strcmp(key, "--ef") == 0) {
      o.ef = parse_ints(value);
    } else {
      std::fprintf(stderr, "bench_flann: unknown option %s\n", key);
      return 2;
    }
  }
  std::printf("bench_flann: candidate search, ours (k-d tree over projections) vs FLANN %s\n", FLANN_VERSION_);
  for (const double h : o.hours) run_length(h, o);
  return 0;
}
