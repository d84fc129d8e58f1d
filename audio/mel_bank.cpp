#include "audio/mel_bank.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "audio/onset.h"

namespace gmg::audio {

namespace {

constexpr int kSr = OnsetAnalysis::kSampleRate;
constexpr int kNfft = OnsetAnalysis::kNfft;
constexpr int kMels = OnsetAnalysis::kMels;
constexpr int kBins = kNfft / 2 + 1;

constexpr double kFsp = 200.0 / 3.0;
constexpr double kMinLogHz = 1000.0;
constexpr double kMinLogMel = kMinLogHz / kFsp;  // 15

}  // namespace

double hz_to_mel(double hz) {
  static const double logstep = std::log(6.4) / 27.0;
  if (hz >= kMinLogHz) return kMinLogMel + std::log(hz / kMinLogHz) / logstep;
  return hz / kFsp;
}

double mel_to_hz(double mel) {
  static const double logstep = std::log(6.4) / 27.0;
  if (mel >= kMinLogMel) return kMinLogHz * std::exp(logstep * (mel - kMinLogMel));
  return kFsp * mel;
}

namespace {

// librosa.filters.mel(sr=22050, n_fft=2048, n_mels=128, fmin=0, fmax=11025,
// htk=False, norm='slaney'), stored sparsely (only the nonzero weights).
std::vector<MelBand> make_mel_bank() {
  const double fmax = kSr / 2.0;
  std::vector<double> mel_f(kMels + 2);
  const double min_mel = hz_to_mel(0.0), max_mel = hz_to_mel(fmax);
  // np.linspace(min_mel, max_mel, n_mels + 2), then back to Hz.
  const double step = (max_mel - min_mel) / (kMels + 1);
  for (int i = 0; i < kMels + 2; ++i) mel_f[static_cast<std::size_t>(i)] = mel_to_hz(min_mel + i * step);
  mel_f[kMels + 1] = mel_to_hz(max_mel);
  std::vector<MelBand> bank(kMels);
  for (int m = 0; m < kMels; ++m) {
    const double lo = mel_f[static_cast<std::size_t>(m)], mid = mel_f[static_cast<std::size_t>(m + 1)],
                 hi = mel_f[static_cast<std::size_t>(m + 2)];
    const double enorm = 2.0 / (hi - lo);  // Slaney: constant area per band
    MelBand& band = bank[static_cast<std::size_t>(m)];
    band.first = -1;
    for (int k = 0; k < kBins; ++k) {
      const double f = static_cast<double>(k) * kSr / kNfft;  // np.fft.rfftfreq
      const double lower = (f - lo) / (mid - lo);             // -ramps[i] / fdiff[i]
      const double upper = (hi - f) / (hi - mid);             // ramps[i+2] / fdiff[i+1]
      const double w = std::max(0.0, std::min(lower, upper));
      if (w > 0.0) {
        if (band.first < 0) band.first = k;
        // Triangles are contiguous: fill any gap (cannot happen) with zeros.
        band.w.resize(static_cast<std::size_t>(k - band.first), 0.0);
        band.w.push_back(w * enorm * 0.25);
      }
    }
    if (band.first < 0) band.first = 0;  // empty band (not at these settings)
  }
  return bank;
}

}  // namespace

const std::vector<MelBand>& mel_bank() {
  static const std::vector<MelBand> bank = make_mel_bank();
  return bank;
}

}  // namespace gmg::audio
