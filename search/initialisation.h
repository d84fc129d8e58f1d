// Feature-based initialisation of the beam search (paper 4.2.3, A.1.3; SPEC "Feature-based
// initialisation"): which start nodes each search gets.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "graph/motion_graph.h"
#include "search/params.h"
#include "search/segmentation.h"

namespace gmg {

// Key-node feature: lengths of the l_feat subsequences that follow key frame index i in `keys`
// (ascending), with keys past the end taken as keys.back(), so trailing entries are 0.
std::vector<double> key_feature(const std::vector<int>& keys, std::size_t i, int l_feat);

// Deterministic integer in [0, n) from the engine's generator (std distributions are
// implementation-defined; this keeps output byte-identical across standard libraries).
inline std::uint64_t random_below(std::mt19937_64& rng, std::uint64_t n) { return n == 0 ? 0 : rng() % n; }

// What the ranking needs, computed once per job.
struct StartNodeIndex {
  std::vector<int> keys;                      // the graph's key frames, ascending
  std::vector<std::vector<double>> features;  // key_feature of each graph key
  std::vector<int> occurrences;               // o_m: accepted paths that started at key m
  std::vector<int> test_keys;                 // subsequence starts and the end frame, ascending
};

StartNodeIndex initialisation_prepare(const MotionGraph& g, const std::vector<Subsequence>& subs,
                                      const SearchParams& params);

// d_feat between test key k and graph key m: lambda_full * ||w_full (f_t - f_m)|| +
// lambda_first * |1 - f_m1 / f_t1| + lambda_occ * o_m.
double feature_distance(const StartNodeIndex& index, std::size_t k, std::size_t m, const SearchParams& params);

// Start nodes of attempt `round` for subsequence k: the key nodes of ranks
// [round * l_npaths, (round + 1) * l_npaths) by d_feat (ties in frame order) with init=feature,
// then random frames (from rng) once key nodes run out, or all random with init=random.
// Exactly l_npaths nodes. With `start_cost` (the natural planner: per key node, what starting
// there is estimated to cost: its junction cost, and the speech and reuse costs of what follows
// it, already weighted), the ranking is by d_feat + junction_rank * start_cost.
std::vector<int> initialisation_start_nodes(const MotionGraph& g, const StartNodeIndex& index, std::size_t k, int round,
                                            const SearchParams& params, std::mt19937_64& rng,
                                            const std::vector<double>* start_cost = nullptr);

// Counts an accepted path that started at `frame` (when it is a key node) for o_m.
void initialisation_count_use(StartNodeIndex& index, int frame);

}  // namespace gmg
