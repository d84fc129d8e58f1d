#include "search/initialisation.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "graph/reference_facts.h"

namespace gmg {

std::vector<double> key_feature(const std::vector<int>& keys, std::size_t i, int l_feat) {
  std::vector<double> f(static_cast<std::size_t>(l_feat), 0.0);
  auto key = [&](std::size_t j) { return j < keys.size() ? keys[j] : keys.back(); };
  for (int e = 0; e < l_feat; ++e) f[static_cast<std::size_t>(e)] = key(i + e + 1) - key(i + e);
  return f;
}

StartNodeIndex initialisation_prepare(const MotionGraph& g, const std::vector<Subsequence>& subs, const SearchParams&) {
  StartNodeIndex index;
  index.keys = graph_keys(g);
  index.occurrences.assign(index.keys.size(), 0);
  index.test_keys.reserve(subs.size() + 1);
  for (const Subsequence& s : subs) index.test_keys.push_back(s.start);
  if (!subs.empty()) index.test_keys.push_back(subs.back().start + subs.back().length);
  return index;
}

namespace {

// d_feat of graph key m against the test feature ft: key_feature(index.keys, m) computed in place.
double feature_distance_to(const StartNodeIndex& index, const std::vector<double>& ft, std::size_t m,
                           const SearchParams& params) {
  const std::vector<int>& keys = index.keys;
  auto key = [&](std::size_t j) { return j < keys.size() ? keys[j] : keys.back(); };
  double full = 0.0;
  for (std::size_t e = 0; e < ft.size(); ++e) {
    const double fm = key(m + e + 1) - key(m + e);
    const double d = params.w_full[e] * (ft[e] - fm);
    full += d * d;
  }
  const double fm0 = key(m + 1) - key(m);
  const double first = ft[0] > 0 ? std::abs(1.0 - fm0 / ft[0]) : 0.0;
  return params.lambda_full * std::sqrt(full) + params.lambda_first * first + params.lambda_occ * index.occurrences[m];
}

}  // namespace

double feature_distance(const StartNodeIndex& index, std::size_t k, std::size_t m, const SearchParams& params) {
  return feature_distance_to(index, key_feature(index.test_keys, k, params.l_feat), m, params);
}

std::vector<std::size_t> start_candidate_sample(std::size_t keys, int cap, std::uint64_t seed, std::size_t k) {
  std::vector<std::size_t> out;
  const std::size_t limit = static_cast<std::size_t>(std::max(0, cap));
  if (limit == 0 || keys <= limit) {
    out.resize(keys);
    std::iota(out.begin(), out.end(), 0);
    return out;
  }
  const std::size_t block = std::min(kCandidateBlock, limit);
  const std::size_t blocks = (keys + block - 1) / block;
  const std::size_t wanted = limit / block;
  const std::size_t stride = (blocks + wanted - 1) / wanted;
  std::uint64_t x = seed + k + 0x9e3779b97f4a7c15ULL;  // SplitMix64
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  x ^= x >> 31;
  out.reserve(limit);
  for (std::size_t b = static_cast<std::size_t>(x % stride); b < blocks; b += stride)
    for (std::size_t i = b * block; i < std::min(keys, (b + 1) * block); ++i) out.push_back(i);
  return out;
}

std::vector<double> feature_distances(const StartNodeIndex& index, std::size_t k,
                                      const std::vector<std::size_t>& candidates, const SearchParams& params) {
  std::vector<double> out(candidates.size());
  if (index.keys.empty()) return out;
  const std::vector<double> ft = key_feature(index.test_keys, k, params.l_feat);
  for (std::size_t c = 0; c < candidates.size(); ++c) out[c] = feature_distance_to(index, ft, candidates[c], params);
  return out;
}

StartRanking::StartRanking(const StartNodeIndex& index, std::size_t k, std::vector<std::size_t> candidates,
                           const std::vector<double>* start_cost, const SearchParams& params)
    : candidates_(std::move(candidates)) {
  if (params.init != InitMode::Feature || index.keys.empty()) {
    candidates_.clear();
    return;
  }
  distance_ = feature_distances(index, k, candidates_, params);
  if (start_cost)
    for (std::size_t c = 0; c < candidates_.size(); ++c) distance_[c] += params.junction_rank * (*start_cost)[c];
  order_.resize(candidates_.size());
  std::iota(order_.begin(), order_.end(), 0);
}

StartRanking::StartRanking(std::vector<std::size_t> candidates, std::vector<double> distance,
                           const SearchParams& params)
    : candidates_(std::move(candidates)), distance_(std::move(distance)) {
  if (params.init != InitMode::Feature) {
    candidates_.clear();
    distance_.clear();
  }
  order_.resize(candidates_.size());
  std::iota(order_.begin(), order_.end(), 0);
}

std::vector<int> StartRanking::start_nodes(const MotionGraph& g, const StartNodeIndex& index, int round,
                                           const SearchParams& params, std::mt19937_64& rng) {
  const std::size_t width = static_cast<std::size_t>(params.l_npaths);
  const std::size_t from = static_cast<std::size_t>(round) * width;
  const std::size_t to = std::min(order_.size(), from + width);
  if (to > sorted_) {
    // Ranks [sorted_, to) among the candidates not yet ranked: by distance, ties in candidate
    // (frame) order, as a stable sort of all of them would give.
    const auto less = [&](std::size_t a, std::size_t b) {
      return distance_[a] < distance_[b] || (distance_[a] == distance_[b] && a < b);
    };
    std::partial_sort(order_.begin() + static_cast<std::ptrdiff_t>(sorted_),
                      order_.begin() + static_cast<std::ptrdiff_t>(to), order_.end(), less);
    sorted_ = to;
  }
  std::vector<int> out;
  for (std::size_t r = from; r < to; ++r) out.push_back(index.keys[candidates_[order_[r]]]);
  while (out.size() < width)
    out.push_back(static_cast<int>(random_below(rng, static_cast<std::uint64_t>(g.frame_count()))));
  return out;
}

std::vector<int> initialisation_start_nodes(const MotionGraph& g, const StartNodeIndex& index, std::size_t k, int round,
                                            const SearchParams& params, std::mt19937_64& rng,
                                            const std::vector<double>* start_cost) {
  std::vector<std::size_t> all(index.keys.size());
  std::iota(all.begin(), all.end(), 0);
  StartRanking ranking(index, k, std::move(all), start_cost, params);
  return ranking.start_nodes(g, index, round, params, rng);
}

void initialisation_count_use(StartNodeIndex& index, int frame) {
  const auto it = std::lower_bound(index.keys.begin(), index.keys.end(), frame);
  if (it != index.keys.end() && *it == frame) ++index.occurrences[static_cast<std::size_t>(it - index.keys.begin())];
}

}  // namespace gmg
