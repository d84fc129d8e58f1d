// WAV reading/writing and scipy-compatible polyphase resampling.
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
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <numeric>
#include <sstream>

#include "engine/core/error.h"

namespace gmg::audio {

double Audio::duration() const {
  if (sample_rate <= 0) return 0.0;
  return static_cast<double>(samples.size()) / sample_rate;
}

namespace {

std::uint16_t u16_at(const std::vector<unsigned char>& b, std::size_t p) {
  return static_cast<std::uint16_t>(b[p] | (b[p + 1] << 8));
}

std::uint32_t u32_at(const std::vector<unsigned char>& b, std::size_t p) {
  return static_cast<std::uint32_t>(b[p]) | (static_cast<std::uint32_t>(b[p + 1]) << 8) |
         (static_cast<std::uint32_t>(b[p + 2]) << 16) | (static_cast<std::uint32_t>(b[p + 3]) << 24);
}

std::uint64_t u64_at(const std::vector<unsigned char>& b, std::size_t p) {
  return static_cast<std::uint64_t>(u32_at(b, p)) | (static_cast<std::uint64_t>(u32_at(b, p + 4)) << 32);
}

// A four-character code for messages: printable characters as they are,
// others as \xNN, in quotes.
std::string fourcc(const std::vector<unsigned char>& b, std::size_t p) {
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

bool id_is(const std::vector<unsigned char>& b, std::size_t p, const char* id) {
  return std::memcmp(b.data() + p, id, 4) == 0;
}

std::vector<unsigned char> read_all(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(error_at_line(path, 0, "cannot read: is a directory"));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(error_at_line(path, 0, std::string("cannot open: ") + std::strerror(errno)));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size < 0 || !in) throw Error(error_at_line(path, 0, "cannot read (not a regular file?)"));
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), size);
  if (in.gcount() != size) {
    throw Error(error_at_byte(path, static_cast<long long>(in.gcount()), "read error"));
  }
  return bytes;
}

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
Format parse_fmt(const std::string& path, const std::vector<unsigned char>& b, std::size_t pos, std::uint64_t size) {
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
                                "WAVE_FORMAT_EXTENSIBLE 'fmt ' chunk is " + std::to_string(size) +
                                    " bytes, needs 40"));
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
      throw Error(error_at_byte(path, static_cast<long long>(body + 14),
                                "unsupported bit depth " + std::to_string(f.bits) +
                                    " for integer PCM (supported: 8, 16, 24, 32)"));
    }
  } else if (code == kTagFloat) {
    f.kind = Format::Kind::kFloat;
    if (f.bits != 32 && f.bits != 64) {
      throw Error(error_at_byte(path, static_cast<long long>(body + 14),
                                "unsupported bit depth " + std::to_string(f.bits) +
                                    " for IEEE float (supported: 32, 64)"));
    }
  } else {
    std::ostringstream os;
    os << "unsupported format tag 0x" << std::hex << std::setw(4) << std::setfill('0') << tag
       << " (only PCM 0x0001, IEEE float 0x0003 and EXTENSIBLE 0xfffe are read)";
    throw Error(error_at_byte(path, static_cast<long long>(body), os.str()));
  }
  if (f.channels == 0) throw Error(error_at_byte(path, static_cast<long long>(body + 2), "zero channels"));
  if (rate == 0) throw Error(error_at_byte(path, static_cast<long long>(body + 4), "zero sample rate"));
  if (rate > 0x7FFFFFFFu) {
    throw Error(error_at_byte(path, static_cast<long long>(body + 4), "sample rate " + std::to_string(rate) + " is out of range"));
  }
  f.sample_rate = static_cast<int>(rate);
  return f;
}

// Zeroth-order modified Bessel function of the first kind (power series; the
// arguments here are at most the Kaiser beta, 5, where it converges in ~20 terms).
double bessel_i0(double x) {
  double sum = 1.0, term = 1.0;
  const double q = 0.25 * x * x;
  for (int k = 1; k < 500; ++k) {
    term *= q / (static_cast<double>(k) * k);
    sum += term;
    if (term < sum * 1e-17) break;
  }
  return sum;
}

// scipy.signal.firwin(numtaps, cutoff, window=('kaiser', beta)) for a
// low-pass with cutoff relative to Nyquist, scaled to unit gain at DC.
std::vector<double> firwin_kaiser(int numtaps, double cutoff, double beta) {
  const double kPi = 3.14159265358979323846;
  std::vector<double> h(static_cast<std::size_t>(numtaps));
  const double alpha = 0.5 * (numtaps - 1);
  const double i0_beta = bessel_i0(beta);
  double sum = 0.0;
  for (int i = 0; i < numtaps; ++i) {
    double m = i - alpha;
    double xm = cutoff * m;
    double sinc = (xm == 0.0) ? 1.0 : std::sin(kPi * xm) / (kPi * xm);
    // Symmetric Kaiser window (scipy.signal.windows.kaiser, sym=True).
    double r = (numtaps > 1) ? (i - alpha) / alpha : 0.0;
    double w = bessel_i0(beta * std::sqrt(std::max(0.0, 1.0 - r * r))) / i0_beta;
    h[static_cast<std::size_t>(i)] = cutoff * sinc * w;
    sum += h[static_cast<std::size_t>(i)];
  }
  for (double& v : h) v /= sum;
  return h;
}

}  // namespace

Audio read_wav(const std::string& path) {
  const std::vector<unsigned char> b = read_all(path);
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

  bool have_fmt = false, have_data = false;
  Format fmt;
  std::uint64_t data_body = 0, data_size = 0, data_pos = 0;
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
      fmt = parse_fmt(path, b, p, size);
      have_fmt = true;
    } else if (id_is(b, p, "data") && !have_data) {
      if (size > avail) {
        throw Error(error_at_byte(path, static_cast<long long>(pos),
                                  "'data' chunk declares " + std::to_string(size) + " bytes but only " +
                                      std::to_string(avail) + " are present (truncated file or lying header)"));
      }
      have_data = true;
      data_pos = pos;
      data_body = body;
      data_size = size;
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
  if (!have_fmt) throw Error(error_at_byte(path, static_cast<long long>(std::min(pos, file_size)), "no 'fmt ' chunk in the file"));
  if (!have_data) throw Error(error_at_byte(path, static_cast<long long>(std::min(pos, file_size)), "no 'data' chunk in the file"));

  const std::uint64_t bytes_per_sample = static_cast<std::uint64_t>(fmt.bits / 8);
  const std::uint64_t frame_bytes = bytes_per_sample * static_cast<std::uint64_t>(fmt.channels);
  // A trailing partial frame (data size not a multiple of the frame size) is
  // ignored, as libsndfile does.
  const std::uint64_t frames = data_size / frame_bytes;
  if (frames == 0) {
    throw Error(error_at_byte(path, static_cast<long long>(data_pos),
                              "'data' chunk holds no samples (" + std::to_string(data_size) + " bytes)"));
  }

  Audio a;
  a.sample_rate = fmt.sample_rate;
  a.samples.resize(static_cast<std::size_t>(frames));
  const double inv_channels = 1.0 / fmt.channels;
  std::size_t p = static_cast<std::size_t>(data_body);
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    double sum = 0.0;
    for (int c = 0; c < fmt.channels; ++c, p += static_cast<std::size_t>(bytes_per_sample)) {
      double v = 0.0;
      if (fmt.kind == Format::Kind::kPcm) {
        switch (fmt.bits) {
          case 8: v = (static_cast<int>(b[p]) - 128) / 128.0; break;  // 8-bit WAV is unsigned
          case 16: v = static_cast<std::int16_t>(u16_at(b, p)) / 32768.0; break;
          case 24: {
            std::int32_t s = static_cast<std::int32_t>(b[p] | (b[p + 1] << 8) | (b[p + 2] << 16));
            if (s & 0x800000) s -= 0x1000000;
            v = s / 8388608.0;
            break;
          }
          default: v = static_cast<std::int32_t>(u32_at(b, p)) / 2147483648.0; break;
        }
      } else {
        if (fmt.bits == 32) {
          std::uint32_t u = u32_at(b, p);
          float f;
          std::memcpy(&f, &u, sizeof f);
          v = f;
        } else {
          std::uint64_t u = u64_at(b, p);
          std::memcpy(&v, &u, sizeof v);
        }
        if (!std::isfinite(v)) {
          throw Error(error_at_byte(path, static_cast<long long>(p),
                                    std::string("sample ") + std::to_string(i) + " (channel " + std::to_string(c) +
                                        ") is " + (std::isnan(v) ? "NaN" : "infinite")));
        }
      }
      sum += v;
    }
    a.samples[i] = static_cast<float>(sum * inv_channels);
  }
  return a;
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

std::vector<float> resample_poly(const std::vector<float>& x, int from_rate, int to_rate) {
  if (from_rate <= 0 || to_rate <= 0) {
    throw Error("resample_poly: sample rates must be positive (from " + std::to_string(from_rate) + " to " +
                std::to_string(to_rate) + ")");
  }
  const long long g = std::gcd(from_rate, to_rate);
  const long long up = to_rate / g, down = from_rate / g;
  if (up == 1 && down == 1) return x;
  const long long n_in = static_cast<long long>(x.size());
  const long long n_out = (n_in * up + down - 1) / down;  // ceil(n_in * up / down)

  // The filter scipy designs: firwin(2 * half_len + 1, 1 / max_rate,
  // ('kaiser', 5.0)) times up.
  const long long max_rate = std::max(up, down);
  const long long half_len = 10 * max_rate;
  const long long taps = 2 * half_len + 1;
  std::vector<double> h = firwin_kaiser(static_cast<int>(taps), 1.0 / static_cast<double>(max_rate), 5.0);
  for (double& v : h) v *= static_cast<double>(up);

  // scipy's alignment: it pre-pads h with n_pre_pad = down - half_len % down
  // zeros and drops n_pre_remove = (half_len + n_pre_pad) / down outputs of
  // upfirdn; since half_len + n_pre_pad is a multiple of down, that works
  // out to exactly
  //   y[n] = sum_k h[k] * xu[n * down + half_len - k]
  //        = sum_k h[k] * xu[n * down + k - half_len]      (h symmetric)
  // where xu is x with up - 1 zeros after every sample (zero outside x):
  // output sample n sits at time n / to_rate, the filter centred on it.
  // Only every up-th tap meets a nonzero xu, so each output costs
  // taps / up multiplications (the polyphase form).
  std::vector<float> y(static_cast<std::size_t>(n_out));
  for (long long n = 0; n < n_out; ++n) {
    const long long base = n * down - half_len;  // xu index of tap k = 0
    // First tap k with (base + k) divisible by up and base + k >= 0.
    long long k0 = ((-base) % up + up) % up;
    long long i0 = (base + k0) / up;  // x index of tap k0 (may be negative)
    if (i0 < 0) {
      k0 += (-i0) * up;
      i0 = 0;
    }
    double acc = 0.0;
    for (long long k = k0, i = i0; k < taps && i < n_in; k += up, ++i) {
      acc += h[static_cast<std::size_t>(k)] * x[static_cast<std::size_t>(i)];
    }
    y[static_cast<std::size_t>(n)] = static_cast<float>(acc);
  }
  return y;
}

void write_wav_pcm16(const std::string& path, const Audio& a) {
  if (a.sample_rate <= 0) {
    throw Error(error_at_line(path, 0, "cannot write WAV: sample rate " + std::to_string(a.sample_rate) + " is not positive"));
  }
  const std::uint64_t data_bytes = 2ull * a.samples.size();
  if (data_bytes + 36 > 0xFFFFFFFFull) throw Error(error_at_line(path, 0, "cannot write WAV: too many samples for RIFF"));
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
  put16(1);          // channels
  put32(rate);
  put32(rate * 2);   // byte rate
  put16(2);          // block align
  put16(16);         // bits
  put("data");
  put32(static_cast<std::uint32_t>(data_bytes));
  for (float s : a.samples) {
    double v = std::isfinite(s) ? std::round(static_cast<double>(s) * 32768.0) : 0.0;
    v = std::min(32767.0, std::max(-32768.0, v));
    put16(static_cast<std::uint16_t>(static_cast<std::int16_t>(v)));
  }

  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw Error(error_at_line(tmp, 0, std::string("cannot open for writing: ") + std::strerror(errno)));
    f.write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
    f.close();
    if (!f) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw Error(error_at_line(tmp, 0, "write failed"));
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::error_code ec2;
    std::filesystem::remove(tmp, ec2);
    throw Error(error_at_line(path, 0, "cannot rename " + tmp + ": " + ec.message()));
  }
}

}  // namespace gmg::audio
