// `gmg evaluate` over files: reads the motions, the speech, the report and the reference, runs
// evaluate_motions (engine/metrics/evaluate.h) and optionally draws the picture (plot.h).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "audio/wav.h"
#include "engine/metrics/evaluate.h"
#include "engine/metrics/face_metrics.h"
#include "engine/motion/motion.h"
#include "engine/motion/npz.h"

namespace gmg {

struct EvaluateInputs {
  std::string generated;                 // BVH or SMPL-X .npz (required)
  std::string truth;                     // BVH or .npz, same skeleton and frame count; "" = skip the metrics needing it
  std::string skeleton;                  // BVH skeleton template of the .npz motions (engine/motion/npz.h); "" = none
  std::string audio;                     // the speech (WAV or another audio format); "" = skip the sync metrics
  std::vector<std::string> other_audio;  // other speech: the mismatched-speech control
  std::string report;                    // reenactment report JSON; "" = skip failures, fallbacks and transitions
  std::string reference;                 // the reference capture: a BVH or a graph (.gmg); "" = none
  std::string transcript;                // the speech's TextGrid with phones (viseme contrast); "" = none
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

// What evaluate_files reads, in memory (the Python module's objects): the same evaluation and
// JSON. Each name labels errors and the JSON's "inputs"; an empty name means the input is absent.
struct EvaluateLoaded {
  Motion generated;
  std::string generated_name;
  Motion truth;
  std::string truth_name;
  audio::Audio audio;
  std::string audio_name;
  std::vector<audio::Audio> other_audio;
  std::vector<std::string> other_audio_names;  // one per other_audio
  std::vector<Motion> reference;               // the reference's clips
  std::string reference_name;
  // The face (engine/metrics/face_metrics.h): the generated motion's expressions, the reference's,
  // and the phones the viseme contrast reads (has_mouth: a transcript with phones was given).
  SmplxBody generated_body;
  SmplxBody reference_body;
  std::vector<MouthSpan> mouth;
  bool has_mouth = false;
  nlohmann::json report;  // a reenactment report
  std::string report_name;
  bool trim = false;
  std::string plot;
  std::vector<std::string> warnings;  // of reading the inputs (decoder damage), each naming its file
};

EvaluateResult evaluate_loaded(EvaluateLoaded in, const EvaluateOptions& options);

// Speech as evaluate_files reads it: decoder damage goes into `warnings`; audio that cannot be
// speech (audio/speech_check.h: shorter than 0.5 s or silent) is a gmg::Error naming the file
// unless allow_silence.
audio::Audio read_evaluated_speech(const std::string& path, bool allow_silence, std::vector<std::string>& warnings);

// The reference clips evaluate_files reads from `path`: a graph's clips (.gmg), else one motion;
// with out_body, the reference's SMPL-X body too (a graph's, or an .npz's).
std::vector<Motion> read_reference_clips(const std::string& path, const std::string& skeleton,
                                         SmplxBody* out_body = nullptr);

// The open vowels and bilabials of a transcript's phones tier (text/phones.h); none without one.
std::vector<MouthSpan> mouth_spans(const std::string& transcript);

// "face": the jaw-energy correlation (with the mismatched-speech control when other audio is
// given), the viseme contrast (with phones) and the share of frames whose expressions leave the
// reference's range (with a reference face); null when the motion has no jaw and no face.
nlohmann::ordered_json face_evaluation(const Motion& generated, const EvaluateLoaded& in);

}  // namespace gmg
