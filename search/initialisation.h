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

// What the ranking needs, computed once per job. A key's feature is taken from `keys` when it is
// ranked (key_feature), so preparing a job costs no work per key node.
struct StartNodeIndex {
  std::vector<int> keys;         // the graph's key frames, ascending
  std::vector<int> occurrences;  // o_m: accepted paths that started at key m
  std::vector<int> test_keys;    // subsequence starts and the end frame, ascending
};

StartNodeIndex initialisation_prepare(const MotionGraph& g, const std::vector<Subsequence>& subs,
                                      const SearchParams& params);

// d_feat between test key k and graph key m: lambda_full * ||w_full (f_t - f_m)|| +
// lambda_first * |1 - f_m1 / f_t1| + lambda_occ * o_m.
double feature_distance(const StartNodeIndex& index, std::size_t k, std::size_t m, const SearchParams& params);

// The key nodes a subsequence ranks (indices into the graph's key frames, ascending). Ranking every
// key node costs a subsequence time in proportion to the reference; above `cap` of them
// (SearchParams::start_candidates; 0 = no cap) subsequence k ranks a sample of at most cap: the
// key nodes in blocks of kCandidateBlock consecutive ones (fewer when cap is smaller), every
// stride-th block from an offset that `seed` and k decide (SplitMix64 of seed + k), so each
// subsequence weighs a different sample spread evenly over the whole reference, and each block's
// key poses are read as one stretch of memory. At or below the cap: all of them.
constexpr std::size_t kCandidateBlock = 64;
std::vector<std::size_t> start_candidate_sample(std::size_t keys, int cap, std::uint64_t seed, std::size_t k);

// The ranking of some key nodes (`candidates`: indices into index.keys, ascending) as start nodes
// for test key k, by d_feat (plus junction_rank times `start_cost` of each candidate, when given:
// the natural planner's estimate of what starting there costs, already weighted), ties in frame
// order. Built once per subsequence; each attempt takes the next l_npaths ranks, sorting no more
// of the candidates than the attempts reach.
class StartRanking {
 public:
  StartRanking() = default;
  StartRanking(const StartNodeIndex& index, std::size_t k, std::vector<std::size_t> candidates,
               const std::vector<double>* start_cost, const SearchParams& params);
  // From each candidate's ranking distance, already computed (feature_distances plus
  // junction_rank times its start cost); with init=random, no candidates.
  StartRanking(std::vector<std::size_t> candidates, std::vector<double> distance, const SearchParams& params);

  // The start nodes of attempt `round`: the candidates of ranks [round * l_npaths, (round + 1) *
  // l_npaths), then random frames (from rng) once candidates run out. Exactly l_npaths nodes.
  std::vector<int> start_nodes(const MotionGraph& g, const StartNodeIndex& index, int round, const SearchParams& params,
                               std::mt19937_64& rng);

 private:
  std::vector<std::size_t> candidates_;
  std::vector<double> distance_;    // per candidate
  std::vector<std::size_t> order_;  // positions in candidates_; the first sorted_ are in rank order
  std::size_t sorted_ = 0;
};

// d_feat of each candidate (indices into index.keys) against test key k.
std::vector<double> feature_distances(const StartNodeIndex& index, std::size_t k,
                                      const std::vector<std::size_t>& candidates, const SearchParams& params);

// Start nodes of attempt `round` for subsequence k: the key nodes of ranks
// [round * l_npaths, (round + 1) * l_npaths) by d_feat (ties in frame order) with init=feature,
// then random frames (from rng) once key nodes run out, or all random with init=random.
// Exactly l_npaths nodes. With `start_cost` (the natural planner: per key node, what starting
// there is estimated to cost: its junction cost, and the speech and reuse costs of what follows
// it, already weighted), the ranking is by d_feat + junction_rank * start_cost. Every key node is
// ranked (StartRanking over all of them).
std::vector<int> initialisation_start_nodes(const MotionGraph& g, const StartNodeIndex& index, std::size_t k, int round,
                                            const SearchParams& params, std::mt19937_64& rng,
                                            const std::vector<double>* start_cost = nullptr);

// Counts an accepted path that started at `frame` (when it is a key node) for o_m.
void initialisation_count_use(StartNodeIndex& index, int frame);

}  // namespace gmg
