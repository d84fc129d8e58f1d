#include "audio/face_features.h"

#include <fftw3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <new>

#include "audio/fftw_planner.h"
#include "audio/speech_features.h"
#include "engine/core/error.h"
#include "engine/core/math.h"

namespace gmg::audio {
namespace {

constexpr int kNfft = 512;
constexpr int kBins = kNfft / 2 + 1;
constexpr double kWindowS = 0.032;
constexpr std::array<double, FaceAudio::kBands + 1> kBandEdgesHz = {0, 300, 700, 1200, 2000, 3500, 8000};

// One real FFT plan of kNfft points for the process (made under FFTW's planner lock).
fftwf_plan face_fft_plan() {
  const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  static fftwf_plan plan = [] {
    float* in = fftwf_alloc_real(kNfft);
    fftwf_complex* out = fftwf_alloc_complex(kBins);
    fftwf_plan p = in && out ? fftwf_plan_dft_r2c_1d(kNfft, in, out, FFTW_ESTIMATE) : nullptr;
    fftwf_free(in);
    fftwf_free(out);
    return p;
  }();
  if (!plan) throw Error("face features: FFTW could not plan a 512-point FFT");
  return plan;
}

struct Buffers {
  float* in = fftwf_alloc_real(kNfft);
  fftwf_complex* out = fftwf_alloc_complex(kBins);
  Buffers() {
    if (!in || !out) {
      fftwf_free(in);
      fftwf_free(out);
      throw std::bad_alloc();
    }
  }
  ~Buffers() {
    fftwf_free(in);
    fftwf_free(out);
  }
  Buffers(const Buffers&) = delete;
  Buffers& operator=(const Buffers&) = delete;
};

}  // namespace

FaceAudio face_audio(const Audio& audio) {
  if (audio.sample_rate <= 0) throw Error("face features: the audio has no sample rate");
  FaceAudio t;
  // Averaging `step` samples at a time brings any rate to 16-32 kHz: the bands end at 8 kHz.
  const int step = std::max(1, audio.sample_rate / 16000);
  const double rate = static_cast<double>(audio.sample_rate) / step;
  const long long n = static_cast<long long>(audio.samples.size()) / step;
  if (n == 0) return t;
  const int width = std::min(kNfft, static_cast<int>(std::lround(kWindowS * rate)));
  std::vector<float> window(static_cast<std::size_t>(width));
  for (int i = 0; i < width; ++i)
    window[static_cast<std::size_t>(i)] = static_cast<float>(0.5 - 0.5 * std::cos(2.0 * kPi * (i + 0.5) / width));
  std::array<int, FaceAudio::kBands + 1> edge{};
  for (std::size_t b = 0; b < edge.size(); ++b)
    edge[b] = std::min(kBins, static_cast<int>(std::lround(kBandEdgesHz[b] / rate * kNfft)));
  const auto sample = [&](long long i) {
    float sum = 0.0f;
    for (int k = 0; k < step; ++k) sum += audio.samples[static_cast<std::size_t>(i * step + k)];
    return sum / static_cast<float>(step);
  };
  const fftwf_plan plan = face_fft_plan();
  Buffers fft;
  const double seconds = static_cast<double>(n) / rate;
  const int frames = static_cast<int>(std::ceil(seconds * FaceAudio::kRateHz - 1e-9));
  t.band_db.reserve(static_cast<std::size_t>(frames) * FaceAudio::kBands);
  t.crossings.reserve(static_cast<std::size_t>(frames));
  std::vector<float> x(static_cast<std::size_t>(width));
  for (int k = 0; k < frames; ++k) {
    const long long first = std::llround(k / FaceAudio::kRateHz * rate) - width / 2;
    int cross = 0;
    for (int i = 0; i < width; ++i) {
      const long long j = first + i;
      x[static_cast<std::size_t>(i)] = j >= 0 && j < n ? sample(j) : 0.0f;
      if (i > 0 && (x[static_cast<std::size_t>(i)] >= 0.0f) != (x[static_cast<std::size_t>(i - 1)] >= 0.0f)) ++cross;
    }
    std::fill(fft.in, fft.in + kNfft, 0.0f);
    for (int i = 0; i < width; ++i) fft.in[i] = x[static_cast<std::size_t>(i)] * window[static_cast<std::size_t>(i)];
    fftwf_execute_dft_r2c(plan, fft.in, fft.out);
    for (int b = 0; b < FaceAudio::kBands; ++b) {
      double power = 1e-12;
      for (int i = edge[static_cast<std::size_t>(b)]; i < edge[static_cast<std::size_t>(b + 1)]; ++i)
        power +=
            static_cast<double>(fft.out[i][0]) * fft.out[i][0] + static_cast<double>(fft.out[i][1]) * fft.out[i][1];
      t.band_db.push_back(static_cast<float>(10.0 * std::log10(power)));
    }
    t.crossings.push_back(static_cast<float>(cross / (width / rate * 1000.0)));
  }
  return t;
}

FaceFeatures face_features(const FaceAudio& track, const EnergyTrack& energy, double fps, int frames) {
  if (!(fps > 0.0) || frames < 0) throw Error("face features: invalid frame grid");
  constexpr int D = FaceFeatures::kDims;
  FaceFeatures out;
  const auto n = static_cast<std::size_t>(frames);
  out.values.assign(n * D, 0.0f);
  if (n == 0) return out;
  const std::vector<float> db = energy_db_on_grid(energy, fps, frames);
  const double level = percentile_of(std::vector<double>(db.begin(), db.end()), 90.0);
  std::vector<double> raw(n * (D - 1), 0.0);  // voicing and band shape before normalising
  std::vector<float> loud(n);
  const int have = track.frames();
  for (std::size_t f = 0; f < n; ++f) {
    loud[f] = static_cast<float>(std::clamp((db[f] - level) / 10.0, -4.0, 1.0));
    out.values[f * D] = loud[f];
    if (have == 0) continue;
    const double t = static_cast<double>(f) / fps * FaceAudio::kRateHz;
    const int k = std::min(have - 1, static_cast<int>(std::floor(t)));
    const int k1 = std::min(have - 1, k + 1);
    const double a = std::clamp(t - k, 0.0, 1.0);
    double* r = &raw[f * (D - 1)];
    r[0] = (1.0 - a) * track.crossings[static_cast<std::size_t>(k)] + a * track.crossings[static_cast<std::size_t>(k1)];
    double total = 0.0;
    std::array<double, FaceAudio::kBands> power{};
    for (int b = 0; b < FaceAudio::kBands; ++b) {
      const double d0 = track.band_db[static_cast<std::size_t>(k) * FaceAudio::kBands + static_cast<std::size_t>(b)];
      const double d1 = track.band_db[static_cast<std::size_t>(k1) * FaceAudio::kBands + static_cast<std::size_t>(b)];
      power[static_cast<std::size_t>(b)] = std::pow(10.0, ((1.0 - a) * d0 + a * d1) / 10.0);
      total += power[static_cast<std::size_t>(b)];
    }
    for (int b = 0; b < FaceAudio::kBands; ++b)
      r[1 + b] = 10.0 * std::log10(power[static_cast<std::size_t>(b)] / total) / 10.0;
  }
  // Relative to the mean over the speaking frames (no pause at all), faded out in pauses.
  std::vector<double> mean(D - 1, 0.0);
  std::size_t speaking = 0;
  for (std::size_t f = 0; f < n; ++f) {
    if (pause_weight(loud[f]) > 0.0f) continue;
    ++speaking;
    for (int d = 0; d < D - 1; ++d) mean[static_cast<std::size_t>(d)] += raw[f * (D - 1) + static_cast<std::size_t>(d)];
  }
  for (double& m : mean) m = speaking > 0 ? m / static_cast<double>(speaking) : 0.0;
  for (std::size_t f = 0; f < n; ++f) {
    const double keep = 1.0 - pause_weight(loud[f]);
    for (int d = 0; d < D - 1; ++d)
      out.values[f * D + 1 + static_cast<std::size_t>(d)] = static_cast<float>(
          keep * (raw[f * (D - 1) + static_cast<std::size_t>(d)] - mean[static_cast<std::size_t>(d)]));
  }
  return out;
}

}  // namespace gmg::audio
