#include "audio/speech_check.h"

#include "audio/audio_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/core/strings.h"

namespace gmg::audio {
namespace {

// "0.01 s", "62.0 s": the precision a user reads durations with.
std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, s < 1.0 ? "%.2g s" : "%.1f s", s);
  return text;
}

const char* const kAllow = "; --allow-silence uses it anyway";

}  // namespace

double loudest_second_db(const EnergyTrack& track) {
  const std::vector<float>& e = track.mean_square;
  if (e.empty()) return -std::numeric_limits<double>::infinity();
  const std::size_t window = std::min(e.size(), static_cast<std::size_t>(EnergyTrack::kRateHz));
  double sum = 0.0;
  for (std::size_t i = 0; i < window; ++i) sum += e[i];
  double best = sum;
  for (std::size_t i = window; i < e.size(); ++i) {
    sum += static_cast<double>(e[i]) - e[i - window];
    best = std::max(best, sum);
  }
  best /= static_cast<double>(window);
  // The running sum may drift a hair below 0 on digital silence.
  return best > 0.0 ? 10.0 * std::log10(best) : -std::numeric_limits<double>::infinity();
}

std::string speech_level_problem(double duration_s, const EnergyTrack& track) {
  if (duration_s < kMinSpeechSeconds)
    return "holds " + seconds(duration_s) + " of audio, too short to be speech (gmg needs at least " +
           format_number(kMinSpeechSeconds) + " s" + kAllow + ")";
  const double db = loudest_second_db(track);
  if (!(db >= kMinLoudestSecondDb)) {
    char level[64];
    // One decimal: -60.4 must not read as the -60 it falls short of.
    std::snprintf(level, sizeof level, "its loudest second is at %.1f dB full scale", db);
    return std::string("is silent: ") + (std::isfinite(db) ? level : "every sample is zero") + ", and speech needs " +
           format_number(kMinLoudestSecondDb) + " dB or more" + kAllow;
  }
  return "";
}

std::string speech_onset_problem(double duration_s, std::size_t onsets, double min_onset_strength) {
  if (onsets > 0 || duration_s <= kOnsetlessSeconds) return "";
  return "has no onset in " + seconds(duration_s) +
         " of audio: a steady sound or noise, not speech (no syllable starts with onset strength " +
         format_number(min_onset_strength) + " or more, the min_onset_strength key" + kAllow + ")";
}

std::string speech_refusal(const std::string& path, const std::string& problem,
                           const std::vector<std::string>& read_warnings) {
  const std::string damaged = path + ": " + kDamagedPrefix;
  for (const std::string& w : read_warnings) {
    if (w.rfind(damaged, 0) != 0) continue;
    return w.substr(0, w.find(" (a cut or corrupted file?)")) + ", and what it decoded " + problem;
  }
  return path + ": " + problem;
}

}  // namespace gmg::audio
