// Whether a recording can be speech at all: what build, reenact and evaluate check before they
// take an audio file as a speaker's voice (SpeechFiles::allow_silence turns the refusal off).
//
// The thresholds, in a user's terms (README "Bad input and exit codes"):
//   - at least kMinSpeechSeconds (0.5 s): a shorter file holds at most a syllable or two;
//   - its loudest second at least kMinLoudestSecondDb (-60 dB full scale, an RMS of 1e-3): speech
//     recorded at any usable gain peaks 20 to 50 dB above that, while digital silence, a muted
//     microphone or a room's hiss stays below it;
//   - some onset (audio/onset.h) in audio longer than kOnsetlessSeconds (10 s): speech has several
//     a second; a long file without any is a steady tone, hum or noise.
// The loudness comes from the planner's own energy track (audio/speech_energy.h, 5 ms bins).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "audio/speech_energy.h"

namespace gmg::audio {

inline constexpr double kMinSpeechSeconds = 0.5;
inline constexpr double kMinLoudestSecondDb = -60.0;
inline constexpr double kOnsetlessSeconds = 10.0;

// 10 log10 of the highest mean square over any 1 s of the track (its 200 consecutive bins; the
// whole track when it is shorter); -infinity for digital silence or an empty track.
double loudest_second_db(const EnergyTrack& track);

// Why audio of `duration_s` with this energy track cannot be speech: "holds 0.01 s of audio, ..."
// or "is silent: ...", without the file's name; "" when it can. The cheap checks, before onsets.
std::string speech_level_problem(double duration_s, const EnergyTrack& track);

// Why audio of `duration_s` in which the onset detector found `onsets` onsets (with
// min_onset_strength) cannot be speech; "" when it can.
std::string speech_onset_problem(double duration_s, std::size_t onsets, double min_onset_strength);

// The error text refusing `path` for `problem` (one of the above): "path: problem", or, when
// read_audio's warnings hold a damage warning for it, that damage first, as the likely cause:
// "x.flac: damaged: the decoder reported ..., and what it decoded is silent: ...".
std::string speech_refusal(const std::string& path, const std::string& problem,
                           const std::vector<std::string>& read_warnings);

}  // namespace gmg::audio
