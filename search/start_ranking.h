// Ranking the start nodes of each subsequence's beam searches (paper 4.2.3, A.1.3; SPEC
// "Feature-based initialisation", "Junction-aware search"). The paper ranks a subsequence's key
// nodes by d_feat (search/initialisation.h); the natural planner adds what starting at each is
// estimated to cost: its junction from where the output is, the speech and reuse of what follows
// it, and the seed's preference. Those costs are the dear part of planning, so they are computed
// only for the candidates that can rank among the first ranks a subsequence's attempts reach.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "graph/motion_graph.h"
#include "search/initialisation.h"
#include "search/junction.h"
#include "search/params.h"
#include "search/reuse.h"
#include "search/segmentation.h"
#include "search/speech_match.h"

namespace gmg {

// Seeded variety: each seed withholds a random share `variety` (at most 0.9) of the reference's
// seconds as places to jump to (continuing through them stays free). Different seeds then build
// from different stretches where several suit the speech, as a user expects of a seed, while each
// output is still chosen by the same costs from most of the reference. Why not a gentler draw,
// and why this share: the `variety` row of docs/decisions.md.
class SeedPreference {
 public:
  SeedPreference() = default;  // no preference: every frame 0
  // Draws one share per second of g's motion from rng.
  SeedPreference(const MotionGraph& g, double variety, std::mt19937_64& rng);

  // The cost of jumping to `frame`: kWithheld in a withheld second, else 0.
  double of(int frame) const {
    return preference_.empty() ? 0.0 : preference_[static_cast<std::size_t>(frame / block_)];
  }
  static constexpr double kWithheld = 1e3;

 private:
  std::vector<double> preference_;  // per block of the reference
  int block_ = 1;                   // frames per block (one second)
};

// The start-node ranking of one planning job: the ranking of the current subsequence's candidates
// (the key nodes it ranks, initialisation.h start_candidate_sample), made once per subsequence
// since nothing it depends on changes before its path is chosen. The costs it reads (junction,
// speech, reuse, preference) belong to the planner and outlive the ranker.
class StartNodeRanker {
 public:
  // `natural`: the natural planner's costs join the ranking; without them it is the paper's
  // d_feat. Above params.start_candidates key nodes, one draw from rng seeds every subsequence's
  // sample; at or below it no draw is made, so a graph with no more key nodes plans exactly as
  // when every key node was ranked.
  StartNodeRanker(const MotionGraph& g, const std::vector<Subsequence>& subs, const SearchParams& params, bool natural,
                  const StartNodeIndex& index, JunctionCost& junction, const SpeechMatch& speech,
                  const ReuseTracker& reuse, const SeedPreference& preference, std::mt19937_64& rng);

  // The start nodes of attempt `round` of subsequence k, whose junction costs are measured from
  // `reference` (-1: none): the candidates of ranks [round * l_npaths, (round + 1) * l_npaths),
  // then random frames from rng once candidates run out. Exactly l_npaths nodes. Ranks beyond
  // those the pruned ranking holds exactly rank every candidate in full.
  std::vector<int> start_nodes(std::size_t k, int reference, int round, std::mt19937_64& rng);

  // The first start node of subsequence k by d_feat alone (what fallback 3 holds when the very
  // first subsequence finds no path).
  int first_by_feature(std::size_t k, std::mt19937_64& rng) const;

 private:
  void rank(std::size_t k, bool prune);
  void rank_pruned(const std::vector<std::size_t>& candidates, std::vector<double>& distance);
  double start_cost(std::size_t m, const std::vector<double>* j, std::size_t at, bool speech) const;
  bool junction() const { return reference_ >= 0 && params_.junction_beam > 0.0; }
  bool speeching() const { return speech_.active() && params_.speech_weight > 0.0; }

  const MotionGraph& g_;
  const std::vector<Subsequence>& subs_;
  const SearchParams& params_;
  const bool natural_;
  const StartNodeIndex& index_;
  JunctionCost& junction_;
  const SpeechMatch& speech_;
  const ReuseTracker& reuse_;
  const SeedPreference& preference_;
  std::uint64_t sample_seed_ = 0;
  int reference_ = -1;  // the junction reference frame of the subsequence ranked
  // The ranking of subsequence ranking_for_'s candidates, and its estimates.
  std::size_t ranking_for_ = static_cast<std::size_t>(-1);
  StartRanking ranking_;
  std::vector<int> candidate_frames_;
  std::size_t exact_ranks_ = 0;                   // ranks of ranking_ that are exact (all of them unless pruned)
  std::vector<double> speech_part_, reuse_part_;  // per candidate: its speech and reuse windows
};

}  // namespace gmg
