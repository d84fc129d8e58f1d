// What a face track needs of the reference's speech under every frame (engine/face): the phones
// spoken (from the transcripts' phones tiers), the speech's face features (audio/face_features.h)
// and how open the jaw is. Computed when the graph is built and kept in its file (format 12 on), so
// a reenactment reads neither the reference's audio nor every frame of its motion.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/motion/samples.h"

namespace gmg {

// One phone of the reference, in graph frames: it is spoken from frame time `start` to `end`
// (fractional: frame f is at f / fps s of the graph's clock, so start = clip's first frame + its
// start in seconds * fps), inside one clip.
struct ReferencePhone {
  double start = 0.0, end = 0.0;
  std::uint32_t symbol = 0;  // index into FaceSpeech::symbols
};

struct FaceSpeech {
  int feature_dims = 0;     // 0: not known (a graph of format 11 or older, or made by hand without it)
  Samples<float> features;  // frames x feature_dims (audio/face_features.h), read in place
  // The jaw's rotation angle at every frame (radians, the angle of the jaw joint's local rotation),
  // or empty when the skeleton has no jaw (engine/motion/body_parts.h jaw_joint).
  Samples<float> jaw;
  std::vector<std::string> symbols;    // the phone symbols (text/phones.h), each once
  std::vector<ReferencePhone> phones;  // ascending, not overlapping; none when no clip had a phones tier

  bool known() const { return feature_dims > 0; }
};

}  // namespace gmg
