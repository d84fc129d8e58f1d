// The speech analysis a reenactment is planned from, written out so users can check the sync
// themselves: the onsets (time, motion frame, strength), the keywords (time, frame, word) and the
// per-frame features the speech-driven planner matches (loudness, onset activity, pause).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "engine/config/config.h"
#include "engine/pipeline/speech_analysis.h"

namespace gmg {

// Everything about one speech on a grid of `fps`: {audio, transcript, duration_s, fps, frames,
// onsets [{time_s, frame, strength}], keywords [{time_s, frame, keyword}], features {loudness,
// onset_activity, pause} (one value per frame; audio/speech_features.h, search/speech_match.h)}.
nlohmann::ordered_json speech_report_json(const SpeechFiles& files, double fps, const Config& config);

// The events as CSV, one per line: kind (onset or keyword), time_s, frame, strength (onsets),
// keyword (keywords), with a header row.
std::string speech_report_csv(const nlohmann::ordered_json& report);

}  // namespace gmg
