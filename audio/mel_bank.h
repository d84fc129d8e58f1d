// The mel filter bank of the onset analysis (audio/onset_strength.h), as librosa 0.10.2 makes it:
// librosa.filters.mel(sr=22050, n_fft=2048, n_mels=128, fmin=0, fmax=11025, htk=False,
// norm='slaney') on librosa's Slaney mel scale.
#pragma once

#include <vector>

namespace gmg::audio {

// librosa's Slaney mel scale (htk=False): linear below 1 kHz, log above.
double hz_to_mel(double hz);
double mel_to_hz(double mel);

// One triangular mel filter: weights for FFT bins first .. first + w.size() - 1, each a quarter
// of librosa's (the spectrogram multiplies them by four times the power, RealFft::power4).
struct MelBand {
  int first = 0;
  std::vector<double> w;
};

// The bank, 128 bands over the 1025 bins of a 2048-point FFT at 22050 Hz, stored sparsely (only
// the nonzero weights); made once per process.
const std::vector<MelBand>& mel_bank();

}  // namespace gmg::audio
