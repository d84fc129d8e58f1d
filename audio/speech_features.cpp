#include "audio/speech_features.h"

#include <algorithm>
#include <cmath>

#include "audio/onset.h"
#include "engine/core/error.h"
#include "engine/core/math.h"

namespace gmg::audio {
double percentile_of(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  const std::size_t k =
      std::min(v.size() - 1, static_cast<std::size_t>(std::floor(p / 100.0 * static_cast<double>(v.size()))));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

SpeechFeatures speech_features(const EnergyTrack& energy, const std::vector<float>& envelope, double fps, int frames,
                               double smooth_s) {
  if (!(fps > 0.0) || frames < 0) throw Error("speech features: invalid frame grid");
  SpeechFeatures out;
  const std::size_t n = static_cast<std::size_t>(frames);
  out.values.assign(n * SpeechFeatures::kDims, 0.0f);
  if (n == 0) return out;

  const std::vector<float> db = energy_db_on_grid(energy, fps, frames);
  std::vector<double> loud(db.begin(), db.end());
  const double level = percentile_of(loud, 90.0);
  for (double& x : loud) x = std::clamp((x - level) / 10.0, -4.0, 1.0);

  const double env_rate = static_cast<double>(OnsetAnalysis::kSampleRate) / OnsetAnalysis::kHop;
  std::vector<double> onset(n, 0.0);
  std::vector<int> count(n, 0);
  for (std::size_t k = 0; k < envelope.size(); ++k) {
    const long f = std::lround(static_cast<double>(k) / env_rate * fps);
    if (f < 0 || f >= frames) continue;
    onset[static_cast<std::size_t>(f)] += std::log1p(std::max(0.0f, envelope[k]));
    ++count[static_cast<std::size_t>(f)];
  }
  for (std::size_t f = 0; f < n; ++f)
    if (count[f] > 0) onset[f] /= count[f];
  const double onset_level = percentile_of(onset, 90.0);
  for (double& x : onset) x = onset_level > 0.0 ? std::clamp(x / onset_level, 0.0, 3.0) : 0.0;

  const int half = static_cast<int>(std::lround(smooth_s * fps / 2.0));
  loud = moving_average(loud, half);
  onset = moving_average(onset, half);
  for (std::size_t f = 0; f < n; ++f) {
    out.values[f * SpeechFeatures::kDims] = static_cast<float>(loud[f]);
    out.values[f * SpeechFeatures::kDims + 1] = static_cast<float>(onset[f]);
  }
  return out;
}

}  // namespace gmg::audio
