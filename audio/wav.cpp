// WAV reading and writing.
//
// Why an own RIFF/WAVE parser rather than aubio's source (aubio_source_*):
// aubio only reports "failed opening" (no byte offset, no reason, so a lying
// header, a missing data chunk or an unsupported format all look alike), and
// which formats it reads (float, 24-bit, extensible) depends on which backend
// (libsndfile, ffmpeg, its own wavread) it was built with. The engine promises
// byte-precise errors and the same behaviour on every build, so it reads the
// format itself; WAV is simple enough that this is a few hundred lines.
#include "audio/wav.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iomanip>
#include <sstream>
#include <utility>

#include "audio/resample.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/limits.h"
#include "engine/core/strings.h"

namespace gmg::audio {

double Audio::duration() const {
  if (sample_rate <= 0) return 0.0;
  return static_cast<double>(samples.size()) / sample_rate;
}

namespace {

// The file's bytes as unsigned values (read_file_bytes returns chars, which are signed here).
class Bytes {
 public:
  explicit Bytes(const std::string& s) : Bytes(s.data(), s.size()) {}
  Bytes(const char* data, std::size_t size) : data_(reinterpret_cast<const unsigned char*>(data)), size_(size) {}
  unsigned char operator[](std::size_t i) const { return data_[i]; }
  const unsigned char* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  const unsigned char* data_;
  std::size_t size_;
};

std::uint16_t u16_at(const Bytes& b, std::size_t p) { return static_cast<std::uint16_t>(b[p] | (b[p + 1] << 8)); }

std::uint32_t u32_at(const Bytes& b, std::size_t p) {
  return static_cast<std::uint32_t>(b[p]) | (static_cast<std::uint32_t>(b[p + 1]) << 8) |
         (static_cast<std::uint32_t>(b[p + 2]) << 16) | (static_cast<std::uint32_t>(b[p + 3]) << 24);
}

// A four-character code for messages: printable characters as they are,
// others as \xNN, in quotes.
std::string fourcc(const Bytes& b, std::size_t p) {
  std::ostringstream os;
  os << '\'';
  for (std::size_t i = p; i < p + 4 && i < b.size(); ++i) {
    unsigned char c = b[i];
    if (c >= 32 && c < 127) {
      os << static_cast<char>(c);
    } else {
      os << "\\x" << std::hex << std::setw(2) << std::setfill('0') << static_cast<int>(c) << std::dec;
    }
  }
  os << '\'';
  return os.str();
}

bool id_is(const Bytes& b, std::size_t p, const char* id) { return std::memcmp(b.data() + p, id, 4) == 0; }

// What the fmt chunk says, reduced to what decoding needs.
struct Format {
  enum class Kind { kPcm, kFloat };
  Kind kind = Kind::kPcm;
  int channels = 0;
  int sample_rate = 0;
  int bits = 0;  // container bits per sample (8/16/24/32 PCM, 32/64 float)
};

constexpr std::uint16_t kTagPcm = 1, kTagFloat = 3, kTagExtensible = 0xFFFE;

// Parses the fmt chunk whose header starts at byte `pos` (body at pos + 8,
// `size` bytes, already known to be inside the file).
Format parse_fmt(const std::string& path, const Bytes& b, std::size_t pos, std::uint64_t size) {
  const std::size_t body = pos + 8;
  if (size < 16) {
    throw Error(error_at_byte(path, static_cast<long long>(pos),
                              "'fmt ' chunk is " + std::to_string(size) + " bytes, needs at least 16"));
  }
  std::uint16_t tag = u16_at(b, body);
  Format f;
  f.channels = u16_at(b, body + 2);
  std::uint32_t rate = u32_at(b, body + 4);
  f.bits = u16_at(b, body + 14);
  // block_align (body + 12) is not used: decoding goes by channels and bits,
  // which is what every writer gets right; a wrong block_align alone is harmless.
  std::uint16_t code = tag;
  if (tag == kTagExtensible) {
    if (size < 40) {
      throw Error(error_at_byte(path, static_cast<long long>(pos),
                                "WAVE_FORMAT_EXTENSIBLE 'fmt ' chunk is " + std::to_string(size) + " bytes, needs 40"));
    }
    // SubFormat GUID: the first two bytes are the format code, the other 14
    // are the fixed KSDATAFORMAT suffix 00000000-0010-8000-00AA00389B71.
    static const unsigned char kSuffix[14] = {0x00, 0x00, 0x00, 0x00, 0x10, 0x00, 0x80,
                                              0x00, 0x00, 0xAA, 0x00, 0x38, 0x9B, 0x71};
    code = u16_at(b, body + 24);
    if (std::memcmp(b.data() + body + 26, kSuffix, 14) != 0 || (code != kTagPcm && code != kTagFloat)) {
      throw Error(error_at_byte(path, static_cast<long long>(body + 24),
                                "unsupported WAVE_FORMAT_EXTENSIBLE subformat (only PCM and IEEE float are read)"));
    }
  }
  if (code == kTagPcm) {
    f.kind = Format::Kind::kPcm;
    if (f.bits != 8 && f.bits != 16 && f.bits != 24 && f.bits != 32) {
      throw Error(error_at_byte(
          path, static_cast<long long>(body + 14),
          "unsupported bit depth " + std::to_string(f.bits) + " for integer PCM (supported: 8, 16, 24, 32)"));
    }
  } else if (code == kTagFloat) {
    f.kind = Format::Kind::kFloat;
    if (f.bits != 32 && f.bits != 64) {
      throw Error(
          error_at_byte(path, static_cast<long long>(body + 14),
                        "unsupported bit depth " + std::to_string(f.bits) + " for IEEE float (supported: 32, 64)"));
    }
  } else {
    std::ostringstream os;
    os << "unsupported format tag 0x" << std::hex << std::setw(4) << std::setfill('0') << tag
       << " (only PCM 0x0001, IEEE float 0x0003 and EXTENSIBLE 0xfffe are read)";
    throw Error(error_at_byte(path, static_cast<long long>(body), os.str()));
  }
  if (f.channels == 0) throw Error(error_at_byte(path, static_cast<long long>(body + 2), "zero channels"));
  if (rate == 0) throw Error(error_at_byte(path, static_cast<long long>(body + 4), "zero sample rate"));
  if (rate < static_cast<std::uint32_t>(limits::kMinSampleRate) ||
      rate > static_cast<std::uint32_t>(limits::kMaxSampleRate)) {
    throw Error(error_at_byte(path, static_cast<long long>(body + 4),
                              "sample rate " + std::to_string(rate) + " Hz is outside the " +
                                  std::to_string(limits::kMinSampleRate) + " to " +
                                  std::to_string(limits::kMaxSampleRate) + " Hz gmg reads"));
  }
  f.sample_rate = static_cast<int>(rate);
  return f;
}

}  // namespace

namespace {

// The RIFF/WAVE magic: "RIFF" <size> "WAVE".
void check_riff_header(const std::string& path, const Bytes& b) {
  const std::uint64_t file_size = b.size();
  if (file_size == 0) throw Error(error_at_byte(path, 0, "empty file"));
  if (file_size < 12) {
    throw Error(error_at_byte(path, static_cast<long long>(file_size),
                              "file ends after " + std::to_string(file_size) + " bytes, inside the RIFF header"));
  }
  if (id_is(b, 0, "RF64")) throw Error(error_at_byte(path, 0, "RF64 (64-bit WAV) is not supported"));
  if (!id_is(b, 0, "RIFF")) {
    throw Error(error_at_byte(path, 0, "not a RIFF/WAVE file (starts with " + fourcc(b, 0) + ", expected 'RIFF')"));
  }
  if (!id_is(b, 8, "WAVE")) {
    throw Error(error_at_byte(path, 8, "not a RIFF/WAVE file (RIFF type " + fourcc(b, 8) + ", expected 'WAVE')"));
  }
  // The RIFF size field (byte 4) is ignored: writers that stream get it
  // wrong, and every chunk is bounded by the real file size below instead.
}

// The fmt chunk and where the data chunk lies.
struct Chunks {
  Format fmt;
  std::uint64_t data_pos = 0, data_body = 0, data_size = 0;
};

// Walks the chunks after the RIFF header: the first 'fmt ' and 'data' chunks, each bounded by
// the real file size.
Chunks find_chunks(const std::string& path, const Bytes& b) {
  const std::uint64_t file_size = b.size();
  bool have_fmt = false, have_data = false;
  Chunks c;
  // 64-bit positions: a chunk size of 0xFFFFFFFF cannot overflow or loop.
  std::uint64_t pos = 12;
  while (pos + 8 <= file_size) {
    const std::size_t p = static_cast<std::size_t>(pos);
    const std::uint64_t size = u32_at(b, p + 4);
    const std::uint64_t body = pos + 8;
    const std::uint64_t avail = file_size - body;
    if (id_is(b, p, "fmt ") && !have_fmt) {
      if (size > avail) {
        throw Error(error_at_byte(path, static_cast<long long>(pos),
                                  "'fmt ' chunk declares " + std::to_string(size) + " bytes but only " +
                                      std::to_string(avail) + " are present"));
      }
      c.fmt = parse_fmt(path, b, p, size);
      have_fmt = true;
    } else if (id_is(b, p, "data") && !have_data) {
      if (size > avail) {
        throw Error(error_at_byte(path, static_cast<long long>(pos),
                                  "'data' chunk declares " + std::to_string(size) + " bytes but only " +
                                      std::to_string(avail) + " are present (truncated file or lying header)"));
      }
      have_data = true;
      c.data_pos = pos;
      c.data_body = body;
      c.data_size = size;
    } else if (size > avail) {
      // Unknown (or repeated) chunk running past the end. Trailing junk
      // after both needed chunks is tolerated; before them it is an error.
      if (have_fmt && have_data) break;
      throw Error(error_at_byte(path, static_cast<long long>(pos),
                                "chunk " + fourcc(b, p) + " declares " + std::to_string(size) + " bytes but only " +
                                    std::to_string(avail) + " are present"));
    }
    // Chunks are word aligned: an odd-sized chunk is followed by a pad byte.
    pos = body + size + (size & 1u);
  }
  const long long end = static_cast<long long>(std::min(pos, file_size));
  if (!have_fmt) throw Error(error_at_byte(path, end, "no 'fmt ' chunk in the file"));
  if (!have_data) throw Error(error_at_byte(path, end, "no 'data' chunk in the file"));
  return c;
}

// The stored sample types: each reads one sample at p as a double (PCM scaled to [-1, 1), float as
// stored), so that a chunk is decoded in one loop per format (with_sample_type picks it once).
template <typename T>
T load_le(const unsigned char* p) {
  T v;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  std::memcpy(&v, p, sizeof v);
#else
  unsigned char le[sizeof(T)];
  for (std::size_t i = 0; i < sizeof(T); ++i) le[i] = p[sizeof(T) - 1 - i];
  std::memcpy(&v, le, sizeof v);
#endif
  return v;
}

// kAlwaysFinite: integer samples, which need no check.
struct Pcm8 {
  static constexpr std::size_t kBytes = 1;
  static constexpr bool kAlwaysFinite = true;
  static double read(const unsigned char* p) { return (static_cast<int>(p[0]) - 128) / 128.0; }
};
struct Pcm16 {
  static constexpr std::size_t kBytes = 2;
  static constexpr bool kAlwaysFinite = true;
  static double read(const unsigned char* p) { return load_le<std::int16_t>(p) / 32768.0; }
};
struct Pcm24 {
  static constexpr std::size_t kBytes = 3;
  static constexpr bool kAlwaysFinite = true;
  static double read(const unsigned char* p) {
    std::int32_t s = static_cast<std::int32_t>(p[0] | (p[1] << 8) | (p[2] << 16));
    if (s & 0x800000) s -= 0x1000000;
    return s / 8388608.0;
  }
};
struct Pcm32 {
  static constexpr std::size_t kBytes = 4;
  static constexpr bool kAlwaysFinite = true;
  static double read(const unsigned char* p) { return load_le<std::int32_t>(p) / 2147483648.0; }
};
struct Float32 {
  static constexpr std::size_t kBytes = 4;
  static constexpr bool kAlwaysFinite = false;
  static double read(const unsigned char* p) { return load_le<float>(p); }
};
struct Float64 {
  static constexpr std::size_t kBytes = 8;
  static constexpr bool kAlwaysFinite = false;
  static double read(const unsigned char* p) { return load_le<double>(p); }
};

// out[i] = the mean of frame i's channels (the sum from 0.0 in channel order, times 1 / channels,
// rounded to float), in a loop the compiler vectorises. Returns false when a sample is not finite
// (the caller then finds it: first_non_finite).
template <typename F>
bool mix_down(const unsigned char* data, std::size_t frames, int channels, float* out) {
  const double inv_channels = 1.0 / channels;
  int finite = 1;
  if (channels == 1) {
    for (std::size_t i = 0; i < frames; ++i) {
      const double v = F::read(data + i * F::kBytes);
      if constexpr (!F::kAlwaysFinite) finite &= std::fabs(v) <= DBL_MAX;
      out[i] = static_cast<float>((0.0 + v) * inv_channels);
    }
    return finite != 0;
  }
  const std::size_t frame_bytes = F::kBytes * static_cast<std::size_t>(channels);
  for (std::size_t i = 0; i < frames; ++i) {
    const unsigned char* p = data + i * frame_bytes;
    double sum = 0.0;
    for (int ch = 0; ch < channels; ++ch) {
      const double v = F::read(p + static_cast<std::size_t>(ch) * F::kBytes);
      if constexpr (!F::kAlwaysFinite) finite &= std::fabs(v) <= DBL_MAX;
      sum += v;
    }
    out[i] = static_cast<float>(sum * inv_channels);
  }
  return finite != 0;
}

// Calls visit(T{}) with the sample type T of the format.
template <typename Visit>
auto with_sample_type(const Format& fmt, const Visit& visit) {
  if (fmt.kind == Format::Kind::kFloat) return fmt.bits == 32 ? visit(Float32{}) : visit(Float64{});
  switch (fmt.bits) {
    case 8:
      return visit(Pcm8{});
    case 16:
      return visit(Pcm16{});
    case 24:
      return visit(Pcm24{});
    default:
      return visit(Pcm32{});
  }
}

// The first of `count` samples at data that is not finite (count when there is none), and its value.
template <typename F>
std::pair<std::size_t, double> first_non_finite(const unsigned char* data, std::size_t count) {
  if constexpr (F::kAlwaysFinite) return {count, 0.0};
  for (std::size_t k = 0; k < count; ++k) {
    const double v = F::read(data + k * F::kBytes);
    if (!std::isfinite(v)) return {k, v};
  }
  return {count, 0.0};
}

// The data chunk's frames, each the mean of its channels. With a file, the pages of the chunk are
// given back as they are decoded, so that a long recording is not held twice.
Audio decode_samples(const std::string& path, const Bytes& b, const Chunks& c, const MappedFile* file) {
  const Format& fmt = c.fmt;
  const std::uint64_t bytes_per_sample = static_cast<std::uint64_t>(fmt.bits / 8);
  const std::uint64_t frame_bytes = bytes_per_sample * static_cast<std::uint64_t>(fmt.channels);
  // A trailing partial frame (data size not a multiple of the frame size) is
  // ignored, as libsndfile does.
  const std::uint64_t frames = c.data_size / frame_bytes;
  if (frames == 0) {
    throw Error(error_at_byte(path, static_cast<long long>(c.data_pos),
                              "'data' chunk holds no samples (" + std::to_string(c.data_size) + " bytes)"));
  }
  if (static_cast<double>(frames) / fmt.sample_rate > limits::kMaxAudioSeconds) {
    throw Error(error_at_byte(path, static_cast<long long>(c.data_pos),
                              std::to_string(frames) + " samples at " + std::to_string(fmt.sample_rate) +
                                  " Hz last longer than the " + format_number(limits::kMaxAudioSeconds / 3600) +
                                  " hours gmg reads"));
  }
  Audio a;
  a.sample_rate = fmt.sample_rate;
  // Decoded a stretch at a time into the reserved samples (not zeroed first).
  a.samples.reserve(static_cast<std::size_t>(frames));
  constexpr std::size_t kStretch = 4096, kRelease = std::size_t{16} << 20;
  float stretch[kStretch];
  bool finite = true;
  std::size_t released = 0;
  for (std::size_t i0 = 0; i0 < frames; i0 += kStretch) {
    const std::size_t n = std::min<std::size_t>(kStretch, frames - i0);
    const unsigned char* data = b.data() + c.data_body + i0 * frame_bytes;
    finite =
        with_sample_type(fmt, [&](auto type) { return mix_down<decltype(type)>(data, n, fmt.channels, stretch); }) &&
        finite;
    a.samples.insert(a.samples.end(), stretch, stretch + n);
    const std::size_t done = c.data_body + (i0 + n) * frame_bytes;
    if (file && done - released >= kRelease) {
      file->release(released, done - released);
      released = done;
    }
  }
  if (finite) return a;
  // A sample is NaN or infinite: the first one in the file, for the message.
  const std::size_t count = static_cast<std::size_t>(frames) * static_cast<std::size_t>(fmt.channels);
  const auto [k, v] =
      with_sample_type(fmt, [&](auto type) { return first_non_finite<decltype(type)>(b.data() + c.data_body, count); });
  if (k == count) return a;
  const std::size_t channels = static_cast<std::size_t>(fmt.channels);
  throw Error(error_at_byte(path, static_cast<long long>(c.data_body + k * bytes_per_sample),
                            std::string("sample ") + std::to_string(k / channels) + " (channel " +
                                std::to_string(k % channels) + ") is " + (std::isnan(v) ? "NaN" : "infinite")));
}

}  // namespace

Audio parse_wav(const std::string& bytes, const std::string& name) {
  return naming_memory_errors(name, "reading the audio", [&] {
    const Bytes b(bytes);
    check_riff_header(name, b);
    return decode_samples(name, b, find_chunks(name, b), nullptr);
  });
}

// The file is read from its mapping, not copied into memory first (an hour of 16-bit audio at
// 16 kHz is 115 MB), and a file changed while it is read is an error rather than a mix of two.
Audio read_wav(const std::string& path) {
  const MappedFile file(path);
  try {
    Audio a = naming_memory_errors(path, "reading the audio", [&] {
      const Bytes b(file.data(), file.size());
      check_riff_header(path, b);
      return decode_samples(path, b, find_chunks(path, b), &file);
    });
    file.check_unchanged();
    return a;
  } catch (const Error&) {
    file.check_unchanged();  // a file cut short while read: that, not what its bytes then looked like
    throw;
  }
}

Audio read_wav(const std::string& path, int target_rate) {
  if (target_rate <= 0) throw Error(path + ": target sample rate " + std::to_string(target_rate) + " is not positive");
  Audio a = read_wav(path);
  if (a.sample_rate != target_rate) {
    a.samples = resample_poly(a.samples, a.sample_rate, target_rate);
    a.sample_rate = target_rate;
  }
  return a;
}

void write_wav_pcm16(const std::string& path, const Audio& a) {
  if (a.sample_rate <= 0) {
    throw Error(
        error_at_line(path, 0, "cannot write WAV: sample rate " + std::to_string(a.sample_rate) + " is not positive"));
  }
  const std::uint64_t data_bytes = 2ull * a.samples.size();
  if (data_bytes + 36 > 0xFFFFFFFFull)
    throw Error(error_at_line(path, 0, "cannot write WAV: too many samples for RIFF"));
  std::vector<unsigned char> out;
  out.reserve(static_cast<std::size_t>(44 + data_bytes));
  auto put = [&out](const char* s) { out.insert(out.end(), s, s + 4); };
  auto put16 = [&out](std::uint32_t v) {
    out.push_back(static_cast<unsigned char>(v & 0xFF));
    out.push_back(static_cast<unsigned char>((v >> 8) & 0xFF));
  };
  auto put32 = [&put16](std::uint32_t v) {
    put16(v & 0xFFFF);
    put16(v >> 16);
  };
  const std::uint32_t rate = static_cast<std::uint32_t>(a.sample_rate);
  put("RIFF");
  put32(static_cast<std::uint32_t>(36 + data_bytes));
  put("WAVE");
  put("fmt ");
  put32(16);
  put16(kTagPcm);
  put16(1);  // channels
  put32(rate);
  put32(rate * 2);  // byte rate
  put16(2);         // block align
  put16(16);        // bits
  put("data");
  put32(static_cast<std::uint32_t>(data_bytes));
  for (float s : a.samples) {
    double v = std::isfinite(s) ? std::round(static_cast<double>(s) * 32768.0) : 0.0;
    v = std::min(32767.0, std::max(-32768.0, v));
    put16(static_cast<std::uint16_t>(static_cast<std::int16_t>(v)));
  }

  auto write = [&out](std::ostream& os) {
    os.write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
  };
  write_file_atomically(path, write, true);
}

}  // namespace gmg::audio
