// WAV reading and writing (resampling: audio/resample.h).
//
// The engine reads speech as mono float samples. read_wav accepts the WAV
// variants found in the field (PCM 8/16/24/32-bit, IEEE float 32/64,
// WAVE_FORMAT_EXTENSIBLE, any channel count, sample rates of 4 to 192 kHz) and rejects
// everything else with a gmg::Error naming the file, the byte offset and the
// problem.
#pragma once

#include <string>
#include <vector>

namespace gmg::audio {

// Mono audio.
struct Audio {
  // Samples per second; > 0 for anything read_wav returns.
  int sample_rate = 0;
  // One sample per tick, nominally in [-1, 1]: integer PCM is scaled by
  // 2^(bits-1) (so it lies in [-1, 1)); float WAV data is kept as stored (it
  // may exceed [-1, 1] slightly, as librosa keeps it), never NaN or inf.
  std::vector<float> samples;

  // Seconds: samples.size() / sample_rate (0 when sample_rate is 0).
  double duration() const;
};

// Reads a RIFF/WAVE file and mixes its channels down to mono (mean of the
// channels). Throws gmg::Error "path: byte N: problem" on anything it cannot
// read faithfully (see wav.cpp for the list), and the reader's "path: cannot
// open (reason)" (engine/core/files.h) when the file cannot be read at all.
Audio read_wav(const std::string& path);

// The same for a file's bytes already in memory; `name` labels errors. The sample rate must lie
// in engine/core/limits.h's kMinSampleRate..kMaxSampleRate and the audio last at most
// kMaxAudioSeconds ("x.wav: byte 24: sample rate 1 Hz is outside the 4000 to 192000 Hz gmg
// reads").
Audio parse_wav(const std::string& bytes, const std::string& name);

// As above, then resamples to target_rate with resample_poly (audio/resample.h)
// when the file's rate differs. target_rate must be > 0 (else gmg::Error naming
// the file).
Audio read_wav(const std::string& path, int target_rate);

// Writes mono 16-bit PCM (samples clipped to [-1, 1], scaled by 32768 and
// rounded, so anything read from a PCM16 file writes back bit-identical).
// Writes atomically (write_file_atomically: a temporary file beside `path`,
// then a rename), so a reader never sees half a file and a failure leaves
// none. Throws gmg::Error naming `path` when the file cannot be written or
// `a` has no rate.
void write_wav_pcm16(const std::string& path, const Audio& a);

}  // namespace gmg::audio
