// Assembly by source time: where each output frame is read from.
//
// A plan is a list of pieces, each a path of source frames stretched or squeezed onto its target
// length. Instead of resampling each piece on its own and joining the pieces, the output is
// mapped to a continuous source time: frame i of a piece reads its path at position
// x = i * (n - 1) / (L - 1), inside the run of consecutive source frames that holds floor(x), so
// a path that walks naturally plays as one stretch of capture at the piece's warp rate. Every
// place where the source does not continue naturally, a junction that did not continue or an
// unnatural edge inside a path, starts a new run: that is a transition (engine/assemble/transitions.h).
#pragma once

#include <vector>

#include "engine/motion/capture_runs.h"

namespace gmg {

// One piece of the plan: graph frames (>= 1) and the output frames they fill (>= 1).
struct PathPiece {
  std::vector<int> path;
  int length = 1;
};

struct SourceClock {
  double time = 0.0;  // source frame time (fractional: between floor(time) and the next frame)
  double rate = 1.0;  // source frames per output frame here (the piece's warp rate; 0 for a held frame)
  int run = 0;        // increases at every transition; equal runs are one continuous stretch
};

// Beats on beats inside a continuous stretch (ours): where the output plays on through an onset
// of the new speech, the source clock is bent so that the reference's nearest kinematic beat (the
// end of a stroke, graph/beats.h) lands on the onset, when one lies within max_shift frames and the
// playback speed stays within [1 / max_rate, max_rate] of the piece's own. The pieces' own key
// frames stay where the plan put them; the bend is as smooth as the rest of the clock (C1).
struct BeatAlignment {
  std::vector<int> onsets;  // output frames, ascending
  std::vector<int> beats;   // source frames, ascending
  int max_shift = 4;
  double max_rate = 1.33;
};

// One clock per output frame (the sum of the pieces' lengths), reading the source's capture runs.
// `beats` (optional) bends it onto the onsets as BeatAlignment says.
std::vector<SourceClock> source_timeline(const std::vector<PathPiece>& pieces, const CaptureRuns& runs,
                                         const BeatAlignment* beats = nullptr);
// The same with `continues[f]`: source frame f is naturally followed by f + 1 (not a break node).
std::vector<SourceClock> source_timeline(const std::vector<PathPiece>& pieces, const std::vector<char>& continues);

}  // namespace gmg
