#include "search/planner.h"

#include <algorithm>

#include "search/initialisation.h"

namespace gmg {

int Plan::fallback_count(Fallback f) const {
  return static_cast<int>(
      std::count_if(segments.begin(), segments.end(), [f](const PlannedSegment& s) { return s.fallback == f; }));
}

int Plan::fallback_total() const { return static_cast<int>(segments.size()) - fallback_count(Fallback::None); }

int Plan::failure_count() const {
  return static_cast<int>(
      std::count_if(segments.begin(), segments.end(), [](const PlannedSegment& s) { return s.failure; }));
}

namespace {

// The state of one job's planning: the graph, the ranking index and the generator.
class Planner {
 public:
  Planner(const MotionGraph& g, const std::vector<Subsequence>& subs, const SearchParams& params, std::mt19937_64& rng)
      : g_(g), subs_(subs), params_(params), rng_(rng), index_(initialisation_prepare(g, subs, params)) {}

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
        request.start_nodes = initialisation_start_nodes(g_, index_, k, round++, params_, rng_);
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
    initialisation_count_use(index_, r.path.front());
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
    // Paper 4.2.2: after a clean result, the next search starts from the children of its last node.
    std::vector<int> continuation;
    if (previous_clean && !previous_path.empty()) continuation = successors(previous_path.back());
    const BeamResult r = attempts(k, request, continuation, &seg.retries, &seg.continued);
    if (r.accepted) {
      accept(seg, r);
      return seg;
    }
    if (params_.fallbacks) {
      if (request.kind == Termination::Keyword) {
        request = fallback_rhythm_request(request);
        if (try_fallback(k, request, Fallback::KeywordToRhythm, seg)) return seg;
      }
      for (int round = 1; round <= params_.ignore_rounds; ++round) {
        const BeamRequest ignoring =
            fallback_ignore_stops_request(request, index_.keys, g_.frame_count(), round, params_.ignore_rounds, rng_);
        if (try_fallback(k, ignoring, Fallback::IgnoreStops, seg)) return seg;
      }
      seg.fallback = Fallback::HoldLastFrame;
    } else {
      seg.failure = true;
    }
    // Fallback 3 (and the failure case, which must still produce frames): hold the previous
    // result's last frame, or for the very first subsequence the best start node.
    const int hold = !previous_path.empty() ? previous_path.back()
                                            : initialisation_start_nodes(g_, index_, k, 0, params_, rng_).front();
    seg.path.assign(1, hold);
    return seg;
  }

  const MotionGraph& g_;
  const std::vector<Subsequence>& subs_;
  const SearchParams& params_;
  std::mt19937_64& rng_;
  StartNodeIndex index_;
};

}  // namespace

Plan plan_reenactment(const MotionGraph& g, const std::vector<Subsequence>& subs, const SearchParams& params,
                      std::mt19937_64& rng) {
  search_params_validate(params);
  return Planner(g, subs, params, rng).run();
}

}  // namespace gmg
