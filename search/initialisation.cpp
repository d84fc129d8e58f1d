#include "search/initialisation.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace gmg {

std::vector<double> key_feature(const std::vector<int>& keys, std::size_t i, int l_feat) {
  std::vector<double> f(static_cast<std::size_t>(l_feat), 0.0);
  auto key = [&](std::size_t j) { return j < keys.size() ? keys[j] : keys.back(); };
  for (int e = 0; e < l_feat; ++e) f[static_cast<std::size_t>(e)] = key(i + e + 1) - key(i + e);
  return f;
}

StartNodeIndex initialisation_prepare(const MotionGraph& g, const std::vector<Subsequence>& subs,
                                      const SearchParams& params) {
  StartNodeIndex index;
  index.keys = g.key_frames();
  index.occurrences.assign(index.keys.size(), 0);
  for (std::size_t i = 0; i < index.keys.size(); ++i)
    index.features.push_back(key_feature(index.keys, i, params.l_feat));
  index.test_keys.reserve(subs.size() + 1);
  for (const Subsequence& s : subs) index.test_keys.push_back(s.start);
  if (!subs.empty()) index.test_keys.push_back(subs.back().start + subs.back().length);
  return index;
}

namespace {

double feature_distance_to(const StartNodeIndex& index, const std::vector<double>& ft, std::size_t m,
                           const SearchParams& params) {
  const std::vector<double>& fm = index.features[m];
  double full = 0.0;
  for (std::size_t e = 0; e < ft.size(); ++e) {
    const double d = params.w_full[e] * (ft[e] - fm[e]);
    full += d * d;
  }
  const double first = ft[0] > 0 ? std::abs(1.0 - fm[0] / ft[0]) : 0.0;
  return params.lambda_full * std::sqrt(full) + params.lambda_first * first + params.lambda_occ * index.occurrences[m];
}

}  // namespace

double feature_distance(const StartNodeIndex& index, std::size_t k, std::size_t m, const SearchParams& params) {
  return feature_distance_to(index, key_feature(index.test_keys, k, params.l_feat), m, params);
}

std::vector<int> initialisation_start_nodes(const MotionGraph& g, const StartNodeIndex& index, std::size_t k, int round,
                                            const SearchParams& params, std::mt19937_64& rng,
                                            const std::vector<double>* start_cost) {
  const std::size_t width = static_cast<std::size_t>(params.l_npaths);
  std::vector<int> out;
  if (params.init == InitMode::Feature && !index.keys.empty()) {
    const std::vector<double> ft = key_feature(index.test_keys, k, params.l_feat);
    std::vector<double> distance(index.keys.size());
    for (std::size_t m = 0; m < index.keys.size(); ++m) {
      distance[m] = feature_distance_to(index, ft, m, params);
      if (start_cost) distance[m] += params.junction_rank * (*start_cost)[m];
    }
    std::vector<std::size_t> order(index.keys.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return distance[a] < distance[b]; });
    for (std::size_t r = static_cast<std::size_t>(round) * width; r < order.size() && out.size() < width; ++r)
      out.push_back(index.keys[order[r]]);
  }
  while (out.size() < width)
    out.push_back(static_cast<int>(random_below(rng, static_cast<std::uint64_t>(g.frame_count()))));
  return out;
}

void initialisation_count_use(StartNodeIndex& index, int frame) {
  const auto it = std::lower_bound(index.keys.begin(), index.keys.end(), frame);
  if (it != index.keys.end() && *it == frame) ++index.occurrences[static_cast<std::size_t>(it - index.keys.begin())];
}

}  // namespace gmg
