// Speech-driven search (SPEC "Speech-driven search"; ours, beyond the paper): every candidate a
// planner weighs, a start node, a beam path, the natural continuation, also pays for how unlike
// the reference speech under it is to the test speech it will be played to. The capture's own
// speech-motion coupling (louder speech, larger strokes; pauses, rest) then carries into the
// output: what is played is chosen by what was being said when it was captured.
//
// The cost of a pair (test frame t, graph frame f) is the weighted squared distance of their
// speech features (audio/speech_features.h), loudness fully, onset activity half (it is noisier:
// a syllable more or less changes it), over the mean of that distance between random pairs of the
// two recordings (so 1 is the cost of a stretch unrelated to what is said). Where the test speech pauses (loudness 20
// dB or more below its speaking level, fully from 35 dB), a frame also pays rest_weight times how much the reference
// moves there (MotionGraph::activity): a speaker rests when silent, and stretches of the reference that look like
// pauses by their sound need not be still (BEAT2's speaker moves most between phrases). A path's cost is the mean over
// the test frames it fills, each reading the path frame its time warp puts there.
#pragma once

#include <vector>

#include "engine/motion/capture_runs.h"
#include "graph/motion_graph.h"

namespace gmg {

class SpeechMatch {
 public:
  // `test` holds test_frames x g.speech_dims features; empty (or a graph without speech features)
  // makes every cost 0. Throws gmg::Error when the sizes disagree.
  SpeechMatch(const MotionGraph& g, const std::vector<float>& test, int test_frames, double rest_weight = 0.0);

  bool active() const { return active_; }

  // Test frame t (clamped to the test) against graph frame f.
  double frame_cost(int t, int f) const;

  // The path played onto test frames [start, start + length): output frame i reads
  // path[round(i * (n - 1) / (length - 1))] (as engine/assemble/timeline.h plays it).
  double path_cost(const std::vector<int>& path, int start, int length) const;

  // What ending a path at graph frame f costs the rhythm: 1 - exp(-d^2 / (2 * 0.1 s^2)), d the time
  // from f to the nearest kinematic beat of the reference in its capture run (a local minimum of
  // its upper-body activity over +-4 frames, above 0.3 of its typical activity: the end of a
  // stroke; graph/beats.h). The stop node lands on the test's onset, so a path that ends on a beat
  // puts the motion's beat on the speech's (EMAGE-style beat consistency); 0 without activity.
  double end_cost(int f) const;

  // For every graph frame s of `frames`: the mean cost of test frames [start, start + window)
  // against s, s + 1, ... played on naturally (holding a run's last frame). How well the speech
  // after a start node fits, before any path from it is known.
  void window_costs(int start, int window, const std::vector<int>& frames, std::vector<double>& out) const;

 private:
  double feature_cost(int t, int f) const;  // unscaled

  const MotionGraph& g_;
  std::vector<float> test_;
  int test_frames_ = 0;
  bool active_ = false;
  double rest_weight_ = 0.0;
  double scale_ = 1.0;        // 1 / the mean feature cost of random pairs
  std::vector<float> pause_;  // per test frame: how much it is a pause, 0..1
  CaptureRuns runs_;          // the graph's capture runs
  // Per graph frame (end_cost): the graph's own (MotionGraph::beat_cost, read in place), or
  // computed here for a graph made without them.
  Samples<float> end_cost_;
};

}  // namespace gmg
