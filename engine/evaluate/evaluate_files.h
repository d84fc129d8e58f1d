// `gmg evaluate` over files: reads the motions, the speech, the report and the reference, runs
// evaluate_motions (engine/metrics/evaluate.h) and optionally draws the picture (plot.h).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/metrics/evaluate.h"

namespace gmg {

struct EvaluateInputs {
  std::string generated;                 // BVH or SMPL-X .npz (required)
  std::string truth;                     // BVH or .npz, same skeleton and frame count; "" = skip the metrics needing it
  std::string skeleton;                  // BVH skeleton template of the .npz motions (engine/motion/npz.h); "" = none
  std::string audio;                     // the speech (WAV or another audio format); "" = skip the sync metrics
  std::vector<std::string> other_audio;  // other speech: the mismatched-speech control
  std::string report;                    // reenactment report JSON; "" = skip failures, fallbacks and transitions
  std::string reference;                 // the reference capture: a BVH or a graph (.gmg); "" = none
  bool trim = false;  // cut the longer of generated and truth to the shorter (a warning says by how much)
  std::string plot;   // write a picture (.png or .svg); "" = none
  // Take speech that cannot be speech as it is (audio/speech_check.h: shorter than 0.5 s or
  // silent); false: an error naming the file.
  bool allow_silence = false;
};

// Speech and motion durations further apart than this get a warning naming both (the sync
// metrics compare them from their starts).
inline constexpr double kMaxEvaluateDurationMismatchS = 1.0;

struct EvaluateResult {
  nlohmann::ordered_json json;
  std::vector<std::string> warnings;  // for standard error, each naming its file: what --trim cut, decoder
                                      // damage, speech and motion of different lengths
};

EvaluateResult evaluate_files(const EvaluateInputs& in, const EvaluateOptions& options);

}  // namespace gmg
