// Speech from any audio file: WAV through the engine's own reader (audio/wav.h), every other
// format (FLAC, MP3, OGG/Vorbis, Opus, M4A/AAC, AIFF, ...) through aubio's source API, which
// decodes with FFmpeg (libavcodec) or libsndfile, whichever this aubio was built with.
#pragma once

#include <string>
#include <vector>

#include "audio/wav.h"

namespace gmg::audio {

// True when `path` ends in .wav (ASCII case-insensitive).
bool is_wav_path(const std::string& path);

// What a file's first bytes say it is: "a WAV file", "an MP3 file", "a FLAC file", ... for the
// audio formats, "a BVH motion file", "a gmg graph file", "a ZIP archive (.npz)", "JSON text",
// "text", "an empty file" for what is not audio; "" when the bytes say nothing. `audio` tells
// which of the two it is.
struct ContentKind {
  std::string name;
  bool audio = false;
};
ContentKind sniff_content(const std::string& head);

// Reads mono audio at the file's own sample rate (the mean of its channels, as read_wav mixes).
// The file's content chooses the reader, not its name: a RIFF/WAVE file is read_wav's (exact,
// strict), another audio format is decoded by aubio (lossless formats give exactly the samples a
// WAV of the same data gives, lossy ones the decoder's). Throws gmg::Error naming the file and
// leading with the cause: "x.flac: cannot open (No such file or directory)", "x.wav: is not
// audio: it is a BVH motion file", "x.xyz: cannot decode as audio (aubio: ...)", a sample that is
// not finite.
//
// What does not stop the read is added to *out_warnings (when given), each naming the file: an
// audio file whose name says another format ("x.wav: is an MP3 file, not a WAV; decoded as
// such"), and damage ("x.mp3: damaged: the decoder reported 'Header missing' and 12 more
// error(s), and decoded 5.0 s of the 6.1 s the file declares (a cut or corrupted file?); the
// audio may be incomplete or have gaps"): the decoder's errors, or a decode more than 0.25 s (and
// 1%) shorter than the file's header declares. A damage warning starts "<path>: damaged: ". The
// decoder's own lines never reach the terminal.
Audio read_audio(const std::string& path, std::vector<std::string>* out_warnings = nullptr);

// "damaged: ", after "<path>: " in read_audio's damage warning.
inline constexpr const char* kDamagedPrefix = "damaged: ";

}  // namespace gmg::audio
