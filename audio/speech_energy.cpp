#include "audio/speech_energy.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace gmg::audio {

EnergyTrack energy_track(const Audio& audio) {
  if (audio.sample_rate <= 0) throw Error("energy: the audio has no sample rate");
  EnergyTrack t;
  const double per_bin = audio.sample_rate / EnergyTrack::kRateHz;
  const std::size_t n = audio.samples.size();
  const std::size_t bins = static_cast<std::size_t>(std::ceil(static_cast<double>(n) / per_bin - 1e-9));
  t.mean_square.reserve(bins);
  for (std::size_t b = 0; b < bins; ++b) {
    const std::size_t first = static_cast<std::size_t>(std::llround(static_cast<double>(b) * per_bin));
    const std::size_t end = std::min(n, static_cast<std::size_t>(std::llround(static_cast<double>(b + 1) * per_bin)));
    double sum = 0.0;
    for (std::size_t i = first; i < end; ++i) sum += static_cast<double>(audio.samples[i]) * audio.samples[i];
    t.mean_square.push_back(end > first ? static_cast<float>(sum / static_cast<double>(end - first)) : 0.0f);
  }
  return t;
}

std::vector<float> energy_db_on_grid(const EnergyTrack& track, double fps, int frames) {
  std::vector<double> sum(static_cast<std::size_t>(std::max(0, frames)), 0.0);
  std::vector<int> count(sum.size(), 0);
  for (std::size_t b = 0; b < track.mean_square.size(); ++b) {
    const double centre_s = (static_cast<double>(b) + 0.5) / EnergyTrack::kRateHz;
    const long f = std::lround(centre_s * fps);
    if (f < 0 || f >= frames) continue;
    sum[static_cast<std::size_t>(f)] += track.mean_square[b];
    ++count[static_cast<std::size_t>(f)];
  }
  std::vector<float> db(sum.size(), kSilenceDb);
  const double floor = std::pow(10.0, kSilenceDb / 10.0);
  for (std::size_t f = 0; f < sum.size(); ++f)
    if (count[f] > 0) db[f] = static_cast<float>(10.0 * std::log10(std::max(floor, sum[f] / count[f])));
  return db;
}

}  // namespace gmg::audio
