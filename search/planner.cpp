#include "search/planner.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace gmg {

int Plan::fallback_count(Fallback f) const {
  return static_cast<int>(
      std::count_if(segments.begin(), segments.end(), [f](const PlannedSegment& s) { return s.fallback == f; }));
}

int Plan::fallback_total() const {
  return static_cast<int>(segments.size()) - fallback_count(Fallback::None);
}

int Plan::failure_count() const {
  return static_cast<int>(
      std::count_if(segments.begin(), segments.end(), [](const PlannedSegment& s) { return s.failure; }));
}

std::vector<double> key_feature(const std::vector<int>& keys, std::size_t i, int l_feat) {
  std::vector<double> f(static_cast<std::size_t>(l_feat), 0.0);
  auto key = [&](std::size_t j) { return j < keys.size() ? keys[j] : keys.back(); };
  for (int e = 0; e < l_feat; ++e) f[static_cast<std::size_t>(e)] = key(i + e + 1) - key(i + e);
  return f;
}

namespace {

class Planner {
 public:
  Planner(const MotionGraph& g, const std::vector<Subsequence>& subs, const SearchParams& params, std::mt19937_64& rng)
      : g_(g), subs_(subs), params_(params), rng_(rng), keys_(g.key_frames()),
        occurrences_(keys_.size(), 0) {
    for (std::size_t i = 0; i < keys_.size(); ++i) key_features_.push_back(key_feature(keys_, i, params.l_feat));
    test_keys_.reserve(subs.size() + 1);
    for (const Subsequence& s : subs) test_keys_.push_back(s.start);
    if (!subs.empty()) test_keys_.push_back(subs.back().start + subs.back().length);
  }

  Plan run() {
    Plan plan;
    std::vector<int> previous_path;
    bool previous_clean = false;  // the previous segment needed no fallback
    for (std::size_t k = 0; k < subs_.size(); ++k) {
      PlannedSegment seg = plan_one(k, previous_path, previous_clean);
      previous_clean = seg.accepted && seg.fallback == Fallback::None;
      previous_path = seg.path;
      plan.segments.push_back(std::move(seg));
    }
    return plan;
  }

 private:
  // Start nodes for attempt `round` of the feature ranking of subsequence k: ranks
  // [round * l_npaths, (round + 1) * l_npaths), then random frames once key nodes run out.
  std::vector<int> start_nodes(std::size_t k, int round) {
    const std::size_t width = static_cast<std::size_t>(params_.l_npaths);
    std::vector<int> out;
    if (params_.init == InitMode::Feature && !keys_.empty()) {
      const std::vector<double> ft = key_feature(test_keys_, k, params_.l_feat);
      std::vector<double> distance(keys_.size());
      for (std::size_t m = 0; m < keys_.size(); ++m) {
        const std::vector<double>& fm = key_features_[m];
        double full = 0.0;
        for (int e = 0; e < params_.l_feat; ++e) {
          const double d = params_.w_full[static_cast<std::size_t>(e)] * (ft[static_cast<std::size_t>(e)] - fm[static_cast<std::size_t>(e)]);
          full += d * d;
        }
        const double first = ft[0] > 0 ? std::abs(1.0 - fm[0] / ft[0]) : 0.0;
        distance[m] = params_.lambda_full * std::sqrt(full) + params_.lambda_first * first +
                      params_.lambda_occ * occurrences_[m];
      }
      std::vector<std::size_t> order(keys_.size());
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return distance[a] < distance[b]; });
      for (std::size_t r = static_cast<std::size_t>(round) * width; r < order.size() && out.size() < width; ++r)
        out.push_back(keys_[order[r]]);
    }
    while (out.size() < width)
      out.push_back(static_cast<int>(random_below(rng_, static_cast<std::uint64_t>(g_.frame_count()))));
    return out;
  }

  std::vector<int> successors(int frame) const {
    std::vector<int> out;
    for (auto [it, end] = boost::out_edges(static_cast<std::size_t>(frame), g_.graph); it != end; ++it)
      out.push_back(static_cast<int>(boost::target(*it, g_.graph)));
    return out;
  }

  // Up to 1 + retries beam searches for one request. The first may start from `first_starts`;
  // *from_first tells whether the accepted one was that first search.
  BeamResult attempts(std::size_t k, BeamRequest request, const std::vector<int>& first_starts, int* retries,
                      bool* from_first = nullptr) {
    int round = 0;
    for (int attempt = 0; attempt <= params_.retries; ++attempt) {
      if (attempt == 0 && !first_starts.empty()) {
        request.start_nodes = first_starts;
      } else {
        request.start_nodes = start_nodes(k, round++);
      }
      if (attempt > 0) ++*retries;
      BeamResult r = beam_search(g_, request, params_);
      if (r.accepted) {
        if (from_first) *from_first = attempt == 0 && !first_starts.empty();
        return r;
      }
    }
    return BeamResult{};
  }

  void accept(PlannedSegment& seg, const BeamResult& r) {
    seg.accepted = true;
    seg.path = r.path;
    seg.cost = r.cost;
    const auto it = std::lower_bound(keys_.begin(), keys_.end(), r.path.front());
    if (it != keys_.end() && *it == r.path.front()) ++occurrences_[static_cast<std::size_t>(it - keys_.begin())];
  }

  // A fallback's searches (each one counts as a retry); on success records it in seg.
  bool try_fallback(std::size_t k, const BeamRequest& request, Fallback fallback, PlannedSegment& seg) {
    const BeamResult r = attempts(k, request, {}, &seg.retries);
    ++seg.retries;
    if (!r.accepted) return false;
    seg.fallback = fallback;
    accept(seg, r);
    return true;
  }

  PlannedSegment plan_one(std::size_t k, const std::vector<int>& previous_path, bool previous_clean) {
    PlannedSegment seg;
    seg.sub = subs_[k];
    BeamRequest request;
    request.target_length = seg.sub.length;
    request.kind = seg.sub.kind;
    request.keyword = seg.sub.keyword;
    std::vector<int> continuation;
    if (previous_clean && !previous_path.empty()) continuation = successors(previous_path.back());
    BeamResult r = attempts(k, request, continuation, &seg.retries, &seg.continued);
    if (r.accepted) {
      accept(seg, r);
      return seg;
    }
    if (params_.fallbacks) {
      // 1: a keyword that cannot be matched falls back to rhythm termination.
      if (request.kind == Termination::Keyword) {
        request.kind = Termination::Rhythm;
        request.keyword.clear();
        if (try_fallback(k, request, Fallback::KeywordToRhythm, seg)) return seg;
      }
      // 2: paths stop too early: ignore a growing share of the stopping nodes.
      for (int round = 1; round <= params_.ignore_rounds; ++round) {
        const double share = static_cast<double>(round) / (params_.ignore_rounds + 1);
        request.ignore_stop.assign(static_cast<std::size_t>(g_.frame_count()), 0);
        for (int f : keys_)
          if (static_cast<double>(rng_() >> 11) * 0x1.0p-53 < share) request.ignore_stop[static_cast<std::size_t>(f)] = 1;
        if (try_fallback(k, request, Fallback::IgnoreStops, seg)) return seg;
      }
      seg.fallback = Fallback::HoldLastFrame;
    } else {
      seg.failure = true;
    }
    // 3 (and the failure case, which must still produce frames): hold the previous result's
    // last frame, or for the very first subsequence the best start node.
    const int hold = !previous_path.empty() ? previous_path.back() : start_nodes(k, 0).front();
    seg.path.assign(1, hold);
    return seg;
  }

  const MotionGraph& g_;
  const std::vector<Subsequence>& subs_;
  const SearchParams& params_;
  std::mt19937_64& rng_;
  std::vector<int> keys_;
  std::vector<std::vector<double>> key_features_;
  std::vector<int> occurrences_;
  std::vector<int> test_keys_;
};

}  // namespace

Plan plan_reenactment(const MotionGraph& g, const std::vector<Subsequence>& subs, const SearchParams& params,
                      std::mt19937_64& rng) {
  return Planner(g, subs, params, rng).run();
}

}  // namespace gmg
