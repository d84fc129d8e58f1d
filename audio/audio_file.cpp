// Audio files by content: WAV through read_wav, the rest through aubio_source.
//
// aubio (and the FFmpeg libraries it decodes with, some sixty shared libraries) is loaded with
// dlopen the first time a file that is not WAV is read, not when gmg starts: most commands never
// decode anything but WAV, and loading them cost every command tens of milliseconds.
#include "audio/audio_file.h"
#include "engine/core/files.h"

#include <aubio/aubio.h>
#include <dlfcn.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
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
  decltype(&aubio_source_get_duration) source_get_duration = nullptr;
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

// FFmpeg, under aubio, reports damage ("Header missing", "invalid sync code") through its log,
// which by default prints raw lines on stderr that name no file. Its errors are collected per
// thread instead and become one warning naming the file; its warnings ("Could not update
// timestamps for skipped samples" for every MP3 with an encoder delay) are dropped. The library
// is aubio's dependency, not ours, so its log is reached through the symbols when this aubio
// has them (libavutil/log.h: AV_LOG_ERROR = 16).
constexpr int kAvLogError = 16;
thread_local std::vector<std::string> decoder_errors;
thread_local std::string decoder_line;  // a message may come in pieces; a line ends with '\n'

extern "C" void keep_decoder_message(void* /*context*/, int level, const char* format, va_list args) {
  if (level > kAvLogError || format == nullptr) return;
  char text[512];
  std::vsnprintf(text, sizeof text, format, args);
  decoder_line += text;
  if (decoder_line.empty() || decoder_line.back() != '\n') return;
  const std::string line(trim(decoder_line));
  decoder_line.clear();
  if (!line.empty() && decoder_errors.size() < 1000) decoder_errors.push_back(line);
}

void route_decoder_log(void* library) {
  using SetLevel = void (*)(int);
  using Callback = void (*)(void*, int, const char*, va_list);
  using SetCallback = void (*)(Callback);
  if (void* f = dlsym(library, "av_log_set_level")) reinterpret_cast<SetLevel>(f)(kAvLogError);
  if (void* f = dlsym(library, "av_log_set_callback")) reinterpret_cast<SetCallback>(f)(keep_decoder_message);
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
  take(a.source_get_duration, "aubio_source_get_duration");
  take(a.del_source, "del_aubio_source");
  take(a.new_matrix, "new_fmat");
  take(a.del_matrix, "del_fmat");
  if (!complete) {
    a.error = "the aubio library lacks a function gmg needs";
    return a;
  }
  a.log_set_level_function(AUBIO_LOG_ERR, keep_aubio_message, nullptr);
  a.log_set_level_function(AUBIO_LOG_WRN, keep_aubio_message, nullptr);
  route_decoder_log(lib);  // dlsym on the library also searches the FFmpeg libraries it loaded
  return a;                // the library stays loaded for the process
}

// Loaded once, by the first reader (under the static's lock).
const Aubio& aubio() {
  static const Aubio a = load_aubio();
  return a;
}

// The first bytes of a file (refused as the engine's readers refuse what is not a regular file).
std::string file_head(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path + ": is a folder, not a file");
  check_input_file(path);  // a FIFO or a device must not be opened (the open could block)
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
  char head[64];
  in.read(head, sizeof head);
  return std::string(head, static_cast<std::size_t>(in.gcount()));
}

bool starts_with(const std::string& s, std::string_view prefix, std::size_t at = 0) {
  return s.size() >= at + prefix.size() && std::string_view(s).substr(at, prefix.size()) == prefix;
}

// Text: printable ASCII, white space and UTF-8 in the first bytes (a cut character at the end
// counts).
bool looks_like_text(const std::string& head) {
  std::size_t pos = 0;
  while (pos < head.size()) {
    const auto c = static_cast<unsigned char>(head[pos]);
    if (c >= 0x80) {
      const std::optional<Utf8Char> u = decode_utf8(head, pos);
      if (!u) return head.size() - pos < 4 && head.size() == 64;  // a character cut by the 64 bytes
      pos += u->length;
      continue;
    }
    if (c < 0x20 && !is_ascii_space(static_cast<char>(c))) return false;
    if (c == 0x7F) return false;
    ++pos;
  }
  return true;
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

// "2.6 s": decoded lengths as a user compares them.
std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", s);
  return text;
}

// A decode shorter than the file declares by more than this is damage: encoder delay and padding
// (an MP3's 1152-sample frames, the priming of AAC) make up less than 0.1 s.
constexpr double kShortfallSeconds = 0.25;

// One warning for what went wrong decoding one file: the decoder's error lines (they repeat, one
// per damaged frame) and a decode shorter than declared; "" when neither.
std::string damage_warning(const std::string& path, const std::vector<std::string>& lines, double decoded_s,
                           double declared_s) {
  std::string what;
  if (!lines.empty()) {
    std::string first = escape_nonprintable(lines.front());
    if (first.size() > 120) first = first.substr(0, 117) + "...";
    what = "the decoder reported '" + first + "'";
    if (lines.size() > 1) what += " and " + std::to_string(lines.size() - 1) + " more error(s)";
  }
  if (declared_s - decoded_s > std::max(kShortfallSeconds, 0.01 * declared_s))
    what += (what.empty() ? "" : ", and ") + std::string("decoded ") + seconds_text(decoded_s) + " of the " +
            seconds_text(declared_s) + " the file declares";
  if (what.empty()) return "";
  return path + ": " + kDamagedPrefix + what + " (a cut or corrupted file?); the audio may be incomplete or have gaps";
}

// `kind` is what the first bytes say (sniff_content; "" when nothing).
Audio decode_with_aubio(const std::string& path, const std::string& kind, std::vector<std::string>* out_warnings) {
  const Aubio& lib = aubio();
  if (!lib.error.empty())
    throw Error(path + ": cannot decode " + (kind.empty() ? std::string("as audio") : kind) + " (" + lib.error + ")");
  aubio_message.clear();
  decoder_errors.clear();
  decoder_line.clear();
  Source s{lib};
  s.source = lib.new_source(path.c_str(), 0, kHop);  // 0: the file's own sample rate
  if (!s.source) {
    // The decoder's own reason ("moov atom not found": a cut MP4) comes first: aubio tries its
    // other readers after it, and the last one's complaint (a WAV reader's "could not find RIFF
    // header") says nothing about a file that is no WAV.
    const bool wav_reader = aubio_message.find("RIFF") != std::string::npos;  // the last reader aubio tried
    const std::string why = !decoder_errors.empty()               ? "the decoder: " + decoder_errors.front()
                            : aubio_message.empty() || wav_reader ? std::string()
                                                                  : "aubio: " + aubio_message;
    throw Error(path + ": cannot decode " + (kind.empty() ? std::string("as audio") : kind) +
                (why.empty() ? "" : " (" + escape_nonprintable(why) + ")") +
                (kind.empty()
                     ? (why.empty() ? ": no audio format the decoder knows (WAV, FLAC, MP3, OGG, M4A, ...)" : "")
                     : "; the file may be cut short or damaged"));
  }
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
  if (a.samples.empty()) {
    const std::string why =
        decoder_errors.empty() ? "" : " (the decoder: " + escape_nonprintable(decoder_errors.front()) + ")";
    throw Error(path + ": holds no audio samples" + why);
  }
  const uint_t declared = lib.source_get_duration(s.source);  // 0: unknown
  const std::string damage =
      damage_warning(path, decoder_errors, a.duration(), declared > 0 ? static_cast<double>(declared) / rate : 0.0);
  if (!damage.empty() && out_warnings) out_warnings->push_back(damage);
  decoder_errors.clear();
  return a;
}

}  // namespace

bool is_wav_path(const std::string& path) { return ends_with_ci(path, ".wav"); }

ContentKind sniff_content(const std::string& h) {
  if (h.empty()) return {"an empty file", false};
  if (starts_with(h, "RIFF") || starts_with(h, "RIFX") || starts_with(h, "RF64") || starts_with(h, "BW64"))
    return {starts_with(h, "WAVE", 8) ? "a WAV file" : "a RIFF file", starts_with(h, "WAVE", 8)};
  if (starts_with(h, "fLaC")) return {"a FLAC file", true};
  if (starts_with(h, "ID3")) return {"an MP3 file", true};
  if (starts_with(h, "OggS")) return {"an Ogg file", true};
  if (starts_with(h, "ftyp", 4)) return {"an MP4/M4A file", true};
  if (starts_with(h, "FORM") && (starts_with(h, "AIFF", 8) || starts_with(h, "AIFC", 8))) return {"an AIFF file", true};
  if (starts_with(h, "caff")) return {"a CAF file", true};
  if (starts_with(h, "\x1A\x45\xDF\xA3")) return {"a Matroska/WebM file", true};
  if (starts_with(h, "\x30\x26\xB2\x75")) return {"a WMA file", true};
  if (starts_with(h, "#!AMR")) return {"an AMR file", true};
  if (starts_with(h, "wvpk")) return {"a WavPack file", true};
  if (starts_with(h, "MAC ")) return {"an APE file", true};
  if (h.size() >= 2 && static_cast<unsigned char>(h[0]) == 0xFF && (static_cast<unsigned char>(h[1]) & 0xE0) == 0xE0)
    return {(static_cast<unsigned char>(h[1]) & 0x06) == 0 ? "an AAC (ADTS) file" : "an MP3 file", true};
  if (starts_with(h, "GMGRAPH")) return {"a gmg graph file", false};
  if (starts_with(h, "PK\x03\x04")) return {"a ZIP archive (an .npz?)", false};
  if (starts_with(h, "\x93NUMPY")) return {"a NumPy .npy file", false};
  if (starts_with(h, "\x89PNG")) return {"a PNG picture", false};
  if (starts_with(h, "%PDF")) return {"a PDF document", false};
  if (!looks_like_text(h)) return {"", false};
  const std::string_view text = trim(strip_utf8_bom(h));
  if (text.substr(0, 9) == "HIERARCHY") return {"a BVH motion file", false};
  if (text.substr(0, 9) == "File type") return {"a Praat TextGrid", false};
  if (!text.empty() && (text.front() == '{' || text.front() == '[')) return {"JSON text", false};
  return {"text", false};
}

Audio read_audio(const std::string& path, std::vector<std::string>* out_warnings) {
  const ContentKind kind = sniff_content(file_head(path));
  if (kind.name == "a WAV file" || (kind.name.empty() && is_wav_path(path)) || kind.name == "a RIFF file")
    return read_wav(path);  // its own byte-precise errors (a RIFF of another type, a raw .wav)
  if (kind.name == "an empty file") throw Error(path + ": is empty (0 bytes), not audio");
  if (!kind.audio && !kind.name.empty())
    throw Error(path + ": is not audio: it is " + (kind.name == "text" ? "a text file" : kind.name) +
                " (give the speech as WAV, FLAC, MP3, OGG, M4A, ...)");
  if (kind.audio && is_wav_path(path) && out_warnings)
    out_warnings->push_back(path + ": is " + kind.name + ", not a WAV; decoded as such");
  return decode_with_aubio(path, kind.name, out_warnings);
}

}  // namespace gmg::audio
