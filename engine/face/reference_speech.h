// The reference's face speech as a graph keeps it (graph/face_speech.h), made when the graph is
// built from what each clip's speech analysis gives (engine/pipeline/speech_analysis.h).
#pragma once

#include <vector>

#include "graph/motion_graph.h"
#include "text/phones.h"

namespace gmg {

// One reference clip's speech as the face track keeps it.
struct ClipFaceSpeech {
  std::vector<float> features;      // the clip's frames x audio::FaceFeatures::kDims; empty: none
  std::vector<text::Phone> phones;  // seconds from the clip's start; empty: no phones tier
};

// The graph's face speech from its clips' (one per graph clip, in order) and its motion: the
// features joined (none unless every clip has them), the phones put on the graph's frames (cut to
// their clip, those past its end dropped), and the jaw's angle at every frame when the skeleton
// has a jaw (engine/motion/body_parts.h jaw_joint). Not known (feature_dims 0) when the clips are
// not the graph's clips one for one. Throws gmg::Error naming the clip whose features do not cover
// its frames.
FaceSpeech face_speech_of(const MotionGraph& g, const std::vector<ClipFaceSpeech>& clips);

}  // namespace gmg
