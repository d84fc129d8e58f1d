// Audio files by format: WAV through read_wav, the rest through aubio_source.
//
// aubio (and the FFmpeg libraries it decodes with, some sixty shared libraries) is loaded with
// dlopen the first time a file that is not WAV is read, not when gmg starts: most commands never
// decode anything but WAV, and loading them cost every command tens of milliseconds.
#include "audio/audio_file.h"
#include "engine/core/files.h"

#include <aubio/aubio.h>
#include <dlfcn.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <type_traits>

#include "engine/core/error.h"
#include "engine/core/limits.h"
#include "engine/core/strings.h"

namespace gmg::audio {
namespace {

// The aubio functions this file calls, from the library loaded on first use.
struct Aubio {
  decltype(&aubio_log_set_level_function) log_set_level_function = nullptr;
  decltype(&new_aubio_source) new_source = nullptr;
  decltype(&aubio_source_get_samplerate) source_get_samplerate = nullptr;
  decltype(&aubio_source_get_channels) source_get_channels = nullptr;
  decltype(&aubio_source_do_multi) source_do_multi = nullptr;
  decltype(&del_aubio_source) del_source = nullptr;
  decltype(&new_fmat) new_matrix = nullptr;
  decltype(&del_fmat) del_matrix = nullptr;
  std::string error;  // why it could not be loaded; empty when it was
};

// aubio prints its errors to stderr. They are kept per thread instead, so the error thrown names
// aubio's reason once, on one line, and concurrent reads (gmg batch) do not mix messages.
thread_local std::string aubio_message;

void keep_aubio_message(sint_t /*level*/, const char_t* message, void* /*data*/) {
  aubio_message = std::string(trim(message ? message : ""));
}

// FFmpeg, under aubio, prints warnings on stderr for ordinary files ("Could not update timestamps
// for skipped samples" for every MP3 with an encoder delay). Only its errors are worth a line.
// The library is aubio's dependency, not ours, so its log level is set through the symbol when
// this aubio has it (AV_LOG_ERROR = 16 in libavutil/log.h).
void quiet_ffmpeg_warnings(void* library) {
  using SetLevel = void (*)(int);
  if (void* f = dlsym(library, "av_log_set_level")) reinterpret_cast<SetLevel>(f)(16);
}

Aubio load_aubio() {
  Aubio a;
  void* lib = nullptr;
  for (const char* name : {GMG_AUBIO_SONAME, "libaubio.so.5", "libaubio.so"})
    if ((lib = dlopen(name, RTLD_NOW | RTLD_LOCAL)) != nullptr) break;
  if (!lib) {
    const char* why = dlerror();
    a.error = std::string("the aubio library could not be loaded: ") + (why ? why : GMG_AUBIO_SONAME);
    return a;
  }
  bool complete = true;
  const auto take = [&](auto& f, const char* symbol) {
    f = reinterpret_cast<std::remove_reference_t<decltype(f)>>(dlsym(lib, symbol));
    complete = complete && f != nullptr;
  };
  take(a.log_set_level_function, "aubio_log_set_level_function");
  take(a.new_source, "new_aubio_source");
  take(a.source_get_samplerate, "aubio_source_get_samplerate");
  take(a.source_get_channels, "aubio_source_get_channels");
  take(a.source_do_multi, "aubio_source_do_multi");
  take(a.del_source, "del_aubio_source");
  take(a.new_matrix, "new_fmat");
  take(a.del_matrix, "del_fmat");
  if (!complete) {
    a.error = "the aubio library lacks a function gmg needs";
    return a;
  }
  a.log_set_level_function(AUBIO_LOG_ERR, keep_aubio_message, nullptr);
  a.log_set_level_function(AUBIO_LOG_WRN, keep_aubio_message, nullptr);
  quiet_ffmpeg_warnings(lib);
  return a;  // the library stays loaded for the process
}

// Loaded once, by the first reader (under the static's lock).
const Aubio& aubio() {
  static const Aubio a = load_aubio();
  return a;
}

// The engine's wording for a file that cannot be read at all (as engine/core/files.h words it).
void check_readable(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path + ": is a folder, not a file");
  check_input_file(path);  // a FIFO or a device must not be opened (the open could block)
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
}

struct Source {
  const Aubio& lib;
  aubio_source_t* source = nullptr;
  fmat_t* buffer = nullptr;
  ~Source() {
    if (buffer) lib.del_matrix(buffer);
    if (source) lib.del_source(source);
  }
};

constexpr uint_t kHop = 4096;

}  // namespace

bool is_wav_path(const std::string& path) { return ends_with_ci(path, ".wav"); }

Audio read_audio(const std::string& path) {
  if (is_wav_path(path)) return read_wav(path);
  check_readable(path);
  const Aubio& lib = aubio();
  if (!lib.error.empty()) throw Error(path + ": cannot decode as audio (" + lib.error + ")");
  aubio_message.clear();
  Source s{lib};
  s.source = lib.new_source(path.c_str(), 0, kHop);  // 0: the file's own sample rate
  if (!s.source)
    throw Error(path + ": cannot decode as audio" + (aubio_message.empty() ? "" : " (aubio: " + aubio_message + ")"));
  const uint_t rate = lib.source_get_samplerate(s.source);
  const uint_t channels = lib.source_get_channels(s.source);
  if (rate < static_cast<uint_t>(limits::kMinSampleRate) || rate > static_cast<uint_t>(limits::kMaxSampleRate) ||
      channels == 0 || channels > 64)
    throw Error(path + ": the decoder reports " + std::to_string(rate) + " Hz and " + std::to_string(channels) +
                " channels (gmg reads " + std::to_string(limits::kMinSampleRate) + " to " +
                std::to_string(limits::kMaxSampleRate) + " Hz, 1 to 64 channels)");
  // A stream that decodes forever (or for days) is refused once past the longest audio gmg reads,
  // so time and memory stay bounded.
  const auto max_samples = static_cast<std::size_t>(limits::kMaxAudioSeconds * rate);
  s.buffer = lib.new_matrix(channels, kHop);
  Audio a;
  a.sample_rate = static_cast<int>(rate);
  const double inv_channels = 1.0 / channels;
  uint_t read = kHop;
  while (read == kHop) {
    read = 0;
    lib.source_do_multi(s.source, s.buffer, &read);
    for (uint_t i = 0; i < read; ++i) {
      double sum = 0.0;
      for (uint_t c = 0; c < channels; ++c) sum += s.buffer->data[c][i];
      if (!std::isfinite(sum))
        throw Error(path + ": sample " + std::to_string(a.samples.size()) + " is not finite after decoding");
      a.samples.push_back(static_cast<float>(sum * inv_channels));
    }
    if (a.samples.size() > max_samples)
      throw Error(path + ": the audio lasts longer than the " + format_number(limits::kMaxAudioSeconds / 3600) +
                  " hours gmg reads");
  }
  if (a.samples.empty()) throw Error(path + ": holds no audio samples");
  return a;
}

}  // namespace gmg::audio
