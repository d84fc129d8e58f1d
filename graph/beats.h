// Kinematic beats of the reference (SPEC "Speech-driven search", beats on beats; ours): the end
// of a stroke is a local minimum of the upper body's activity (MotionGraph::activity). A path's
// stop node lands on the new speech's onset, so a path that stops on a beat puts the motion's beat
// on the speech's; the planner charges a path for stopping elsewhere (search/speech_match.h
// end_cost). The cost of stopping at every frame depends on the whole run around it, so the graph
// keeps it (graph/reference_facts.h).
#pragma once

#include <vector>

#include "engine/motion/capture_runs.h"
#include "engine/motion/samples.h"

namespace gmg {

// A frame is a beat when its activity is above kBeatMinActivity (0.3 of the speaker's typical
// motion) and below that of every frame within kBeatOrder (4) frames either side, all in its
// capture run.
constexpr int kBeatOrder = 4;
constexpr float kBeatMinActivity = 0.3f;
// The width of the end cost: 0.1 s (3 frames at 30 fps).
constexpr double kBeatSigmaS = 0.1;

// Per frame: 1 - exp(-d^2 / (2 (kBeatSigmaS fps)^2)), d the distance in frames to the nearest beat
// in its capture run (1 where the run has none). `activity` has one value per frame of `runs`.
std::vector<float> beat_end_costs(const Samples<float>& activity, const CaptureRuns& runs, double fps);

}  // namespace gmg
