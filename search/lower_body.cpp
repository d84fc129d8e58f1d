#include "search/lower_body.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/error.h"
#include "search/initialisation.h"

namespace gmg {
namespace {

constexpr double kNearEqual = 0.05;     // targets within this cost of the best are drawn among
constexpr double kWithheld = 1.0;       // what a target the seed withholds costs (half a typical stance gap)
constexpr double kLongRunS = 5.0;       // a stretch that can play this long needs no other change soon
constexpr double kMinRunS = 2.0;        // the least a changed-into stretch must be able to play
constexpr double kRunEndWindowS = 6.0;  // a change before a run's end is sought in its last seconds
constexpr double kRestWindowS = 3.0;    // a change into a rest is sought in the seconds before it
// A rest whose legs are not still costs kStillWeight per share of its frames that move; a change of
// stance is made for it only when that saves more than the change's own cost (its gap, ...) plus
// kChangeCost: a stance change the legs would not need is itself motion.
constexpr double kStillWeight = 2.0;
constexpr double kChangeCost = 0.5;
constexpr std::size_t kFromCandidates = 8;  // stance frames weighed as the place of a change

class LowerPlanner {
 public:
  LowerPlanner(const Stance& stance, const CaptureRuns& runs, const std::vector<Anchor>& rests, int total, double fps,
               const LowerBodyParams& params, std::mt19937_64& rng)
      : st_(stance), runs_(runs), total_(total), fps_(fps), params_(params), rng_(rng) {
    const int frames = runs.frame_count();
    plays_.assign(static_cast<std::size_t>(frames), 0);
    for (int f = 0; f < frames; ++f)
      if (st_.planted[static_cast<std::size_t>(f)]) planted_.push_back(f);
    // Still frames ahead of every frame, inside its capture run.
    still_ahead_.assign(static_cast<std::size_t>(frames), 0);
    for (int f = frames - 1; f >= 0; --f) {
      const bool still = st_.speed[static_cast<std::size_t>(f)] < st_.still_speed;
      const bool next = f + 1 < frames && runs_.continues(f);
      still_ahead_[static_cast<std::size_t>(f)] =
          still ? 1 + (next ? still_ahead_[static_cast<std::size_t>(f) + 1] : 0) : 0;
    }
    for (const Anchor& a : rests)
      if (a.kind == Fixed::Rest) windows_.push_back({a.start + a.lead, a.start + a.length});
    typical_gap_ = typical_gap();
    if (params.variety > 0.0) {
      const int block = std::max(1, static_cast<int>(std::lround(fps)));
      withheld_.resize(static_cast<std::size_t>(frames / block + 1));
      for (char& w : withheld_) w = static_cast<double>(random_below(rng_, 1u << 20)) < params.variety * (1u << 20);
      block_ = block;
    }
  }

  LowerPlan run() {
    LowerPlan plan;
    if (total_ <= 0) return plan;
    int t = 0;
    int s = start_frame();
    plan.segments.push_back({0, 0, s, LowerChange::Start, 0.0});
    const int min_gap = static_cast<int>(std::lround(1.0 * fps_));  // no two changes within a second
    std::size_t next_window = 0;
    for (;;) {
      const int end = t + (runs_.last(s) - s) + 1;  // the first output frame this stretch cannot play
      // The next rest a change of stance makes stiller than playing on, by more than the change costs.
      Change c;
      LowerChange why = LowerChange::Rest;
      for (; next_window < windows_.size(); ++next_window) {
        const auto [a, b] = windows_[next_window];
        if (a >= std::min(end, total_)) break;
        if (a < t + min_gap) continue;
        const int need = b - a;
        const double stay = kStillWeight * deficit(s + (a - t), need);
        if (stay == 0.0) continue;
        c = change(s, t, a - static_cast<int>(std::lround(kRestWindowS * fps_)), a, -1, a, need);
        if (c.at >= 0 && c.cost + kChangeCost < stay) break;
        c = Change{};
      }
      if (c.at < 0) {
        if (end >= total_) break;
        // Before the run ends, at the stance of the last few seconds that leads to the nearest one.
        // A rest that starts there or within a second after the run ends: the change comes before
        // it and goes to a stance still for it (else the legs would move through the rest, the
        // stretch changed into too new to change again).
        why = LowerChange::RunEnd;
        const int lo = end - static_cast<int>(std::lround(kRunEndWindowS * fps_));
        int hi = end - 2, rest_at = -1, need = 0;
        for (const auto& [a, b] : windows_) {
          if (b <= std::max(lo, t + 1)) continue;
          if (a < end + min_gap && a > std::max(lo, t + 1)) {
            rest_at = a;
            need = b - a;
            hi = std::min(hi, a);
          }
          break;
        }
        c = change(s, t, lo, hi, end - 1, rest_at, need);
      }
      const int at = c.at, to = c.to;
      played(s, at - t);
      plan.segments.back().length = at - t;
      plan.segments.push_back({at, 0, to, why, std::sqrt(stance_distance(st_, c.from, to))});
      t = at;
      s = to;
      if (why == LowerChange::Rest) ++next_window;
    }
    plan.segments.back().length = total_ - t;
    return plan;
  }

 private:
  void played(int s, int length) {
    for (int i = 0; i < length; ++i) ++plays_[static_cast<std::size_t>(s + i)];
  }

  // The median stance distance of planted frames paired across the reference: 1 is a typical gap.
  double typical_gap() const {
    if (planted_.size() < 2) return 1.0;
    std::vector<double> d;
    const std::size_t n = planted_.size();
    for (std::size_t i = 0; i < 512; ++i)
      d.push_back(std::sqrt(stance_distance(st_, planted_[(i * 7919) % n], planted_[(i * 104729 + n / 2) % n])));
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
    const double m = d[d.size() / 2];
    return m > 0.0 ? m : 1.0;
  }

  bool withheld(int f) const { return !withheld_.empty() && withheld_[static_cast<std::size_t>(f / block_)]; }

  // The cost of changing into graph frame b: the stance gap (squared, over a typical gap: a change
  // between near-identical stances is what keeps the feet where they are), how far the hips stand
  // from where they stood (the root anchor would have to carry it), the rest it gives (`need` still
  // frames from `lead` frames on), a run too short for what is left (another change soon), reuse.
  double cost(int from, int b, int lead, int need, int left) const {
    if (std::abs(b - from) < 2 * fps_) return std::numeric_limits<double>::infinity();  // a stutter, not a change
    const int last = runs_.last(b);
    if (b + lead > last) return std::numeric_limits<double>::infinity();
    // A stretch that cannot play kMinRunS (or what is left) forces another change at once, from a
    // frame that need not be a stance: two short stretches then ping-pong between run ends.
    if (last - b + 1 < std::min(left, static_cast<int>(std::lround(kMinRunS * fps_))))
      return std::numeric_limits<double>::infinity();
    const double gap = std::sqrt(stance_distance(st_, from, b)) / typical_gap_;
    double c = 4.0 * gap * gap;
    const double dx = st_.place[2 * static_cast<std::size_t>(from)] - st_.place[2 * static_cast<std::size_t>(b)];
    const double dz =
        st_.place[2 * static_cast<std::size_t>(from) + 1] - st_.place[2 * static_cast<std::size_t>(b) + 1];
    c += 0.5 * std::hypot(dx, dz);
    c += kStillWeight * deficit(b + lead, need);
    const int wanted = std::min(left, static_cast<int>(std::lround(kLongRunS * fps_)));
    if (wanted > 0) c += 2.0 * std::max(0.0, 1.0 - static_cast<double>(last - b + 1) / wanted);
    int most = 0;
    const int span = std::min(last, b + std::max(lead + need, static_cast<int>(std::lround(2.0 * fps_))));
    for (int f = b; f <= span; ++f) most = std::max(most, static_cast<int>(plays_[static_cast<std::size_t>(f)]));
    if (params_.reuse_cap_plays > 0 && most >= params_.reuse_cap_plays) c += 100.0;
    c += 0.25 * most * most;
    if (withheld(b)) c += kWithheld;
    return c;
  }

  int choose(const std::vector<std::pair<double, int>>& scored) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [c, f] : scored) best = std::min(best, c);
    std::vector<int> near;
    for (const auto& [c, f] : scored)
      if (c <= best + kNearEqual) near.push_back(f);
    return near[random_below(rng_, near.size())];
  }

  // Candidates are weighed nearest stance first: every other part of the cost is >= 0, so once
  // the gap alone exceeds the best cost found by more than kNearEqual nothing further can be chosen.
  std::pair<double, int> target(int from, int lead, int need, int left) {
    const std::vector<int>& pool = planted_.size() >= 2 ? planted_ : all_frames();
    std::vector<std::pair<double, int>> by_gap;
    by_gap.reserve(pool.size());
    for (int b : pool) by_gap.push_back({std::sqrt(stance_distance(st_, from, b)) / typical_gap_, b});
    std::sort(by_gap.begin(), by_gap.end());
    std::vector<std::pair<double, int>> scored;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [gap, b] : by_gap) {
      if (4.0 * gap * gap > best + kNearEqual) break;
      const double c = cost(from, b, lead, need, left);
      if (!std::isfinite(c)) continue;
      scored.push_back({c, b});
      best = std::min(best, c);
    }
    if (scored.empty()) return {std::numeric_limits<double>::infinity(), std::max(0, runs_.first(from))};
    const int chosen = choose(scored);
    for (const auto& [c, f] : scored)
      if (f == chosen) return {c, f};
    return {best, chosen};
  }

  // The change of stance out of the current stretch (graph frame s at output frame t) within output
  // frames [lo, hi]: from each of its last kFromCandidates stance frames there, the best target;
  // the pair of least cost (the later one among equals). Without a stance frame in the window, at
  // `otherwise`.
  struct Change {
    int at = -1, from = 0, to = 0;
    double cost = 0.0;
  };
  // The change of stance out of the current stretch (graph frame s at output frame t) within output
  // frames [lo, hi]: from each of up to kFromCandidates of its stance frames there (spread over the
  // window), the best target; the pair of least cost. Without a stance frame in the window, at
  // `otherwise`, or none (at = -1) when `otherwise` is negative. A rest at output frame rest_at
  // needs `need` still frames from there.
  Change change(int s, int t, int lo, int hi, int otherwise, int rest_at, int need) {
    std::vector<int> stances;
    for (int at = hi; at >= std::max(lo, t + 1); --at) {
      const int f = s + (at - t);
      if (f < runs_.frame_count() && st_.planted[static_cast<std::size_t>(f)] && !in_rest(at)) stances.push_back(at);
    }
    std::vector<int> times;
    for (std::size_t k = 0; k < std::min(kFromCandidates, stances.size()); ++k)
      times.push_back(stances[k * stances.size() / std::min(kFromCandidates, stances.size())]);
    if (times.empty()) {
      if (otherwise < 0) return {};
      times.push_back(std::max(otherwise, t + 1));
    }
    Change best;
    best.cost = std::numeric_limits<double>::infinity();
    for (int at : times) {
      const int from = s + (at - t);
      const int lead = rest_at >= 0 ? std::max(0, rest_at - at) : 0;
      const auto [cost, to] = target(from, lead, need, total_ - at);
      if (best.at < 0 || cost < best.cost) best = {at, from, to, cost};
    }
    return best;
  }

  // Whether output frame `at` lies inside a rest (from its still part's start to its end): a change
  // there would move the legs the rest keeps still.
  bool in_rest(int at) const {
    for (const auto& [a, b] : windows_)
      if (at >= a && at < b) return true;
    return false;
  }

  // The share of `need` frames from graph frame f that are not still (0 when need is 0).
  double deficit(int f, int need) const {
    return need > 0 ? static_cast<double>(need - std::min(need, still_ahead_[static_cast<std::size_t>(f)])) / need
                    : 0.0;
  }

  int start_frame() {
    std::vector<std::pair<double, int>> scored;
    const int need = !windows_.empty() && windows_.front().first == 0 ? windows_.front().second : 0;
    const std::vector<int>& pool = planted_.empty() ? all_frames() : planted_;
    for (int b : pool) {
      // The longer the stretch can play, the fewer changes: a start that plays the whole output
      // through costs 0.
      double c = std::max(0.0, 1.0 - static_cast<double>(runs_.last(b) - b + 1) / std::max(1, total_));
      c += 0.5 * kStillWeight * deficit(b, need);
      if (withheld(b)) c += kWithheld;
      scored.push_back({c, b});
    }
    return choose(scored);
  }

  std::vector<int> all_frames() {
    if (all_.empty())
      for (int f = 0; f < runs_.frame_count(); ++f) all_.push_back(f);
    return all_;
  }

  const Stance& st_;
  const CaptureRuns& runs_;
  const int total_;
  const double fps_;
  const LowerBodyParams& params_;
  std::mt19937_64& rng_;
  std::vector<int> planted_, all_;
  std::vector<int> still_ahead_;
  std::vector<std::uint16_t> plays_;
  std::vector<std::pair<int, int>> windows_;
  double typical_gap_ = 1.0;
  std::vector<char> withheld_;
  int block_ = 1;
};

}  // namespace

LowerPlan plan_lower_body(const Stance& stance, const CaptureRuns& runs, const std::vector<Anchor>& rests,
                          int total_frames, double fps, const LowerBodyParams& params, std::mt19937_64& rng) {
  if (!stance.known) throw Error("lower body: the reference's stance is not known");
  if (static_cast<int>(stance.planted.size()) != runs.frame_count())
    throw Error("lower body: the stance does not cover the reference");
  for (const Anchor& a : rests)
    if (a.start < 0 || a.length < 1 || a.start + a.length > total_frames)
      throw Error("lower body: a rest lies outside the output");
  return LowerPlanner(stance, runs, rests, total_frames, fps, params, rng).run();
}

}  // namespace gmg
