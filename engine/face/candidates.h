// The reference stretches a unit of new speech may play, each with its target cost: how unlike the
// unit it sounds and is spoken (engine/face/params.h). A phone unit's stretches are the reference's
// phones of the same symbol (of the same viseme too while there are fewer than 4), a silence's the
// reference's silences; a window's every stretch of the reference as long as the window.
#pragma once

#include <vector>

#include "engine/face/reference_face.h"
#include "engine/face/units.h"

namespace gmg {

struct FaceCandidate {
  double start = 0.0, end = 0.0;  // reference frame times, warped onto the unit's
  int clip = 0;
  double cost = 0.0;  // target cost
};

// The new speech as the target costs read it.
struct FaceTarget {
  int frames = 0;
  std::vector<float> z;     // frames x reference dims: the face features over the reference's spread
  std::vector<double> jaw;  // the jaw predicted at each frame (engine/face/jaw_model.h); empty: none
};

// At most params.candidates per unit, cheapest first; never none while the reference has frames
// (a phone unit without a reference phone to play takes windows).
std::vector<std::vector<FaceCandidate>> face_candidates(const ReferenceFace& r, const std::vector<FaceUnit>& units,
                                                        const FaceTarget& target, const FaceParams& params);

}  // namespace gmg
