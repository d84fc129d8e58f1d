// Speech from any audio file: WAV through the engine's own reader (audio/wav.h), every other
// format (FLAC, MP3, OGG/Vorbis, Opus, M4A/AAC, AIFF, ...) through aubio's source API, which
// decodes with FFmpeg (libavcodec) or libsndfile, whichever this aubio was built with.
#pragma once

#include <string>

#include "audio/wav.h"

namespace gmg::audio {

// True when `path` ends in .wav (ASCII case-insensitive): read_audio reads it with read_wav.
bool is_wav_path(const std::string& path);

// Reads mono audio at the file's own sample rate (the mean of its channels, as read_wav mixes).
// A .wav file is read_wav's (exact, strict); anything else is decoded by aubio: lossless formats
// (FLAC, ALAC, AIFF) give exactly the samples a WAV of the same data gives, lossy ones the
// decoder's. Throws gmg::Error naming the file: "x.flac: cannot open (No such file or directory)",
// "x.xyz: cannot decode as audio (aubio: ...)", a sample that is not finite.
Audio read_audio(const std::string& path);

}  // namespace gmg::audio
