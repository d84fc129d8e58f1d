// How open the reference's jaw is for the speech under it, as a ridge regression on the speech's
// face features around each frame (audio/face_features.h, 2 frames either side) and, with phones,
// the viseme spoken there (text/phones.h). Fitted on the reference in each reenactment and applied
// to the new speech, it gives the jaw the face track's target cost compares stretches with: unit
// selection guided by a predicted trajectory, as HMM-guided sample selection does for talking heads
// (Wang and Soong 2015). The prediction only ranks the reference's own stretches; it is never shown.
#pragma once

#include <vector>

#include "engine/face/reference_face.h"

namespace gmg {

// The viseme spoken at every frame of a grid of `frames` frames (Silence between phones), from
// phones in frame times ([start, end), ascending): a frame takes the phone its time falls in.
struct TimedViseme {
  double start = 0.0, end = 0.0;
  text::Viseme viseme = text::Viseme::Silence;
};
std::vector<text::Viseme> frame_visemes(const std::vector<TimedViseme>& phones, int frames);

struct JawModel {
  bool with_visemes = false;
  std::vector<double> weights;  // intercept, then features at lags -2..2, then one per viseme
};

// Fits on the reference's frames (with_visemes: only those of clips with phones; every frame
// otherwise; at most about 50000 of them, evenly spread). The reference must have a jaw.
JawModel fit_jaw_model(const ReferenceFace& r, bool with_visemes);

// The jaw the model predicts at each frame of speech given as standardised features (frames x
// r.dims, as ReferenceFace::z) and, for a model with visemes, the viseme of each frame.
std::vector<double> predict_jaw(const JawModel& m, const std::vector<float>& z, int dims,
                                const std::vector<text::Viseme>& visemes);

}  // namespace gmg
