#include "engine/assemble/timeline.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace gmg {
namespace {

// Inside one continuous run, pieces meet with a kink: each piece plays at its own warp rate, and
// the step across the boundary is one whole source frame whatever the rates (the stop node is
// the next piece's first frame). The source time through the pieces' first frames is made one
// C1 curve instead: monotone cubic Hermite interpolation through those knots (Fritsch-Butland
// slopes), so the playback speed changes gradually and every key frame still lands where the plan
// put it. A run with a held frame (rate 0) is left as it is.
void smooth_run(std::vector<SourceClock>& clock, const std::vector<int>& knots) {
  const std::size_t n = knots.size();
  if (n < 3) return;
  std::vector<double> m(n - 1), d(n);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double h = knots[k + 1] - knots[k];
    m[k] = (clock[static_cast<std::size_t>(knots[k + 1])].time - clock[static_cast<std::size_t>(knots[k])].time) / h;
    if (!(m[k] > 0.0)) return;
  }
  d[0] = m[0];
  d[n - 1] = m[n - 2];
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double h0 = knots[k] - knots[k - 1], h1 = knots[k + 1] - knots[k];
    const double w1 = 2.0 * h1 + h0, w2 = h1 + 2.0 * h0;
    d[k] = (w1 + w2) / (w1 / m[k - 1] + w2 / m[k]);
  }
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const int a = knots[k], b = knots[k + 1];
    const double h = b - a, t0 = clock[static_cast<std::size_t>(a)].time, t1 = clock[static_cast<std::size_t>(b)].time;
    for (int i = a + 1; i < b; ++i) {
      const double s = (i - a) / h, s2 = s * s, s3 = s2 * s;
      SourceClock& c = clock[static_cast<std::size_t>(i)];
      c.time = (2 * s3 - 3 * s2 + 1) * t0 + (s3 - 2 * s2 + s) * h * d[k] + (-2 * s3 + 3 * s2) * t1 +
               (s3 - s2) * h * d[k + 1];
      c.rate = (6 * s2 - 6 * s) / h * t0 + (3 * s2 - 4 * s + 1) * d[k] + (-6 * s2 + 6 * s) / h * t1 +
               (3 * s2 - 2 * s) * d[k + 1];
    }
    clock[static_cast<std::size_t>(a)].rate = d[k];
  }
  clock[static_cast<std::size_t>(knots.back())].rate = d[n - 1];
}

// The source frame of `beats` nearest t within max_shift, or -1.
int nearest_beat(const BeatAlignment& align, double t) {
  const auto b = std::lower_bound(align.beats.begin(), align.beats.end(), static_cast<int>(std::floor(t)));
  int beat = -1;
  double best = align.max_shift + 0.5;
  for (auto it : {b, b == align.beats.begin() ? b : b - 1})
    if (it != align.beats.end() && std::abs(*it - t) < best) {
      best = std::abs(*it - t);
      beat = *it;
    }
  return beat;
}

// Whether the speeds from knot (kp, tp) to (o, t) and on to (kn, tn) stay within max_rate of `rate`.
bool within_rate(const BeatAlignment& align, int kp, double tp, int o, double t, int kn, double tn, double rate) {
  const double in = (t - tp) / (o - kp) / rate, out = (tn - t) / (kn - o) / rate;
  return in >= 1.0 / align.max_rate && in <= align.max_rate && out >= 1.0 / align.max_rate && out <= align.max_rate;
}

// Beats onto the onsets inside one run (BeatAlignment): an onset on an inner knot (a piece's first
// frame, which the plan put on a key frame of the new speech) moves that knot's source time to the
// nearest beat; an onset between knots becomes a knot there. `knots` (sorted, the run's own, its
// ends first and last) gains the new ones; their times are set in `clock`.
struct BeatMove {
  int frame = 0;          // the knot
  double time = 0.0;      // its source time, moved onto the beat
  bool inserted = false;  // a knot added at an onset, not a piece's first frame
};

std::vector<BeatMove> add_beat_knots(std::vector<SourceClock>& clock, std::vector<int>& knots,
                                     const BeatAlignment& align) {
  std::vector<BeatMove> moves;
  const int first = knots.front(), last = knots.back();
  for (auto o_it = std::lower_bound(align.onsets.begin(), align.onsets.end(), first + 1);
       o_it != align.onsets.end() && *o_it < last; ++o_it) {
    const int o = *o_it;
    auto at = std::lower_bound(knots.begin(), knots.end(), o);
    const bool on_knot = *at == o;
    const int kp = *(at - 1), kn = on_knot ? *(at + 1) : *at;
    if (!on_knot && (o - kp < 3 || kn - o < 3)) continue;  // a key frame is next to it already
    SourceClock& c = clock[static_cast<std::size_t>(o)];
    if (!(c.rate > 0.0)) continue;
    const int beat = nearest_beat(align, c.time);
    if (beat < 0 || beat == c.time) continue;
    if (!within_rate(align, kp, clock[static_cast<std::size_t>(kp)].time, o, beat, kn,
                     clock[static_cast<std::size_t>(kn)].time, c.rate))
      continue;
    c.time = beat;
    if (!on_knot) knots.insert(at, o);
    moves.push_back({o, static_cast<double>(beat), !on_knot});
  }
  return moves;
}

// The run's clock smoothed through its knots and the beat knots, keeping the speed within
// max_rate of the speed without them at every frame, not only on the secants the knots were
// checked on: the C1 curve through a bent knot overshoots its secants (onto a beat 4 frames
// later over 13 frames, secant 1.31, the curve reached 1.37). The move nearest the worst frame is
// undone until none is left over.
void align_beats(std::vector<SourceClock>& clock, const std::vector<int>& knots, const BeatAlignment& align) {
  const int first = knots.front(), last = knots.back();
  const std::vector<SourceClock> before(clock.begin() + first, clock.begin() + last + 1);
  auto restore = [&] { std::copy(before.begin(), before.end(), clock.begin() + first); };
  smooth_run(clock, knots);
  std::vector<double> base(before.size());
  for (std::size_t i = 0; i < base.size(); ++i) base[i] = clock[static_cast<std::size_t>(first) + i].rate;
  restore();
  std::vector<int> with = knots;
  std::vector<BeatMove> moves = add_beat_knots(clock, with, align);
  while (true) {
    smooth_run(clock, with);
    int worst = -1;
    double worst_excess = 1.0 + 1e-9;
    for (int i = first; i <= last; ++i) {
      const double b = base[static_cast<std::size_t>(i - first)], r = clock[static_cast<std::size_t>(i)].rate;
      if (!(b > 0.0)) continue;
      const double excess = r > 0.0 ? std::max(r / b, b / r) / align.max_rate : 1e9;
      if (excess > worst_excess) {
        worst_excess = excess;
        worst = i;
      }
    }
    if (worst < 0 || moves.empty()) return;
    std::size_t undo = 0;
    for (std::size_t k = 1; k < moves.size(); ++k)
      if (std::abs(moves[k].frame - worst) < std::abs(moves[undo].frame - worst)) undo = k;
    if (moves[undo].inserted) with.erase(std::find(with.begin(), with.end(), moves[undo].frame));
    moves.erase(moves.begin() + static_cast<std::ptrdiff_t>(undo));
    restore();
    for (const BeatMove& m : moves) clock[static_cast<std::size_t>(m.frame)].time = m.time;
  }
}

// Every run that spans several pieces: its knots are the pieces' first frames and its last frame.
void smooth_rates(std::vector<SourceClock>& clock, const std::vector<int>& piece_starts, const BeatAlignment* beats) {
  std::vector<char> starts(clock.size(), 0);
  for (int i : piece_starts) starts[static_cast<std::size_t>(i)] = 1;
  for (std::size_t first = 0; first < clock.size();) {
    std::size_t last = first;
    bool held = clock[first].rate <= 0.0;
    while (last + 1 < clock.size() && clock[last + 1].run == clock[first].run) {
      ++last;
      held = held || clock[last].rate <= 0.0;
    }
    std::vector<int> knots = {static_cast<int>(first)};
    for (std::size_t i = first + 1; i <= last; ++i)
      if (starts[i]) knots.push_back(static_cast<int>(i));
    if (knots.back() != static_cast<int>(last)) knots.push_back(static_cast<int>(last));
    if (!held && beats && knots.size() >= 2)
      align_beats(clock, knots, *beats);
    else if (!held)
      smooth_run(clock, knots);
    first = last + 1;
  }
}

}  // namespace

std::vector<SourceClock> source_timeline(const std::vector<PathPiece>& pieces, const std::vector<char>& continues) {
  return source_timeline(pieces, CaptureRuns(continues));
}

std::vector<SourceClock> source_timeline(const std::vector<PathPiece>& pieces, const CaptureRuns& runs,
                                         const BeatAlignment* beats) {
  const int frames = runs.frame_count();
  std::vector<SourceClock> out;
  int run = -1;
  int previous_frame = -2;  // last path frame of the previous piece
  std::vector<int> piece_starts;
  for (const PathPiece& piece : pieces) {
    piece_starts.push_back(static_cast<int>(out.size()));
    const std::vector<int>& p = piece.path;
    if (p.empty() || piece.length < 1) throw Error("source_timeline: empty path or length");
    for (int f : p)
      if (f < 0 || f >= frames) throw Error("source_timeline: path frame out of range");
    const int n = static_cast<int>(p.size());
    const double rate = piece.length > 1 ? static_cast<double>(n - 1) / (piece.length - 1) : 0.0;
    // run_first[k]: index in p of the first frame of the run holding p[k].
    std::vector<int> run_first(static_cast<std::size_t>(n));
    std::vector<int> run_id(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      const int before = k == 0 ? previous_frame : p[static_cast<std::size_t>(k - 1)];
      const bool natural = before >= 0 && p[static_cast<std::size_t>(k)] == before + 1 && runs.continues(before);
      if (!natural) ++run;
      run_first[static_cast<std::size_t>(k)] = natural && k > 0 ? run_first[static_cast<std::size_t>(k - 1)] : k;
      run_id[static_cast<std::size_t>(k)] = run;
    }
    for (int i = 0; i < piece.length; ++i) {
      const double x = std::min(static_cast<double>(n - 1), i * rate);
      const int a = std::min(n - 1, static_cast<int>(std::floor(x)));
      const int first = run_first[static_cast<std::size_t>(a)];
      SourceClock c;
      // Inside its run the path is consecutive frames, so source time is linear in x. Past the
      // run's last path frame (x between it and an unnatural jump) it reads on into the natural
      // successor, which exists unless that frame is a break.
      c.time = p[static_cast<std::size_t>(first)] + (x - first);
      const int base = static_cast<int>(std::floor(c.time));
      if (base >= frames || (c.time > base && !runs.continues(base))) c.time = base;
      c.rate = rate;
      c.run = run_id[static_cast<std::size_t>(a)];
      out.push_back(c);
    }
    previous_frame = p.back();
  }
  smooth_rates(out, piece_starts, beats);
  return out;
}

}  // namespace gmg
