// The candidate searches bench_flann compares (tests/bench_flann.cpp): the reference it asks them
// for, our finder, FLANN's and hnswlib's indexes over two Euclidean spaces that bound the pose
// distance from below, and the refinement of their results to K_l as the build defines it.
#pragma once

#include <algorithm>
#include <memory>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <flann/flann.hpp>
#ifdef GMG_HAVE_HNSWLIB
#include <hnswlib/hnswlib.h>
#endif

#include "engine/core/parallel.h"
#include "graph/candidate_gathering.h"
#include "graph/continuity.h"
#include "graph/features.h"
#include "graph/neighbours.h"
#include "graph/params.h"
#include "graph/pose_space.h"
#include "tests/benchmark_support.h"

namespace gmg::flann_bench {

using bench::Timer;

using Lists = std::vector<std::vector<int>>;

// One row of the table.
struct Row {
  std::string method, params;
  double build_s = 0, cpu_s = 0, wall_s = 0, refine_s = -1, recall = 0;
};

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
inline Lists run_ours(const Reference& ref, int checks, int workers, Row& row) {
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
inline Lists brute_force(const Reference& ref, const std::vector<int>& frames) {
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

inline Space full_space(const Reference& ref) {
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

inline Space proj_space(const Reference& ref) {
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
inline Lists run_flann(const Reference& ref, const neighbours::PoseSpace& space, const Space& s,
                       const FlannIndex& index, int kprime, int checks, int cores, Row& row) {
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
inline std::unique_ptr<HnswIndex> build_hnsw(hnswlib::L2Space& l2, const Space& s, int m, int ef_construction,
                                             int cores, double& cpu_s) {
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
inline Lists run_hnsw(const Reference& ref, const neighbours::PoseSpace& space, const Space& s, HnswIndex& index,
                      int kprime, int ef, int cores, Row& row) {
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

}  // namespace gmg::flann_bench
