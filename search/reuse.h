// Reuse of the reference (SPEC "Reuse"): a reference frame played recently costs more, so the
// planner does not replay one attractive stretch while others lie unused.
//
// Each frame keeps a play count that decays with output time (half-life halflife frames); a
// candidate pays the mean of its frames' counts. A stretch just played costs about 1 per play; a
// stretch played a half-life ago half that; an overlapping stretch pays for the frames it shares.
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
  double frame_cost(int f, int time) const;

  // Mean frame_cost over a path's frames.
  double path_cost(const std::vector<int>& path, int time) const;

  // For every frame s of `frames`: the mean frame_cost of s, s + 1, ..., s + window - 1 (clamped
  // to the graph).
  void window_costs(int window, int time, const std::vector<int>& frames, std::vector<double>& out) const;

 private:
  std::vector<double> count_;  // at time last_[f]
  std::vector<int> last_;
  double decay_per_frame_;  // ln 2 / halflife
};

}  // namespace gmg
