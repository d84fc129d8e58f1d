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
#include "tests/benchmark_support.h"

using namespace gmg;

namespace {

using bench::median;
using bench::peak_rss_mb;
using bench::Timer;

using Lists = std::vector<std::vector<int>>;

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

// One row of the table.
struct Row {
  std::string method, params;
  double build_s = 0, cpu_s = 0, wall_s = 0, refine_s = -1, recall = 0;
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

struct Reference {
  PoseFeatures features;
  std::vector<double> theta;
  GraphParams params;
  std::vector<int> block_starts;  // ascending
  std::vector<int> frames;        // the query frames, block by block
  int block = 0;
};

// Ours: the search built, then asked for every query frame (in blocks, as the analysis asks,
// each block on `workers` threads). Returns the lists, fills the row.
Lists run_ours(const Reference& ref, int checks, int workers, Row& row) {
  GraphParams p = ref.params;
  p.ann_checks = checks;
  const int n = ref.features.frame_count();
  Timer build;
  const CandidateSearch search(ref.features, ref.theta, p, NeighbourSearch::Approximate);
  row.build_s = build.wall();
  Lists all(ref.frames.size());
  std::vector<CandidateScratch> scratch(static_cast<std::size_t>(workers));
  std::vector<std::vector<Candidate>> found(static_cast<std::size_t>(workers));
  Timer q;
  std::size_t at = 0;
  for (const int first : ref.block_starts) {
    const int count = std::min(ref.block, n - first);
    parallel_for(static_cast<std::size_t>(count), workers, [&](std::size_t i, int w) {
      std::vector<Candidate>& k = found[static_cast<std::size_t>(w)];
      search.find(first + static_cast<int>(i), scratch[static_cast<std::size_t>(w)], k);
      for (const Candidate& c : k) all[at + i].push_back(c.r);
    });
    at += static_cast<std::size_t>(count);
  }
  row.cpu_s = q.cpu();
  row.wall_s = q.wall();
  row.method = "ours";
  row.params = "ann_checks " + std::to_string(checks) + ", workers " + std::to_string(workers);
  return all;
}

// K_l from candidate frames (any order, duplicates allowed): allowed, d <= theta in double, the
// k nearest by (d, r), ascending by r. `n_sq` (FLANN's squared N <= d^2, or negative) rejects
// early those with N clearly above theta.
struct Refiner {
  const Reference& ref;
  neighbours::Allowed allowed{ref.params.l_pn, ref.params.exclude_near};
  std::size_t k = static_cast<std::size_t>(candidate_limit(ref.params));

  void operator()(int l, const int* cand, const float* n_sq, int count, std::vector<std::pair<double, int>>& scratch,
                  std::vector<int>& out) const {
    out.clear();
    scratch.clear();
    const double theta = ref.theta[static_cast<std::size_t>(l)];
    if (theta <= 0) return;
    const float reject = static_cast<float>(theta * theta) * 1.001f + 1e-12f;
    for (int i = 0; i < count; ++i) {
      const int r = cand[i];
      if (r < 0 || !allowed(l, r) || (n_sq && n_sq[i] > reject)) continue;
      const double d = pose_distance(ref.features, l, r, ref.params);
      if (d <= theta) scratch.emplace_back(d, r);
    }
    std::sort(scratch.begin(), scratch.end());
    scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
    if (k && scratch.size() > k) scratch.resize(k);
    for (const auto& c : scratch) out.push_back(c.second);
    std::sort(out.begin(), out.end());
  }
};

// The same refinement as our finder does it (graph/candidate_gathering.h): d screened in single
// precision on the pose space's padded float features, decided in double only within float error
// of theta or of the k-th distance. Gives the same K_l as Refiner, faster.
struct FastRefiner {
  const Reference& ref;
  const neighbours::PoseSpace& space;
  neighbours::Allowed allowed{ref.params.l_pn, ref.params.exclude_near};
  std::size_t k = static_cast<std::size_t>(candidate_limit(ref.params));

  void operator()(int l, const int* cand, const float* n_sq, int count, std::vector<int>& out) const {
    out.clear();
    const double theta = ref.theta[static_cast<std::size_t>(l)];
    std::vector<Candidate> items, found;
    std::vector<float> kth;
    std::vector<std::pair<double, int>> ties;
    neighbours::Gathered g(space, k, space.radius(theta), items, kth, ties);
    if (g.radius() < 0) return;
    const float reject = g.radius() * g.radius() * 1.001f + 1e-12f;
    for (int i = 0; i < count; ++i) {
      const int r = cand[i];
      if (r < 0 || !allowed(l, r) || (n_sq && n_sq[i] > reject)) continue;
      const float d = space.approx(l, r);
      if (d > g.radius() || !space.within(l, r, d, theta)) continue;
      g.add(d, r);
    }
    g.resolve(l, found);
    for (const Candidate& c : found) out.push_back(c.r);
  }
};

// The brute-force K_l of `frames` (every frame a candidate), to check the exact reference.
Lists brute_force(const Reference& ref, const std::vector<int>& frames) {
  const Refiner refine{ref};
  const int n = ref.features.frame_count();
  std::vector<int> all(static_cast<std::size_t>(n));
  std::iota(all.begin(), all.end(), 0);
  Lists out(frames.size());
  std::vector<std::vector<std::pair<double, int>>> scratch(2);
  parallel_for(frames.size(), 2, [&](std::size_t i, int worker) {
    refine(frames[i], all.data(), nullptr, n, scratch[static_cast<std::size_t>(worker)], out[i]);
  });
  return out;
}

// A FLANN search space: n rows of `dims` floats.
struct Space {
  std::string name;
  int dims = 0;
  std::vector<float> data;
  double build_s = 0;  // seconds to make it
};

Space full_space(const Reference& ref) {
  Timer t;
  const PoseFeatures& f = ref.features;
  const int n = f.frame_count();
  const Eigen::VectorXd mp = f.positions.rowwise().mean(), mv = f.velocities.rowwise().mean();
  std::vector<int> rows_p, rows_v;  // rows that are not 0 in every frame
  for (Eigen::Index d = 0; d < f.positions.rows(); ++d) {
    if (f.positions.row(d).cwiseAbs().maxCoeff() > 0) rows_p.push_back(static_cast<int>(d));
    if (f.velocities.row(d).cwiseAbs().maxCoeff() > 0) rows_v.push_back(static_cast<int>(d));
  }
  Space s;
  s.name = "full";
  s.dims = static_cast<int>(rows_p.size() + rows_v.size());
  s.data.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(s.dims));
  const double lp = ref.params.lambda_pos, lv = ref.params.lambda_vel;
  for (int l = 0; l < n; ++l) {
    float* row = s.data.data() + static_cast<std::size_t>(l) * static_cast<std::size_t>(s.dims);
    for (const int d : rows_p) *row++ = static_cast<float>(lp * (f.positions(d, l) - mp(d)));
    for (const int d : rows_v) *row++ = static_cast<float>(lv * (f.velocities(d, l) - mv(d)));
  }
  s.build_s = t.wall();
  return s;
}

Space proj_space(const Reference& ref) {
  Timer t;
  const neighbours::PoseSpace ps(ref.features, ref.params);
  const Eigen::MatrixXf& proj = ps.projections();  // frame order (no set_order)
  Space s;
  s.name = "proj";
  // The rows in use: the position axes (rows 0 to 7), then the velocity axes (from row 8).
  std::vector<int> rows;
  rows.reserve(static_cast<std::size_t>(ps.position_dims() + ps.velocity_dims()));
  for (int d = 0; d < ps.position_dims(); ++d) rows.push_back(d);
  for (int d = 0; d < ps.velocity_dims(); ++d) rows.push_back(8 + d);
  s.dims = static_cast<int>(rows.size());
  const int n = ps.frames();
  s.data.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(s.dims));
  for (int l = 0; l < n; ++l)
    for (int i = 0; i < s.dims; ++i) {
      const int row = rows[static_cast<std::size_t>(i)];
      s.data[static_cast<std::size_t>(l) * static_cast<std::size_t>(s.dims) + static_cast<std::size_t>(i)] =
          proj(row, l) * (row < 8 ? ps.lambda_pos() : ps.lambda_vel());
    }
  s.build_s = t.wall();
  return s;
}

using FlannIndex = flann::Index<flann::L2<float>>;

// FLANN's knn of every query frame, refined to K_l. Fills the row's query times and refine time.
Lists run_flann(const Reference& ref, const neighbours::PoseSpace& space, const Space& s, const FlannIndex& index,
                int kprime, int checks, int cores, Row& row) {
  const std::size_t q = ref.frames.size(), dims = static_cast<std::size_t>(s.dims);
  std::vector<float> qdata(q * dims);
  for (std::size_t i = 0; i < q; ++i)
    std::copy_n(s.data.data() + static_cast<std::size_t>(ref.frames[i]) * dims, dims, qdata.data() + i * dims);
  const flann::Matrix<float> queries(qdata.data(), q, dims);
  std::vector<int> idx(q * static_cast<std::size_t>(kprime), -1);
  std::vector<float> dist(q * static_cast<std::size_t>(kprime));
  flann::Matrix<int> indices(idx.data(), q, static_cast<std::size_t>(kprime));
  flann::Matrix<float> dists(dist.data(), q, static_cast<std::size_t>(kprime));
  flann::SearchParams sp(checks);
  sp.cores = cores;
  Lists out(q);
  const FastRefiner refine{ref, space};
  Timer t;
  index.knnSearch(queries, indices, dists, static_cast<std::size_t>(kprime), sp);
  Timer tr;
  constexpr std::size_t kChunk = 64;
  parallel_for((q + kChunk - 1) / kChunk, cores, [&](std::size_t chunk, int) {
    for (std::size_t i = chunk * kChunk; i < std::min(q, (chunk + 1) * kChunk); ++i)
      refine(ref.frames[i], idx.data() + i * static_cast<std::size_t>(kprime),
             dist.data() + i * static_cast<std::size_t>(kprime), kprime, out[i]);
  });
  row.refine_s = tr.wall();
  row.cpu_s = t.cpu();
  row.wall_s = t.wall();
  row.method = "flann";
  return out;
}

#ifdef GMG_HAVE_HNSWLIB
using HnswIndex = hnswlib::HierarchicalNSW<float>;

// An HNSW graph over every frame of a space, built on `cores` threads (hnswlib's insertions may
// run in parallel once the first point is in). Returns the build's CPU seconds in `cpu_s`.
std::unique_ptr<HnswIndex> build_hnsw(hnswlib::L2Space& l2, const Space& s, int m, int ef_construction, int cores,
                                      double& cpu_s) {
  const std::size_t n = s.data.size() / static_cast<std::size_t>(s.dims), dims = static_cast<std::size_t>(s.dims);
  Timer t;
  auto index =
      std::make_unique<HnswIndex>(&l2, n, static_cast<std::size_t>(m), static_cast<std::size_t>(ef_construction), 1);
  index->addPoint(s.data.data(), 0);
  parallel_for(n - 1, cores, [&](std::size_t i, int) { index->addPoint(s.data.data() + (i + 1) * dims, i + 1); });
  cpu_s = t.cpu();
  return index;
}

// hnswlib's k' nearest of every query frame (with `ef`), refined to K_l as FLANN's are.
Lists run_hnsw(const Reference& ref, const neighbours::PoseSpace& space, const Space& s, HnswIndex& index, int kprime,
               int ef, int cores, Row& row) {
  const std::size_t q = ref.frames.size(), dims = static_cast<std::size_t>(s.dims);
  index.setEf(static_cast<std::size_t>(ef));
  Lists out(q);
  const FastRefiner refine{ref, space};
  std::vector<std::vector<int>> idx(static_cast<std::size_t>(cores));
  std::vector<std::vector<float>> dist(static_cast<std::size_t>(cores));
  Timer t;
  parallel_for(q, cores, [&](std::size_t i, int w) {
    const int l = ref.frames[i];
    auto found = index.searchKnn(s.data.data() + static_cast<std::size_t>(l) * dims, static_cast<std::size_t>(kprime));
    std::vector<int>& ids = idx[static_cast<std::size_t>(w)];
    std::vector<float>& ds = dist[static_cast<std::size_t>(w)];
    ids.clear(), ds.clear();
    for (; !found.empty(); found.pop()) {
      ds.push_back(found.top().first);
      ids.push_back(static_cast<int>(found.top().second));
    }
    refine(l, ids.data(), ds.data(), static_cast<int>(ids.size()), out[i]);
  });
  row.cpu_s = t.cpu();
  row.wall_s = t.wall();
  row.method = "hnsw";
  row.params = s.name + " M " + std::to_string(index.M_) + ", efC " + std::to_string(index.ef_construction_) + ", k' " +
               std::to_string(kprime) + ", ef " + std::to_string(ef) + ", cores " + std::to_string(cores);
  return out;
}
#endif

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

// A budgeted search's lists handed on between consecutive query frames: a frame's candidates are
// mostly runs of consecutive frames, so a member r of frame l's K_l suggests r + 1 for frame l + 1
// (and r - 1 for l - 1). A forward pass over each block (frame i takes its own list and frame
// i - 1's, each member shifted a frame on and widened by `width` frames either side), then a
// backward one (frame i + 1's, shifted a frame back), each list refined as K_l is defined
// (FastRefiner: exact over the frames offered). The cost is fixed per frame, whatever the length.
// `chained` false: one pass in which each frame takes its two neighbours' own lists (as found, not
// as passed on), so that a frame's result does not depend on the order frames are taken in.
// out_fresh: frames offered beyond the lists they were added to, per query frame (both passes).
Lists propagate(const Reference& ref, const neighbours::PoseSpace& space, const Lists& found, int width, bool chained,
                Row& row, double& out_fresh) {
  const FastRefiner refine{ref, space};
  const int n = ref.features.frame_count();
  Lists out = found;
  std::vector<int> offered;
  auto offer = [&](const std::vector<int>& from, int shift) {
    for (const int r : from)
      for (int d = -width; d <= width; ++d) {
        const int c = r + shift + d;
        if (c >= 0 && c < n) offered.push_back(c);
      }
  };
  // Frames offered beyond a frame's own list: the distances a pass that kept the list's own would
  // have to make.
  std::size_t fresh = 0;
  auto settle = [&](std::size_t i, std::size_t own) {
    std::sort(offered.begin(), offered.end());
    offered.erase(std::unique(offered.begin(), offered.end()), offered.end());
    fresh += offered.size() - own;
    refine(ref.frames[i], offered.data(), nullptr, static_cast<int>(offered.size()), out[i]);
  };
  auto pass = [&](std::size_t i, std::size_t from, int shift) {
    offered = out[i];
    offer(out[from], shift);
    settle(i, out[i].size());
  };
  Timer t;
  if (chained) {
    for (std::size_t i = 1; i < ref.frames.size(); ++i)
      if (ref.frames[i] == ref.frames[i - 1] + 1) pass(i, i - 1, 1);
    for (std::size_t i = ref.frames.size() - 1; i-- > 0;)
      if (ref.frames[i + 1] == ref.frames[i] + 1) pass(i, i + 1, -1);
  } else {
    for (std::size_t i = 0; i < ref.frames.size(); ++i) {
      offered = found[i];
      if (i > 0 && ref.frames[i] == ref.frames[i - 1] + 1) offer(found[i - 1], 1);
      if (i + 1 < ref.frames.size() && ref.frames[i + 1] == ref.frames[i] + 1) offer(found[i + 1], -1);
      settle(i, found[i].size());
    }
  }
  row.refine_s = t.cpu();
  out_fresh = ref.frames.empty() ? 0.0 : static_cast<double>(fresh) / static_cast<double>(ref.frames.size());
  return out;
}

// The neighbours' pass (propagate, not chained, width 0) as a build would make it: each frame's own
// members keep the distances the search gave them (made here before the clock starts), and only the
// frames its neighbours offer beyond them are measured, into one reused gathering. Returns the
// lists; row.refine_s is the pass's CPU.
Lists propagate_lean(const Reference& ref, const neighbours::PoseSpace& space, const Lists& found, Row& row) {
  const neighbours::Allowed allowed{ref.params.l_pn, ref.params.exclude_near};
  const std::size_t k = static_cast<std::size_t>(candidate_limit(ref.params));
  const std::size_t q = ref.frames.size();
  std::vector<std::vector<Candidate>> own(q);
  for (std::size_t i = 0; i < q; ++i)
    for (const int r : found[i]) own[i].push_back({space.approx(ref.frames[i], r), r});
  Lists out(q);
  std::vector<Candidate> items, result;
  std::vector<int> fresh;
  std::vector<float> kth;
  std::vector<std::pair<double, int>> ties;
  Timer t;
  for (std::size_t i = 0; i < q; ++i) {
    const int l = ref.frames[i];
    const double theta = ref.theta[static_cast<std::size_t>(l)];
    neighbours::Gathered g(space, k, space.radius(theta), items, kth, ties);
    if (g.radius() < 0) continue;
    for (const Candidate& c : own[i]) g.add(c.d, c.r);
    const std::vector<int>& mine = found[i];  // ascending
    fresh.clear();
    auto offer = [&](const std::vector<int>& from, int shift) {
      for (const int f : from) {
        const int r = f + shift;
        if (r >= 0 && r < ref.features.frame_count() && allowed(l, r) &&
            !std::binary_search(mine.begin(), mine.end(), r))
          fresh.push_back(r);
      }
    };
    if (i > 0 && ref.frames[i - 1] == l - 1) offer(found[i - 1], 1);
    if (i + 1 < q && ref.frames[i + 1] == l + 1) offer(found[i + 1], -1);
    std::sort(fresh.begin(), fresh.end());
    fresh.erase(std::unique(fresh.begin(), fresh.end()), fresh.end());
    for (const int r : fresh) {
      const float d = space.approx(l, r);
      if (d <= g.radius() && space.within(l, r, d, theta)) g.add(d, r);
    }
    g.resolve(l, result);
    for (const Candidate& c : result) out[i].push_back(c.r);
  }
  row.refine_s = t.cpu();
  return out;
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
