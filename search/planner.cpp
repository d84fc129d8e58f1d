#include "search/planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "search/anchors.h"
#include "search/continuation.h"
#include "search/initialisation.h"
#include "search/junction.h"
#include "search/rests.h"
#include "search/reuse.h"
#include "search/speech_match.h"
#include "search/start_ranking.h"

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

int total_frames(const std::vector<Subsequence>& subs) {
  return subs.empty() ? 0 : subs.back().start + subs.back().length;
}

// The state of one job's planning: the graph, the ranking index, the junction, speech and reuse
// costs, the seed's preference, the start-node ranker and the generator. In the paper's mode
// every natural-planner step is skipped.
class Planner {
 public:
  Planner(const MotionGraph& g, const std::vector<Subsequence>& subs, const SearchParams& params, std::mt19937_64& rng,
          const std::vector<float>& test_speech)
      : g_(g),
        subs_(subs),
        params_(params),
        rng_(rng),
        natural_(params.planner == PlannerMode::Natural),
        index_(initialisation_prepare(g, subs, params)),
        junction_(g),
        speech_(g, natural_ ? test_speech : std::vector<float>{}, total_frames(subs), params.rest_weight),
        reuse_(g.frame_count(), params.reuse_halflife_s * g.motion.fps, params.reuse_cap_plays,
               static_cast<int>(std::lround(params.reuse_cap_window_s * g.motion.fps)),
               static_cast<int>(std::lround(params.no_return_s * g.motion.fps))),
        // The preference is drawn before the ranker's sample seed: the order of the generator's draws.
        preference_(natural_ && params.variety > 0.0 ? SeedPreference(g, params.variety, rng) : SeedPreference()),
        ranker_(g, subs, params, natural_, index_, junction_, speech_, reuse_, preference_, rng),
        rests_(g),
        spike_budget_(spike_budget(g, total_frames(subs))) {}

  Plan run() {
    Plan plan;
    std::vector<int> previous_path;
    bool previous_clean = false;  // the previous segment needed no fallback
    for (std::size_t k = 0; k < subs_.size(); ++k) {
      PlannedSegment seg = plan_one(k, previous_path, previous_clean);
      describe_junction(seg, previous_path);
      if (natural_) {
        seg.speech_cost = speech_.path_cost(seg.path, seg.sub.start, seg.sub.length);
        reuse_.play(seg.path, seg.sub.start);
      }
      spikes_used_ += spike_frames(seg.path);
      previous_clean = seg.accepted && seg.fallback == Fallback::None;
      previous_path = seg.path;
      plan.segments.push_back(std::move(seg));
      // The junction poses of this subsequence were read from the motion here and there: give
      // those pages back (a graph served from its file keeps only what is read next resident).
      motion_release_pages(g_.motion);
    }
    return plan;
  }

 private:
  bool continues(int f) const { return f + 1 < g_.frame_count() && !(g_.node(f).kinds & kBreakNode); }

  std::vector<int> successors(int frame) const {
    std::vector<int> out;
    for (const GraphEdge e : g_.graph.out_edges(static_cast<GraphVertex>(frame)))
      out.push_back(static_cast<int>(g_.graph.target(e)));
    return out;
  }

  // Start nodes of attempt `round` with their estimated costs.
  void ranked_starts(std::size_t k, int round, BeamRequest& request) {
    request.start_nodes = ranker_.start_nodes(k, reference_, round, rng_);
    starts_cost(request);
  }

  void starts_cost(BeamRequest& request) {
    request.start_costs.clear();
    if (!natural_) return;
    for (int s : request.start_nodes)
      request.start_costs.push_back((reference_ >= 0 && params_.junction_beam > 0.0
                                         ? params_.junction_beam * junction_.cost(reference_, s)
                                         : 0.0) +
                                    preference_.of(s));
  }

  // The natural planner's additions to a request: transitions at the graph's own scale, and the
  // speech and reuse costs of the path's frames.
  void natural_request(const Subsequence& sub, BeamRequest& request) const {
    if (!natural_) return;
    request.weight_scale = 1.0 / junction_.normaliser();
    // Two transitions within a quarter second overlap their blends (a hub frame used as a
    // stepping stone between two stretches): 1-frame visits made up most of the most replayed
    // frames on BEAT2.
    request.min_run = static_cast<int>(std::lround(0.25 * g_.motion.fps));
    request.speech = &speech_;
    request.speech_weight = params_.speech_weight;
    request.end_weight = params_.speech_weight * params_.beat_weight;
    request.test_start = sub.start;
    request.reuse = &reuse_;
    request.reuse_weight = params_.reuse_weight;
    request.time = sub.start;
  }

  // Among the candidates (sorted by cost), the natural planner draws one of the near-equal ones
  // (within kNearEqual of the best); the paper takes the best.
  const BeamCandidate& choose(std::size_t k, const std::vector<BeamCandidate>& candidates) {
    if (!natural_) return candidates.front();
    constexpr double kNearEqual = 0.05;
    std::size_t near = 0;
    while (near < candidates.size() && candidates[near].cost <= candidates.front().cost + kNearEqual) ++near;
    near = std::max<std::size_t>(near, 1);
    // Among near-equal candidates, playing on beats a jump: a junction avoided is worth more than
    // the small cost difference.
    for (std::size_t i = 0; i < near; ++i)
      if (continuing_from_ >= 0 && candidates[i].path.front() == continuing_from_) return candidates[i];
    // One step of lookahead: prefer the near-equal paths whose end continues naturally into the
    // next subsequence (a junction avoided there is worth more than the small cost difference;
    // measured: docs/decisions.md, Junction-aware search).
    if (k + 1 < subs_.size()) {
      BeamRequest next;
      next.target_length = subs_[k + 1].length;
      next.kind = subs_[k + 1].kind;
      next.keyword = subs_[k + 1].keyword;
      std::vector<std::size_t> good;
      for (std::size_t i = 0; i < near; ++i) {
        const int stop = candidates[i].path.back();  // played as the next subsequence's first frame
        if (!natural_continuation(g_, stop, next, params_).empty()) good.push_back(i);
      }
      if (!good.empty()) return candidates[good[random_below(rng_, good.size())]];
    }
    return candidates[random_below(rng_, near)];
  }

  // Up to `max_attempts` beam searches for one request. The first may start from `first_starts`.
  BeamResult attempts(std::size_t k, BeamRequest request, const std::vector<int>& first_starts, int* retries,
                      int max_attempts) {
    int round = 0;
    for (int attempt = 0; attempt < max_attempts; ++attempt) {
      if (attempt == 0 && !first_starts.empty() && natural_) {
        // The natural planner's first search starts both from where the output is (the previous
        // path's successors: its continuation and the graph's transitions out of it) and from the
        // best-ranked key nodes anywhere, each priced by its junction cost: a stretch that suits
        // the speech better is worth a jump even where the graph has no edge to it.
        ranked_starts(k, round++, request);
        for (int s : first_starts)
          if (std::find(request.start_nodes.begin(), request.start_nodes.end(), s) == request.start_nodes.end())
            request.start_nodes.push_back(s);
        starts_cost(request);
      } else if (attempt == 0 && !first_starts.empty()) {
        request.start_nodes = first_starts;
        starts_cost(request);
      } else {
        ranked_starts(k, round++, request);
      }
      if (attempt > 0) ++*retries;
      BeamResult r = beam_search(g_, request, params_);
      if (r.accepted) return r;
    }
    return BeamResult{};
  }

  void accept(PlannedSegment& seg, const std::vector<int>& path, double cost) {
    seg.accepted = true;
    seg.path = path;
    seg.cost = cost;
    initialisation_count_use(index_, path.front());
    // The natural planner plays the stop node as the next subsequence's first frame, where the
    // test's key frame is, instead of as this one's last frame, one frame early; the next piece
    // continues from it. Besides the rhythm, this keeps playback at the capture's speed: a path
    // that keeps its stop node advances len source frames in len - 1 output steps, plus one more
    // into the next piece, so every piece played ~1/l_sub fast (docs/decisions.md, Junction-aware
    // search).
    if (natural_ && seg.path.size() >= 2) seg.path.pop_back();
  }

  // Candidates that replay a frame past its cap (or jump back into what was just played) are no
  // candidates: the fallbacks look further, and the last one plays the capture on. Nor are, while
  // others remain, those that would play more of the capture's jerk spikes than the output's share
  // of them (engine/motion/spikes.h): a spike is played no more often than the speaker made it.
  // strict: a fallback's paths, which ignore stops and wander: looping ones go even when none else
  // remains (the next fallback plays on or holds).
  void drop_capped(std::vector<BeamCandidate>& candidates, bool strict = false) const {
    if (!natural_) return;
    if (params_.reuse_weight > 0.0) {
      const double capped = params_.reuse_weight * ReuseTracker::kCapCost;
      candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                      [&](const BeamCandidate& c) { return c.cost >= capped; }),
                       candidates.end());
    }
    // A path that loops back into itself, where another does not (the beam's cost sees a path's
    // reuse from its start, not the plays the path makes of itself).
    std::vector<BeamCandidate> straight;
    for (const BeamCandidate& c : candidates)
      if (!ReuseTracker::loops(c.path)) straight.push_back(c);
    if (!straight.empty() || strict) candidates.swap(straight);
    const long left = spike_budget_ - spikes_used_;
    std::vector<BeamCandidate> within;
    for (const BeamCandidate& c : candidates)
      if (spike_frames(c.path) <= std::max(0L, left)) within.push_back(c);
    if (!within.empty()) candidates.swap(within);
  }

  long spike_frames(const std::vector<int>& path) const {
    if (g_.spikes.empty()) return 0;
    long n = 0;
    for (int f : path) n += g_.spikes[static_cast<std::size_t>(f)];
    return n;
  }

  // The output's share of the capture's spikes: as many spiking frames per output frame as the
  // capture has per frame, rounded up.
  static long spike_budget(const MotionGraph& g, int output_frames) {
    if (g.spikes.empty() || g.frame_count() == 0) return 0;
    long n = 0;
    for (std::size_t f = 0; f < g.spikes.size(); ++f) n += g.spikes[f];
    return (n * output_frames + g.frame_count() - 1) / g.frame_count();
  }

  // A fallback's searches (each one counts as a retry); on success records it in seg.
  bool try_fallback(std::size_t k, BeamRequest request, Fallback fallback, PlannedSegment& seg) {
    natural_request(seg.sub, request);
    BeamResult r = attempts(k, request, {}, &seg.retries, params_.retries + 1);
    ++seg.retries;
    if (!r.accepted) return false;
    drop_capped(r.candidates, true);
    if (r.candidates.empty()) return false;
    seg.fallback = fallback;
    const BeamCandidate& c = choose(k, r.candidates);
    accept(seg, c.path, c.cost);
    return true;
  }

  // The natural continuations as candidates: the length mismatch, and the speech and reuse of
  // what they play (the stop node is the next subsequence's first frame, so it is not played).
  void add_continuations(const Subsequence& sub, int from, const BeamRequest& request,
                         std::vector<BeamCandidate>& out) const {
    for (std::vector<int>& path : natural_continuations(g_, from, request, params_)) {
      std::vector<int> played(path.begin(), path.end() - 1);
      const double cost = params_.lambda_len * std::abs(1.0 - static_cast<double>(path.size()) / sub.length) +
                          params_.speech_weight * (speech_.path_cost(played, sub.start, sub.length) +
                                                   params_.beat_weight * speech_.end_cost(path.back())) +
                          params_.reuse_weight * reuse_.path_cost(played, sub.start);
      out.push_back({std::move(path), cost});
    }
  }

  // A pinned stretch plays its graph frames as given; a rest plays the reference's stretch of the
  // subsequence's length that is stillest for what it costs to get there: the junction from where
  // the output is (nothing when it plays on into it), the stillness (activity, 1 = the speaker's
  // typical motion) weighed like a pause's rest cost, reuse and the seed's preference.
  void plan_fixed(PlannedSegment& seg) {
    seg.accepted = true;
    const int length = seg.sub.length;
    if (seg.sub.fixed == Fixed::Pin) {
      for (int i = 0; i < length; ++i) seg.path.push_back(seg.sub.source + i);
      return;
    }
    // The still part follows `lead` frames of the reference's own way into it.
    const int lead = std::min(seg.sub.lead, length - 1), still = length - lead;
    std::vector<int> candidates;
    std::vector<int> stillest = rests_.stillest(still, kRestCandidates);
    for (int f : rests_.stillest_pauses(still, kRestCandidates / 4))
      if (std::find(stillest.begin(), stillest.end(), f) == stillest.end()) stillest.push_back(f);
    for (int f : stillest)
      if (f - lead >= 0 && std::isfinite(rests_.stillness(f - lead, length))) candidates.push_back(f - lead);
    if (continuing_from_ >= 0 && std::isfinite(rests_.stillness(continuing_from_, length)))
      candidates.push_back(continuing_from_);
    if (candidates.empty()) {  // a graph without activity: play on, or hold
      seg.path = continuing_from_ >= 0 ? natural_run(g_, continuing_from_, length)
                                       : std::vector<int>{reference_ < 0 ? 0 : reference_};
      return;
    }
    auto score = [&](int f) {
      std::vector<int> path(static_cast<std::size_t>(length));
      std::iota(path.begin(), path.end(), f);
      const double junction =
          reference_ < 0 || f == continuing_from_ ? 0.0 : params_.junction_beam * junction_.cost(reference_, f);
      const double cost = junction + kRestStillness * params_.rest_weight * rests_.stillness(f + lead, still) +
                          kRestPause * (1.0 - rests_.pause_share(f + lead, still)) +
                          params_.reuse_weight * reuse_.path_cost(path, seg.sub.start) +
                          (f == continuing_from_ ? 0.0 : preference_.of(f));
      return BeamCandidate{std::move(path), cost};
    };
    std::vector<BeamCandidate> scored;
    for (int f : candidates) scored.push_back(score(f));
    std::vector<BeamCandidate> uncapped = scored;
    drop_capped(uncapped);
    if (uncapped.empty()) {
      // The stillest stretches are neighbours of a few rests; when those are played out, look
      // further down the list, still in order of stillness, for rests not yet at their cap.
      for (int f : rests_.stillest(still, std::numeric_limits<int>::max())) {
        if (f - lead < 0 || !std::isfinite(rests_.stillness(f - lead, length))) continue;
        std::vector<BeamCandidate> one{score(f - lead)};
        drop_capped(one);
        if (!one.empty()) uncapped.push_back(std::move(one.front()));
        if (uncapped.size() >= kRestCandidates / 4) break;
      }
    }
    std::stable_sort(uncapped.begin(), uncapped.end(),
                     [](const BeamCandidate& a, const BeamCandidate& b) { return a.cost < b.cost; });
    std::stable_sort(scored.begin(), scored.end(),
                     [](const BeamCandidate& a, const BeamCandidate& b) { return a.cost < b.cost; });
    if (!uncapped.empty()) scored.swap(uncapped);  // else the least replayed of the few rests there are
    constexpr double kNearEqual = 0.05;
    std::size_t near = 1;
    while (near < scored.size() && scored[near].cost <= scored.front().cost + kNearEqual) ++near;
    const BeamCandidate& c = scored[random_below(rng_, near)];
    seg.path = c.path;
    seg.cost = c.cost;
    seg.reuse_cost = reuse_.path_cost(c.path, seg.sub.start);
  }
  // Rests weigh this many stillest stretches (and the natural continuation): the reference's still
  // stretches are few, so more only adds neighbours of the same ones.
  static constexpr int kRestCandidates = 64;
  // A rest's stillness cost per unit of activity, as a share of rest_weight: at the default 12, a
  // stretch moving as the speaker typically does costs 3 more than a still one, three typical
  // transitions: a jump to rest is worth it, a far one is not.
  static constexpr double kRestStillness = 0.25;
  // A rest's cost when the reference speaks all through it: a typical transition. The speaker's
  // own pauses are where they rest; a still moment mid-sentence is taken only when it is much
  // nearer or stiller.
  static constexpr double kRestPause = 1.0;

  PlannedSegment plan_one(std::size_t k, const std::vector<int>& previous_path, bool previous_clean) {
    PlannedSegment seg;
    seg.sub = subs_[k];
    BeamRequest request;
    request.target_length = seg.sub.length;
    request.kind = seg.sub.kind;
    request.keyword = seg.sub.keyword;
    request.stop_frame = seg.sub.stop_frame;
    // The frame the output would continue into; junction costs are measured from it.
    const int last = previous_path.empty() ? -1 : previous_path.back();
    reference_ = last < 0 ? -1 : (continues(last) ? last + 1 : last);
    continuing_from_ = last >= 0 && continues(last) ? last + 1 : -1;
    seg.junction_from = reference_;
    seg.reuse_cost = 0.0;
    if (seg.sub.fixed != Fixed::None) {
      plan_fixed(seg);
      return seg;
    }
    // Paper 4.2.2: after a clean result, the next search starts from the children of its last
    // node. The natural planner always does, since its junction costs price every start.
    std::vector<int> first_starts;
    if (last >= 0 && (previous_clean || natural_)) first_starts = successors(last);
    if (natural_) {
      // The natural continuation competes with the beam's paths on cost: it is taken when what it
      // plays suits the speech at least as well as a jump to a better-suited stretch would,
      // junction included.
      natural_request(seg.sub, request);
      std::vector<BeamCandidate> candidates;
      if (last >= 0 && continues(last)) add_continuations(seg.sub, last + 1, request, candidates);
      // With a continuation at hand one search decides; retries are for when nothing fits, and
      // for when the continuation would play a frame past its reuse cap (with only it at hand, a
      // first search that found nothing let it play a frame a fourth time in a minute).
      bool continuation_capped = true;
      for (const BeamCandidate& c : candidates)
        if (c.cost < params_.reuse_weight * ReuseTracker::kCapCost) continuation_capped = false;
      const int max_attempts =
          candidates.empty() || (params_.reuse_weight > 0.0 && continuation_capped) ? params_.retries + 1 : 1;
      BeamResult r = attempts(k, request, first_starts, &seg.retries, max_attempts);
      candidates.insert(candidates.end(), r.candidates.begin(), r.candidates.end());
      drop_capped(candidates);
      if (!candidates.empty()) {
        std::stable_sort(candidates.begin(), candidates.end(),
                         [](const BeamCandidate& a, const BeamCandidate& b) { return a.cost < b.cost; });
        const BeamCandidate& c = choose(k, candidates);
        seg.reuse_cost = reuse_.path_cost(c.path, seg.sub.start);
        accept(seg, c.path, c.cost);
        return seg;
      }
    } else {
      BeamResult r = attempts(k, request, first_starts, &seg.retries, params_.retries + 1);
      if (r.accepted) {
        accept(seg, r.path, r.cost);
        return seg;
      }
    }
    if (params_.fallbacks) {
      if (request.kind != Termination::Rhythm) {
        request = fallback_rhythm_request(request);
        if (try_fallback(k, request, Fallback::KeywordToRhythm, seg)) return seg;
      }
      for (int round = 1; round <= params_.ignore_rounds; ++round) {
        const BeamRequest ignoring =
            fallback_ignore_stops_request(request, index_.keys, g_.frame_count(), round, params_.ignore_rounds, rng_);
        if (try_fallback(k, ignoring, Fallback::IgnoreStops, seg)) return seg;
      }
      if (natural_ && last >= 0 && continues(last)) {
        // Played on only where that plays no frame past its cap: a hold is still, a replay a
        // fourth time is the same gesture again.
        std::vector<int> run = natural_run(g_, last + 1, seg.sub.length);
        if (params_.reuse_weight <= 0.0 || reuse_.path_cost(run, seg.sub.start) < ReuseTracker::kCapCost) {
          seg.fallback = Fallback::ContinueMotion;
          seg.path = std::move(run);
          return seg;
        }
      }
      seg.fallback = Fallback::HoldLastFrame;
    } else {
      seg.failure = true;
    }
    // Fallback 3 (and the failure case, which must still produce frames): hold the previous
    // result's last frame, or for the very first subsequence the best start node.
    seg.path.assign(1, last >= 0 ? last : ranker_.first_by_feature(k, rng_));
    return seg;
  }

  // What the report says about the junction into seg and the transitions inside it.
  void describe_junction(PlannedSegment& seg, const std::vector<int>& previous_path) {
    const int last = previous_path.empty() ? -1 : previous_path.back();
    seg.continued = last >= 0 && continues(last) && seg.path.front() == last + 1;
    if (seg.junction_from >= 0 && !seg.continued) {
      seg.junction_cost = junction_.cost(seg.junction_from, seg.path.front());
      seg.junction_gap = junction_.largest_joint_gap(seg.junction_from, seg.path.front());
    }
    for (std::size_t i = 1; i < seg.path.size(); ++i)
      seg.transitions_inside += !(seg.path[i] == seg.path[i - 1] + 1 && continues(seg.path[i - 1]));
  }

  const MotionGraph& g_;
  const std::vector<Subsequence>& subs_;
  const SearchParams& params_;
  std::mt19937_64& rng_;
  const bool natural_;
  StartNodeIndex index_;
  JunctionCost junction_;
  SpeechMatch speech_;
  ReuseTracker reuse_;
  SeedPreference preference_;
  StartNodeRanker ranker_;
  RestFinder rests_;
  long spike_budget_ = 0, spikes_used_ = 0;
  int reference_ = -1;        // the current subsequence's junction reference frame
  int continuing_from_ = -1;  // the natural successor of the previous path, or -1
};

}  // namespace

Plan plan_reenactment(const MotionGraph& g, const std::vector<Subsequence>& subs, const SearchParams& params,
                      std::mt19937_64& rng, const std::vector<float>& test_speech, const std::vector<Anchor>& anchors) {
  search_params_validate(params);
  if (params.planner == PlannerMode::Natural && (params.merge_below > 1 || !anchors.empty())) {
    const std::vector<Subsequence> merged =
        place_anchors(merge_short_subsequences(subs, params.merge_below), anchors, params.merge_below);
    return Planner(g, merged, params, rng, test_speech).run();
  }
  return Planner(g, place_anchors(subs, anchors, 0), params, rng, test_speech).run();
}

}  // namespace gmg
