#include "search/start_ranking.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace gmg {

SeedPreference::SeedPreference(const MotionGraph& g, double variety, std::mt19937_64& rng) {
  block_ = std::max(1, static_cast<int>(std::lround(g.motion.fps)));
  preference_.resize(static_cast<std::size_t>(g.frame_count() / block_ + 1));
  const std::uint64_t scale = 1u << 20;
  const double share = std::min(variety, 0.9);
  for (double& p : preference_)
    p = static_cast<double>(random_below(rng, scale)) < share * static_cast<double>(scale) ? kWithheld : 0.0;
}

namespace {

// The window over which a start node's speech and reuse are estimated: the subsequence, within
// [10, 60] frames (shorter says little, longer is beyond what the path will play).
int window_of(const Subsequence& sub) { return std::clamp(sub.length, 10, 60); }

}  // namespace

StartNodeRanker::StartNodeRanker(const MotionGraph& g, const std::vector<Subsequence>& subs, const SearchParams& params,
                                 bool natural, const StartNodeIndex& index, JunctionCost& junction,
                                 const SpeechMatch& speech, const ReuseTracker& reuse, const SeedPreference& preference,
                                 std::mt19937_64& rng)
    : g_(g),
      subs_(subs),
      params_(params),
      natural_(natural),
      index_(index),
      junction_(junction),
      speech_(speech),
      reuse_(reuse),
      preference_(preference) {
  const std::size_t cap = static_cast<std::size_t>(params.start_candidates);
  if (cap > 0 && index_.keys.size() > cap) sample_seed_ = rng();
}

std::vector<int> StartNodeRanker::start_nodes(std::size_t k, int reference, int round, std::mt19937_64& rng) {
  reference_ = reference;
  const std::size_t needed = static_cast<std::size_t>(round + 1) * static_cast<std::size_t>(params_.l_npaths);
  if (ranking_for_ != k) rank(k, true);
  if (needed > exact_ranks_ && exact_ranks_ < candidate_frames_.size()) rank(k, false);
  return ranking_.start_nodes(g_, index_, round, params_, rng);
}

int StartNodeRanker::first_by_feature(std::size_t k, std::mt19937_64& rng) const {
  return StartRanking(index_, k, start_candidate_sample(index_.keys.size(), params_.start_candidates, sample_seed_, k),
                      nullptr, params_)
      .start_nodes(g_, index_, 0, params_, rng)
      .front();
}

// The key nodes subsequence k ranks, their estimated costs and their ranking. `prune`: the
// junction and speech costs, the dearest parts, are computed only for the candidates that can rank
// among the first exact_ranks_ (rank_pruned).
void StartNodeRanker::rank(std::size_t k, bool prune) {
  std::vector<std::size_t> candidates =
      start_candidate_sample(index_.keys.size(), params_.start_candidates, sample_seed_, k);
  const std::size_t n = candidates.size();
  candidate_frames_.resize(n);
  for (std::size_t m = 0; m < n; ++m) candidate_frames_[m] = index_.keys[candidates[m]];
  ranking_for_ = k;
  exact_ranks_ = n;
  if (!natural_) {
    ranking_ = StartRanking(index_, k, std::move(candidates), nullptr, params_);
    return;
  }
  const Subsequence& sub = subs_[k];
  speech_part_.assign(n, 0.0);
  reuse_part_.assign(n, 0.0);
  if (params_.reuse_weight > 0.0) reuse_.window_costs(window_of(sub), sub.start, candidate_frames_, reuse_part_);
  std::vector<double> distance = feature_distances(index_, k, candidates, params_);
  if (prune && n > 0) {
    rank_pruned(candidates, distance);
  } else {
    if (speeching()) speech_.window_costs(sub.start, window_of(sub), candidate_frames_, speech_part_);
    std::vector<double> j;
    if (junction() && junction_.has_key_poses())
      junction_.key_costs(reference_, candidates, j);
    else if (junction())
      junction_.costs(reference_, candidate_frames_, j);
    for (std::size_t m = 0; m < n; ++m) distance[m] += params_.junction_rank * start_cost(m, &j, m, true);
  }
  ranking_ = StartRanking(std::move(candidates), std::move(distance), params_);
}

// A candidate's estimated start cost: junction_beam * J ((*j)[at]; none when j is null) +
// speech_weight * speech window (when `speech`; speech_part_) + reuse_weight * reuse window
// (reuse_part_) + its preference, summed in that order. Costs are not negative and rounding keeps a
// sum at least any of its partial sums, so the cost without J, or without J and speech, is never
// above the whole.
double StartNodeRanker::start_cost(std::size_t m, const std::vector<double>* j, std::size_t at, bool speech) const {
  double cost = 0.0;
  if (j && !j->empty()) cost += params_.junction_beam * (*j)[at];
  if (speech && speeching()) cost += params_.speech_weight * speech_part_[m];
  if (params_.reuse_weight > 0.0) cost += params_.reuse_weight * reuse_part_[m];
  if (candidate_frames_[m] != reference_) cost += preference_.of(candidate_frames_[m]);
  return cost;
}

// Ranking distances (d_feat in `distance` on entry) exact for the first exact_ranks_ ranks: a
// subsequence's attempts are at most retries + 1 (fallbacks start again from the first rank).
// A candidate's distance without its junction cost, or without its junction and speech costs,
// bounds it from below, so one whose bound exceeds the exact_ranks_-th lowest distance found so
// far cannot rank among the first exact_ranks_: its costs are not computed and its distance is
// left infinite. The candidates of lowest bound come first (so the bar is low early), then the
// others in blocks of consecutive key nodes, whose poses are read as one stretch.
void StartNodeRanker::rank_pruned(const std::vector<std::size_t>& candidates, std::vector<double>& distance) {
  const std::size_t n = candidates.size();
  const Subsequence& sub = subs_[ranking_for_];
  exact_ranks_ =
      std::min(n, static_cast<std::size_t>(params_.retries + 1) * static_cast<std::size_t>(params_.l_npaths));
  std::vector<double> cheap(n);  // the bound without junction and speech
  for (std::size_t m = 0; m < n; ++m) cheap[m] = distance[m] + params_.junction_rank * start_cost(m, nullptr, m, false);
  std::vector<std::pair<double, std::size_t>> best;  // max-heap: the exact_ranks_ lowest so far
  std::vector<char> done(n, 0);
  std::vector<std::size_t> some, kept, keys, at;
  std::vector<int> frames;
  std::vector<double> part, j, bound;
  // The full distances of `some` (ascending), pruned again by the bound with the junction cost's
  // lower bound (JunctionCost::key_lower_bounds), then by the bound with speech and that.
  auto complete = [&](const std::vector<std::size_t>& group) {
    const double bar = best.size() < exact_ranks_ ? std::numeric_limits<double>::infinity() : best.front().first;
    const std::vector<std::size_t>* survivors = &group;
    bound.clear();
    // While the bar is still infinite (the first group) no bound can prune: none is computed.
    if (junction() && junction_.has_key_poses() && bar < std::numeric_limits<double>::infinity()) {
      keys.clear();
      for (std::size_t m : group) keys.push_back(candidates[m]);
      junction_.key_lower_bounds(reference_, keys, part);
      kept.clear();
      for (std::size_t i = 0; i < group.size(); ++i)
        if (distance[group[i]] + params_.junction_rank * start_cost(group[i], &part, i, false) <= bar) {
          kept.push_back(group[i]);
          bound.push_back(part[i]);
        }
      survivors = &kept;
    }
    frames.clear();
    for (std::size_t m : *survivors) frames.push_back(candidate_frames_[m]);
    if (speeching()) {
      speech_.window_costs(sub.start, window_of(sub), frames, part);
      for (std::size_t i = 0; i < survivors->size(); ++i) speech_part_[(*survivors)[i]] = part[i];
    }
    keys.clear();
    at.clear();
    for (std::size_t i = 0; i < survivors->size(); ++i) {
      const std::size_t m = (*survivors)[i];
      if (distance[m] + params_.junction_rank * start_cost(m, bound.empty() ? nullptr : &bound, i, true) <= bar) {
        keys.push_back(candidates[m]);
        at.push_back(m);
      }
    }
    j.clear();
    if (junction() && junction_.has_key_poses()) {
      junction_.key_costs(reference_, keys, j);
    } else if (junction()) {  // a graph made without key poses
      frames.clear();
      for (std::size_t m : at) frames.push_back(candidate_frames_[m]);
      junction_.costs(reference_, frames, j);
    }
    std::size_t next = 0;
    for (std::size_t m : group) {
      done[m] = 1;
      if (next < at.size() && at[next] == m) {
        distance[m] += params_.junction_rank * start_cost(m, &j, next++, true);
        best.emplace_back(distance[m], m);
        std::push_heap(best.begin(), best.end());
        if (best.size() > exact_ranks_) {
          std::pop_heap(best.begin(), best.end());
          best.pop_back();
        }
      } else {
        distance[m] = std::numeric_limits<double>::infinity();
      }
    }
  };
  // First the 4 x exact_ranks_ candidates of lowest cheap bound.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  const std::size_t first = std::min(n, 4 * exact_ranks_);
  std::nth_element(
      order.begin(), order.begin() + static_cast<std::ptrdiff_t>(first - 1), order.end(),
      [&](std::size_t a, std::size_t b) { return cheap[a] < cheap[b] || (cheap[a] == cheap[b] && a < b); });
  some.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(first));
  std::sort(some.begin(), some.end());
  complete(some);
  // Then the rest in blocks, each candidate only when its cheap bound does not exceed the bar.
  for (std::size_t from = 0; from < n; from += kCandidateBlock) {
    const double bar = best.size() < exact_ranks_ ? std::numeric_limits<double>::infinity() : best.front().first;
    some.clear();
    for (std::size_t m = from; m < std::min(n, from + kCandidateBlock); ++m) {
      if (done[m]) continue;
      if (cheap[m] <= bar)
        some.push_back(m);
      else
        distance[m] = std::numeric_limits<double>::infinity();
    }
    if (!some.empty()) complete(some);
  }
}

}  // namespace gmg
