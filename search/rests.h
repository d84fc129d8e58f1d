// Rest stretches of the reference (ours): where the upper body is still, for the planner to play
// where the new speech pauses (search/anchors.h rest anchors). Stillness is the graph's activity
// (MotionGraph::activity: the upper body's speed over its median), so a rest is what the speaker
// did between phrases, not a held frame.
#pragma once

#include <vector>

#include "engine/motion/capture_runs.h"
#include "graph/motion_graph.h"

namespace gmg {

// A frame is still when its activity is below the reference's kStillQuantile-th quantile.
constexpr double kStillQuantile = 0.10;

class RestFinder {
 public:
  // An empty finder (hold 0) for a graph without activity.
  explicit RestFinder(const MotionGraph& g);

  // The longest run of still frames inside one capture run: how long the speaker ever rests.
  int hold() const { return hold_; }

  // The mean activity of graph frames [f, f + length); infinity when they leave f's capture run.
  double stillness(int f, int length) const;

  // Up to `count` graph frames f whose stretch [f, f + length) is stillest, stillest first.
  std::vector<int> stillest(int length, int count) const;
  // The same among the stretches where the reference mostly pauses (pause_share at least a half).
  std::vector<int> stillest_pauses(int length, int count) const;

  // The share of graph frames [f, f + length) where the reference's own speech pauses
  // (audio/speech_features.h pause_weight of its loudness): a speaker rests when they pause, so a
  // rest is taken from their pauses before their still moments mid-sentence. 1 for a graph
  // without speech (nothing to prefer); 0 outside f's capture run.
  double pause_share(int f, int length) const;

 private:
  std::vector<int> stillest_where(int length, int count, bool in_pauses) const;

  CaptureRuns runs_;
  std::vector<double> prefix_;  // prefix sums of the activity
  std::vector<double> pause_;   // prefix sums of the reference speech's pause weight (empty: no speech)
  int hold_ = 0;
};

}  // namespace gmg
