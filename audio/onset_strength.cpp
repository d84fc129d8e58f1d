// The onset strength envelope, after librosa 0.10.2's onset_strength: resampling as the frames
// reach the audio, the STFT, the mel spectrogram in dB, and the rises.
#include "audio/onset_strength.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <utility>

#include "audio/fftw_planner.h"
#include "audio/lanes.h"
#include "audio/mel_bank.h"
#include "audio/onset.h"
#include "audio/resample.h"
#include "engine/core/error.h"
#include "engine/core/math.h"

namespace gmg::audio {

namespace {

constexpr int kSr = OnsetAnalysis::kSampleRate;
constexpr int kHop = OnsetAnalysis::kHop;
constexpr int kNfft = OnsetAnalysis::kNfft;
constexpr int kMels = OnsetAnalysis::kMels;
constexpr int kBins = kNfft / 2 + 1;

// Periodic Hann window (scipy get_window('hann', 2048, fftbins=True)).
const std::vector<double>& hann_window() {
  static const std::vector<double> w = [] {
    std::vector<double> v(kNfft);
    for (int i = 0; i < kNfft; ++i) v[static_cast<std::size_t>(i)] = 0.5 - 0.5 * std::cos(2.0 * kPi * i / kNfft);
    return v;
  }();
  return w;
}

// One complex FFT plan of 1024 points (see RealFft) for the whole process (FFTW's planner is not
// thread-safe, so it is made once, under a lock; executing a plan on other arrays of the same
// alignment is safe from any thread).
fftwf_plan fft_plan() {
  const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  static fftwf_plan plan = [] {
    float* in = fftwf_alloc_real(kNfft);
    fftwf_complex* out = fftwf_alloc_complex(kBins);
    fftwf_plan p =
        in && out ? fftwf_plan_dft_1d(kNfft / 2, reinterpret_cast<fftwf_complex*>(in), out, FFTW_FORWARD, FFTW_ESTIMATE)
                  : nullptr;
    fftwf_free(in);
    fftwf_free(out);
    return p;
  }();
  if (!plan) throw Error("onset detection: FFTW could not plan a 2048-point FFT");
  return plan;
}

// An input and an output buffer for the plan, aligned as FFTW allocates (so the plan's SIMD code
// applies), freed on scope exit.
struct FftBuffers {
  float* in = fftwf_alloc_real(kNfft);
  fftwf_complex* out = fftwf_alloc_complex(kBins);
  FftBuffers() {
    if (!in || !out) {
      release();
      throw std::bad_alloc();
    }
  }
  ~FftBuffers() { release(); }
  FftBuffers(const FftBuffers&) = delete;
  FftBuffers& operator=(const FftBuffers&) = delete;
  void release() {
    fftwf_free(in);
    fftwf_free(out);
    in = nullptr;
    out = nullptr;
  }
};

}  // namespace

namespace {

void check_rate(const Audio& audio) {
  if (audio.sample_rate <= 0) {
    throw Error("onset detection: sample rate " + std::to_string(audio.sample_rate) + " is not positive");
  }
}

// The audio at 22050 Hz a stretch at a time, as the spectrogram reaches it: the samples
// themselves at that rate, else resample_poly's output computed a few of its blocks at a time
// into a buffer that keeps only what the frames still to come read (an hour at 16 kHz would be
// 317 MB at 22050 Hz, written once and read back from memory four times over; the buffer stays
// in the second-level cache).
class OnsetSignal {
 public:
  // x must outlive the signal.
  OnsetSignal(const std::vector<float>& x, int rate) : x_(x) {
    if (rate == kSr) {
      n_ = static_cast<long long>(x.size());
      return;
    }
    resampler_ = std::make_unique<PolyphaseResampler>(x, rate, kSr);
    n_ = resampler_->size();
    block_ = resampler_->block();
  }

  // Samples at 22050 Hz in all.
  long long size() const { return n_; }

  // Samples a .. b - 1 (0 <= a <= b <= size(); a never below an earlier call's a, b - a at most
  // kMaxSpan): a pointer to sample a, valid until the next call.
  const float* samples(long long a, long long b) {
    if (!resampler_) return x_.data() + a;
    if (b > hi_) {
      const long long more = (b - hi_ + block_ - 1) / block_ * block_;
      const long long cap = 2 * (kMaxSpan + block_) + 4 * block_;
      if (buf_.empty()) buf_.resize(static_cast<std::size_t>(cap));
      if (hi_ - lo_ + more > cap) {
        // Only a .. hi_ - 1 is read again: moved to the front (at most kMaxSpan + block_ samples).
        std::memmove(buf_.data(), buf_.data() + (a - lo_), static_cast<std::size_t>(hi_ - a) * sizeof(float));
        lo_ = a;
      }
      const long long count = std::min(more, n_ - hi_);
      resampler_->compute(hi_, count, buf_.data() + (hi_ - lo_));
      hi_ += count;
    }
    return buf_.data() + (a - lo_);
  }

  // The span of samples a block of frames reads, at most.
  static constexpr long long kMaxSpan = 16 * kHop + kNfft;

 private:
  const std::vector<float>& x_;
  std::unique_ptr<PolyphaseResampler> resampler_;
  long long n_ = 0, block_ = 0;
  std::vector<float> buf_;
  long long lo_ = 0, hi_ = 0;  // buf_ holds samples lo_ .. hi_ - 1
};

// The envelope of the signal.
std::vector<float> envelope_of(OnsetSignal& y);

}  // namespace

std::vector<float> onset_strength_envelope(const Audio& audio) {
  check_rate(audio);
  OnsetSignal y(audio.samples, audio.sample_rate);
  return envelope_of(y);
}

std::vector<float> onset_strength_envelope(Audio&& audio) {
  check_rate(audio);
  std::vector<float> samples = std::move(audio.samples);
  std::vector<float>().swap(audio.samples);
  OnsetSignal y(samples, audio.sample_rate);
  return envelope_of(y);
}

namespace {

// The spectrogram is computed kFrames frames at a time, one frame per lane of two vectors
// (audio/lanes.h): sixteen frames with AVX-512, eight with AVX, four with SSE2. Two vectors give
// each band's sum, and the logarithm's series, two independent chains where one would wait on its
// own latency (with AVX-512 too: docs/decisions.md, "Implementation choices").
using lanes::LaneBits;
using lanes::Lanes;
using lanes::LanesF;
using lanes::select;
constexpr int kLanes = lanes::kWidth;
constexpr int kVectors = 2;
constexpr int kFrames = kVectors * kLanes;

// power_to_db (onset_strength.h) lane by lane. glibc's log10 is a scalar call, much of the
// analysis; this is its argument reduction and a series, vectorised: x = 2^e m with m in
// [sqrt(1/2), sqrt(2)), ln m = 2 atanh(s) with s = (m - 1) / (m + 1), |s| < 0.172, whose odd series
// to s^19 is within double rounding (the next term is below 3e-17 of the sum). How close it is to
// std::log10: Onsets.PowerToDbIsTheLibraryLog and docs/decisions.md, "Implementation choices".
Lanes power_to_db_lanes(const Lanes& power) {
  const Lanes x = select(power > 1e-10, power, Lanes{} + 1e-10);  // as std::max(1e-10, power)
  LaneBits bits;
  std::memcpy(&bits, &x, sizeof bits);
  LaneBits e = ((bits >> 52) & 0x7ff) - 1023;
  const LaneBits mbits = (bits & 0x000fffffffffffffLL) | 0x3ff0000000000000LL;  // [1, 2)
  Lanes m;
  std::memcpy(&m, &mbits, sizeof m);
  const LaneBits big = m > 1.4142135623730951;
  m = select(big, m * 0.5, m);
  e -= big;                 // big is -1 where true
  const Lanes f = m - 1.0;  // exact (Sterbenz)
  const Lanes s = f / (2.0 + f);
  const Lanes z = s * s;
  Lanes p = z * (1.0 / 19.0);
  for (int k = 17; k >= 3; k -= 2) p = z * (p + 1.0 / k);
  const Lanes ln_m = 2.0 * s + 2.0 * s * p;
  Lanes ef;
  for (int l = 0; l < kLanes; ++l) ef[l] = static_cast<double>(e[l]);
  // 10 log10(2) and 10 / ln(10).
  const Lanes db = ef * 3.0102999566398120 + ln_m * 4.3429448190325182;
  return select(x == HUGE_VAL, x, db);
}

}  // namespace

double power_to_db(double power) { return power_to_db_lanes(Lanes{} + power)[0]; }

namespace {

// Frame t of the STFT with center=True, windowed: the signal (n samples) is zero padded by
// n_fft / 2 on both sides (librosa 0.10's default pad_mode="constant"), frame t covers
// y[t * hop - n_fft / 2, t * hop + n_fft / 2). y points to sample a, and the frame's samples in
// 0 .. n - 1 are from a on.
void windowed_frame(const float* y, long long a, long long n, long long t, float* out) {
  const std::vector<double>& win = hann_window();
  const long long start = t * kHop - kNfft / 2;
  if (start >= 0 && start + kNfft <= n) {
    const float* x = y + (start - a);
    for (int i = 0; i < kNfft; ++i)
      out[i] = static_cast<float>(win[static_cast<std::size_t>(i)] * static_cast<double>(x[i]));
    return;
  }
  for (int i = 0; i < kNfft; ++i) {
    const long long j = start + i;
    out[i] =
        static_cast<float>((j >= 0 && j < n) ? win[static_cast<std::size_t>(i)] * static_cast<double>(y[j - a]) : 0.0);
  }
}

// The real FFT of 2048 points is FFTW's single precision complex FFT of 1024 points of the
// frame's even and odd samples as real and imaginary parts (the frame itself, read as 1024
// complex numbers), split in double: with Z the transform and Z[1024] = Z[0],
//   X[k] = (Z[k] + conj Z[1024 - k]) / 2 - i e^(-i pi k / 1024) (Z[k] - conj Z[1024 - k]) / 2.
// FFTW's own real-input transform does the same split in single precision and its complex
// codelets are faster than its real-input ones here; the envelopes move by less than a float step
// at their peaks, with the same onsets (docs/decisions.md, "Implementation choices").
struct RealFft {
  static constexpr int kHalf = kNfft / 2;  // 1024

  // e^(-i pi k / 1024): real parts wr[k] and imaginary parts wi[k], k = 0 .. 1024, and the same
  // read backwards (wr_back[k] = wr[1024 - k]), so that both bins of a pair k, 1024 - k load their
  // factors in ascending k.
  struct Twiddles {
    std::vector<double> wr = std::vector<double>(kBins), wi = std::vector<double>(kBins);
    std::vector<double> wr_back = std::vector<double>(kBins), wi_back = std::vector<double>(kBins);
    Twiddles() {
      for (int k = 0; k < kBins; ++k) {
        const double a = kPi * k / (0.5 * kNfft);
        wr[static_cast<std::size_t>(k)] = std::cos(a);
        wi[static_cast<std::size_t>(k)] = -std::sin(a);
      }
      for (int k = 0; k < kBins; ++k) {
        wr_back[static_cast<std::size_t>(k)] = wr[static_cast<std::size_t>(kHalf - k)];
        wi_back[static_cast<std::size_t>(k)] = wi[static_cast<std::size_t>(kHalf - k)];
      }
    }
  };
  static const Twiddles& twiddles() {
    static const Twiddles t;
    return t;
  }

  // Four times the power, 4 |X_k|^2 = xr^2 + xi^2 below, k = 0 .. 1024, from Z (1024 values, and
  // room for one more) into power4 (the factor 1/4 is in the mel weights: a power of two, so
  // w (p / 4) and (w / 4) p are the same double).
  //
  // Bins k and r = 1024 - k are computed together, kLanes pairs at a time, from the same two
  // vectors of Z (Z[k ..] and Z[r ..], the latter reversed as it is loaded): with zr, zi the parts
  // of Z in double, bin k's terms are er = zr[k] + zr[r], ei = zi[k] - zi[r], orr = zi[k] + zi[r],
  // oi = zr[r] - zr[k], and bin r's are er, -ei, orr, -oi (the same sums, the differences negated:
  // IEEE rounding is symmetric, so they are the same values up to the sign of a zero, and so are
  // the sums and products made from them, whose squares are then the same). Each bin's value is
  // the formula's, with its twiddle factor, bit for bit:
  //   xr = er + (wr orr - wi oi),  xi = ei + (wr oi + wi orr),  4 |X|^2 = xr^2 + xi^2.
  static void power4(fftwf_complex* z, double* power4) {
    const Twiddles& tw = twiddles();
    z[kHalf][0] = z[0][0];
    z[kHalf][1] = z[0][1];
    const float* zf = &z[0][0];
    for (int k0 = 0; k0 < kHalf / 2; k0 += kLanes) {
      const int r0 = kHalf - k0 - (kLanes - 1);  // lane l: k = k0 + l, r = kHalf - k0 - l
      lanes::Floats vk, vr;
      std::memcpy(&vk, zf + 2 * static_cast<std::ptrdiff_t>(k0), sizeof vk);
      std::memcpy(&vr, zf + 2 * static_cast<std::ptrdiff_t>(r0), sizeof vr);
      LanesF kre, kim, rre, rim;
      lanes::deinterleave(vk, kre, kim);
      lanes::deinterleave_reversed(vr, rre, rim);
      const Lanes zkr = lanes::widen(kre), zki = lanes::widen(kim), zrr = lanes::widen(rre), zri = lanes::widen(rim);
      const Lanes er = zkr + zrr, ei = zki - zri, orr = zki + zri, oi = zrr - zkr;
      const Lanes wrk = lanes::load(&tw.wr[static_cast<std::size_t>(k0)]);
      const Lanes wik = lanes::load(&tw.wi[static_cast<std::size_t>(k0)]);
      const Lanes wrr = lanes::load(&tw.wr_back[static_cast<std::size_t>(k0)]);
      const Lanes wir = lanes::load(&tw.wi_back[static_cast<std::size_t>(k0)]);
      const Lanes xr = er + (wrk * orr - wik * oi), xi = ei + (wrk * oi + wik * orr);
      lanes::store(power4 + k0, xr * xr + xi * xi);
      // Bin r: er + (wr orr - wi (-oi)) and -ei + (wr (-oi) + wi orr).
      const Lanes yr = er + (wrr * orr + wir * oi), yi = (wir * orr - wrr * oi) - ei;
      lanes::store(power4 + r0, lanes::reversed(yr * yr + yi * yi));
    }
    // Bin 512, its own partner.
    const double zr = z[kHalf / 2][0], zi = z[kHalf / 2][1];
    const double wr = tw.wr[kHalf / 2], wi = tw.wi[kHalf / 2];
    const double er = zr + zr, ei = zi - zi, orr = zi + zi, oi = zr - zr;
    const double xr = er + (wr * orr - wi * oi), xi = ei + (wr * oi + wi * orr);
    power4[kHalf / 2] = xr * xr + xi * xi;
  }
};
static_assert((RealFft::kHalf / 2) % kLanes == 0, "whole vectors of bin pairs");
static_assert((kFrames - 1) * kHop + kNfft <= OnsetSignal::kMaxSpan, "a block's frames within one stretch");

// One plan, a frame's buffers, and the power spectra of kFrames frames.
struct SpectrogramBlock {
  static constexpr int kBlocks = (kBins + kLanes - 1) / kLanes;
  const fftwf_plan plan = fft_plan();
  FftBuffers fft;
  // rows[l * kRow + k]: frame l's bin k (the last block of kLanes padded with zeros).
  static constexpr int kRow = kBlocks * kLanes;
  std::vector<double> rows = std::vector<double>(static_cast<std::size_t>(kRow * kFrames), 0.0);
  // power[k * kFrames + l]: bin k of frame l (kVectors vectors per bin), so a band's weighted sum
  // is kVectors vector operations per bin for all kFrames frames, each frame's products still
  // summed in ascending bin order.
  std::vector<double> power = std::vector<double>(static_cast<std::size_t>(kRow * kFrames));

  // Frames t0 .. t0 + kFrames - 1 (those before `frames`; silence after) into power.
  void compute(OnsetSignal& y, long long t0, long long frames) {
    const long long n = y.size();
    const long long first = std::clamp(t0 * kHop - kNfft / 2, 0LL, n);
    const long long end = std::clamp((std::min(t0 + kFrames, frames) - 1) * kHop + kNfft / 2, first, n);
    const float* samples = y.samples(first, end);
    for (int l = 0; l < kFrames; ++l) {
      double* row = &rows[static_cast<std::size_t>(l * kRow)];
      if (t0 + l >= frames) {
        std::fill(row, row + kRow, 0.0);
        continue;
      }
      windowed_frame(samples, first, n, t0 + l, fft.in);
      fftwf_execute_dft(plan, reinterpret_cast<fftwf_complex*>(fft.in), fft.out);
      RealFft::power4(fft.out, row);
    }
    for (int b = 0; b < kBlocks; ++b)
      for (int v = 0; v < kVectors; ++v)
        lanes::transpose_block<Lanes>(&rows[static_cast<std::size_t>(v * kLanes * kRow + b * kLanes)], kRow,
                                      &power[static_cast<std::size_t>(b * kLanes * kFrames + v * kLanes)], kFrames);
  }
};

// onset_strength_multi on a band-major dB spectrogram S (band m's frames at S[m * stride ...]):
// diff with lag 1, half-wave rectified, mean over bands, giving frames - 1 values; then padded
// with lag + n_fft / (2 hop) = 3 zeros at the front and trimmed to `frames`. So envelope[t]
// (t >= 3) is the rise from spectrogram frame t - 3 to t - 2. (Centred frame t already sees an
// event n_fft / 2 = 2 hops before its centre, so with this shift the rise of a sharp onset at time
// T lands at about frame T * 22050 / 512, its own frame.) Values below floor_db count as floor_db;
// the sums run over the bands in order, frame by frame.
// The frames are taken kRiseBlock at a time, all bands for each block, so that the block's sums
// stay in the first-level cache however long the recording.
std::vector<float> rises(const double* S, long long frames, long long stride, double floor_db) {
  constexpr long long kPad = 1 + kNfft / (2 * kHop);
  constexpr long long kRiseBlock = 512;
  std::vector<float> env(static_cast<std::size_t>(frames), 0.0f);
  if (frames <= kPad) return env;
  const long long count = frames - kPad;  // envelope frames kPad .. frames - 1
  double acc[kRiseBlock];
  for (long long r0 = 0; r0 < count; r0 += kRiseBlock) {
    const long long n = std::min(kRiseBlock, count - r0);
    std::fill(acc, acc + n, 0.0);
    for (int m = 0; m < kMels; ++m) {
      const double* s = S + m * stride + r0;
      for (long long r = 0; r < n; ++r)
        acc[r] += std::max(0.0, std::max(s[r + 1], floor_db) - std::max(s[r], floor_db));
    }
    for (long long r = 0; r < n; ++r) env[static_cast<std::size_t>(r0 + r + kPad)] = static_cast<float>(acc[r] / kMels);
  }
  return env;
}

std::vector<float> envelope_of(OnsetSignal& y) {
  const long long frames = 1 + y.size() / kHop;
  const std::vector<MelBand>& bank = mel_bank();
  // dB, band-major (band m's frames are S[m * stride ...], the stride a whole number of blocks of
  // kFrames frames), so the envelope sums over bands for many frames at once.
  const long long stride = (frames + kFrames - 1) / kFrames * kFrames;
  // Every value is written below (the frames past the end as silence): left uninitialised.
  const std::unique_ptr<double[]> S(new double[static_cast<std::size_t>(stride * kMels)]);
  SpectrogramBlock block;
  // Lanes past the last frame see silence (-100 dB, no more than any real frame's value): they
  // leave the maximum as it is.
  Lanes max_db = Lanes{} - HUGE_VAL;
  for (long long t0 = 0; t0 < frames; t0 += kFrames) {
    block.compute(y, t0, frames);
    for (int m = 0; m < kMels; ++m) {
      const MelBand& band = bank[static_cast<std::size_t>(m)];
      const double* power = &block.power[static_cast<std::size_t>(band.first) * kFrames];
      Lanes acc[kVectors] = {};
      for (std::size_t k = 0; k < band.w.size(); ++k)
        for (int v = 0; v < kVectors; ++v)
          acc[v] += band.w[k] * lanes::load(power + k * kFrames + static_cast<std::size_t>(v) * kLanes);
      for (int v = 0; v < kVectors; ++v) {
        const Lanes db = power_to_db_lanes(acc[v]);
        std::memcpy(&S[static_cast<std::size_t>(m * stride + t0 + static_cast<long long>(v) * kLanes)], &db, sizeof db);
        max_db = select(max_db < db, db, max_db);
      }
    }
  }
  // top_db = 80 below the maximum of the whole spectrogram.
  double max_all = max_db[0];
  for (int l = 1; l < kLanes; ++l) max_all = std::max(max_all, max_db[l]);
  return rises(S.get(), frames, stride, max_all - 80.0);
}

}  // namespace

}  // namespace gmg::audio
