// Reuse of the reference (SPEC "Reuse"): a reference frame played recently costs more, so the
// planner does not replay one attractive stretch while others lie unused.
//
// Each frame keeps a play count that decays with output time (half-life halflife frames); a
// frame costs the square of its count (a third play of a stretch costs four times a second) and a
// candidate pays its most played frame. A stretch just played costs about 1 per play,
// one played a half-life ago half that, and so does a stretch that shares only some frames with it:
// a short popular stretch (an onset-ended gesture) replayed inside ever different paths was what
// the mean over a path's frames let through (4-6 plays of its frames in a minute).
#pragma once

#include <vector>

namespace gmg {

class ReuseTracker {
 public:
  // frames: the graph's frame count; halflife in output frames (> 0).
  ReuseTracker(int frames, double halflife);

  // The frames of a committed path, played from output frame `time` on.
  void play(const std::vector<int>& path, int time);

  // Frame f's decayed play count at output frame `time`.
  double plays(int f, int time) const;

  // Its cost: plays squared.
  double frame_cost(int f, int time) const {
    const double p = plays(f, time);
    return p * p;
  }

  // The largest frame_cost over a path's frames.
  double path_cost(const std::vector<int>& path, int time) const;

  // For every frame s of `frames`: the largest frame_cost of s, s + 1, ..., s + window - 1
  // (clamped to the graph).
  void window_costs(int window, int time, const std::vector<int>& frames, std::vector<double>& out) const;

 private:
  std::vector<double> count_;  // at time last_[f]
  std::vector<int> last_;
  double decay_per_frame_;  // ln 2 / halflife
};

}  // namespace gmg
