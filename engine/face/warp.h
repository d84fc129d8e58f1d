// The reference times the face track plays at each output frame: each unit's stretch warped
// linearly onto the unit's time (the new phone's length; kept on the stretch's own frames), and at a
// join between stretches that do not follow each other in the reference a linear cross-fade from
// one to the other, each read on into its own reference context, over crossfade_s either side of
// the join (at most half of either unit).
#pragma once

#include <vector>

#include "engine/face/candidates.h"
#include "engine/face/units.h"

namespace gmg {

// Output frame's face: the reference at time `a` (graph frames, fractional, inside one clip),
// blended with the reference at time `b` by weight w (0: a alone).
struct FaceSource {
  double a = 0.0, b = 0.0;
  double w = 0.0;
};

// One source per output frame [0, frames). units cover [0, frames) in order; chosen[i] is unit i's
// stretch (a reference time range in clip chosen[i].clip).
std::vector<FaceSource> face_sources(const ReferenceFace& r, const std::vector<FaceUnit>& units,
                                     const std::vector<FaceCandidate>& chosen, int frames, double crossfade_frames);

}  // namespace gmg
