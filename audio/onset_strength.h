// The onset analysis's spectral front end, after librosa 0.10.2: the audio at 22050 Hz, a
// centred STFT (2048 points, hop 512, periodic Hann window), its power through the mel bank
// (audio/mel_bank.h) in dB, and the onset strength envelope of the rises. Peak picking and
// backtracking on the envelope are in audio/onset.h.
#pragma once

#include <vector>

#include "audio/wav.h"

namespace gmg::audio {

// librosa.onset.onset_strength(y=y, sr=22050) with its defaults. Resamples to
// 22050 Hz internally (resample_poly) when audio.sample_rate differs.
// Empty audio gives an envelope of one frame (0). Throws gmg::Error when
// audio.sample_rate is not positive.
std::vector<float> onset_strength_envelope(const Audio& audio);

// The same, taking the audio: its samples are released when the envelope is done, not kept by the
// caller beside the analysis (an hour at 16 kHz is 230 MB). The audio is resampled to 22050 Hz a
// stretch at a time as the spectrogram reaches it, so the analysis never holds it twice.
std::vector<float> onset_strength_envelope(Audio&& audio);

// librosa.power_to_db(power, ref=1, amin=1e-10) without top_db, 10 log10(max(1e-10, power)), as
// the spectrogram computes it eight values at a time (exposed for tests): within a few units in the
// last place of 10 * std::log10; +inf stays +inf, NaN gives -100 as std::max(1e-10, NaN) does.
double power_to_db(double power);

}  // namespace gmg::audio
