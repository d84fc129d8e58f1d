// Extra per-frame channels along an assembly: the face of an SMPL-X reference (its expression
// coefficients) played with the motion, so each output frame shows the face of the source time
// its body plays, and transitions blend the face like the body.
//
// The channels ride the motion's clock (engine/assemble/timeline.h) and are inertialized like a
// translation channel of engine/assemble/transitions.h: sampled linearly between source frames,
// and at every transition the value and velocity offset between where the output was heading
// and the new source is carried over and decays with the same critically damped spring. A
// channel is never anchored or foot-locked. Between transitions, once the offset has decayed,
// an output frame's channels are the source's at its source time.
#pragma once

#include <vector>

#include "engine/assemble/params.h"
#include "engine/assemble/timeline.h"

namespace gmg {

// `values`: source frames x dims, frame-major (dims >= 1; runs.frame_count() source frames).
// Returns the pieces' total length x dims, frame-major. halflife_frames > 0 (the motion's
// params.halflife_s * fps).
std::vector<double> assemble_channels_inertialized(const std::vector<double>& values, int dims, const CaptureRuns& runs,
                                                   const std::vector<PathPiece>& pieces, double halflife_frames);
// The same with `continues[f]`: source frame f is naturally followed by f + 1.
std::vector<double> assemble_channels_inertialized(const std::vector<double>& values, int dims,
                                                   const std::vector<char>& continues,
                                                   const std::vector<PathPiece>& pieces, double halflife_frames);

// The same channels for the paper's blending (BlendMode::Offset, Crossfade): each piece's
// channels resampled to its length (engine/assemble/resample.h) and the pieces joined by
// blend_concatenate with `params`, as the motion's translations are.
std::vector<double> assemble_channels_blended(const std::vector<double>& values, int dims,
                                              const std::vector<PathPiece>& pieces, const BlendParams& params);

}  // namespace gmg
