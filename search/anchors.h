// Anchors: stretches of the output whose frames are decided before the beam search plans the rest
// around them (ours). A rest is a still stretch of the reference played where the new speech
// pauses, so the speaker rests as the speaker does; a pin is a stretch of the reference the user
// puts at a moment of the output. The subsequences are cut at every anchor's ends; the one before
// a pin ends at the pin's first frame (Termination::Frame), so the path walks into it; the one after
// any anchor starts from where it ends, as after any path.
#pragma once

#include <vector>

#include "search/segmentation.h"

namespace gmg {

struct Anchor {
  int start = 0;   // output frame
  int length = 0;  // output frames (>= 1)
  Fixed kind = Fixed::Rest;
  int source = -1;  // Pin: the graph frame played at `start` (then source + 1, ...)
  int lead = 0;     // Rest: frames before the still part, which starts at start + lead
};

// The rests of an output: for every pause of the new speech (`pause`, per output frame, 0..1: runs
// at or above 0.5 lasting rest_min_s or longer), still for `hold` frames from its start, or the
// whole pause when it is shorter: a speaker holds a rest about as long as the reference ever holds
// one, and moves again in a longer pause. Each rest starts up to `lead` frames before its pause
// (never before the output or the previous rest): the reference's own way into the rest plays
// there, and the transition into it has decayed when the pause begins. Empty when hold < 1.
std::vector<Anchor> rest_anchors(const std::vector<float>& pause, double fps, double rest_min_s, int hold, int lead);

// `subs` (covering [0, total)) cut at the anchors' ends (sorted by start, not overlapping, inside
// the output: gmg::Error otherwise): every anchor becomes one subsequence of its kind; the
// subsequence before a pin ends with Termination::Frame at its first frame. Planned pieces shorter
// than min_length join the planned piece before them (taking its end and termination), else the one
// after, never an anchor.
std::vector<Subsequence> place_anchors(const std::vector<Subsequence>& subs, const std::vector<Anchor>& anchors,
                                       int min_length);

}  // namespace gmg
