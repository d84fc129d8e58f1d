// Polyphase resampling, after scipy.signal.resample_poly (scipy 1.x).
#include "audio/resample.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <numeric>
#include <string>

#include "audio/lanes.h"
#include "engine/core/error.h"
#include "engine/core/math.h"

namespace gmg::audio {
namespace {

using lanes::Lanes;
using lanes::LanesF;
// A row of the tile's float outputs as the transpose into place reads it: a register of floats, at
// most 32 bytes (blocks of 8 x 8 floats with AVX and AVX-512, 4 x 4 with SSE2).
constexpr int kRowBytes = lanes::kBytes < 32 ? lanes::kBytes : 32;
constexpr int kRowFloats = kRowBytes / static_cast<int>(sizeof(float));
using RowF = float __attribute__((vector_size(kRowBytes)));

// 192 kHz against a coprime target rate: the WAV reader's highest rate.
constexpr long long kMaxReducedRate = 192000;

// The filter scipy designs, firwin(2 * half_len + 1, 1 / max_rate, ('kaiser', 5.0)) times up, with
// the taps of one phase (k = p, p + up, ...) stored together and zero padded to the longest phase.
std::vector<double> make_polyphase_filter(long long up, long long down) {
  const long long max_rate = std::max(up, down);
  const long long half_len = 10 * max_rate;
  const long long taps = 2 * half_len + 1;
  std::vector<double> h = firwin_kaiser(static_cast<int>(taps), 1.0 / static_cast<double>(max_rate), 5.0);
  for (double& v : h) v *= static_cast<double>(up);
  const long long phase_len = (taps + up - 1) / up;
  std::vector<double> phases(static_cast<std::size_t>(up * phase_len), 0.0);
  for (long long k = 0; k < taps; ++k)
    phases[static_cast<std::size_t>((k % up) * phase_len + k / up)] = h[static_cast<std::size_t>(k)];
  return phases;
}

// Designing the filter costs more than resampling a short clip (a Bessel function per tap), and a
// run resamples every clip between the same two rates: the last few designs are kept.
std::shared_ptr<const std::vector<double>> polyphase_filter(long long up, long long down) {
  struct Entry {
    long long up, down;
    std::shared_ptr<const std::vector<double>> phases;
  };
  static std::mutex mutex;
  static std::vector<Entry> cache;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    for (const Entry& e : cache)
      if (e.up == up && e.down == down) return e.phases;
  }
  auto phases = std::make_shared<const std::vector<double>>(make_polyphase_filter(up, down));
  const std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() >= 4) cache.erase(cache.begin());
  cache.push_back({up, down, phases});
  return phases;
}

// The polyphase form of the resampler for one signal and filter (scipy's alignment, see
// resample_poly): output n is sum_k h[k] * xu[n * down + k - half_len].
//
// Outputs n + l * up (l = 0 .. kLanes - 1) share a phase and read x at i0 + l * down: a tile of
// kLanes * up outputs is computed phase by phase, kLanes outputs at once (kVectors vectors of
// lanes::kWidth doubles), from a transposed copy of its stretch of x converted to double
// (xt[j][l] = x[x0 + l * down + j], zero outside x), so the kLanes products of a tap are kVectors
// vector operations. Two phases are summed side by side: each sum is a chain of dependent
// additions, and 2 kVectors (four with AVX-512, eight otherwise) independent chains keep the adder
// busy where one would wait on its own latency. Each output still sums its products in ascending
// tap order, from 0.0, as the formula does: a tap outside x adds h * 0 = +-0, which leaves a sum
// of +0 before the first real product as +0 and a nonzero sum as it is (it can only turn a sum of
// -0 into +0, after the last one). Which phases are paired depends on the output's index modulo
// up only, not on kLanes, so neither does any output's sum.
struct Polyphase {
  // Sixteen outputs per phase in two vectors with AVX-512 or four with AVX; eight in four with
  // SSE2, whose sixteen registers could not hold the sixteen sums of sixteen outputs.
  static constexpr int kLanes = lanes::kWidth >= 4 ? 16 : 8;
  static constexpr int kVectors = kLanes / lanes::kWidth;
  static_assert(kLanes % kRowFloats == 0, "a tile's lanes are whole blocks of the transpose");
  const std::vector<float>& x;
  const std::vector<double>& phases;  // polyphase_filter(up, down)
  long long up, down;
  long long half_len = 10 * std::max(up, down);
  long long taps = 2 * half_len + 1;
  long long phase_len = (taps + up - 1) / up;
  long long n_in = static_cast<long long>(x.size());
  std::vector<double> xt{};  // a tile's stretch of x, transposed
  std::vector<float> yt{};   // a tile's outputs, transposed

  // Output n's tap k = p (its phase, 0 <= p < up) is the first to land on a sample of xu: it reads
  // x at i0 (negative before the signal starts).
  void first_tap(long long n, long long& p, long long& i0) const {
    const long long base = n * down - half_len;  // xu index of tap k = 0
    p = ((-base) % up + up) % up;
    i0 = (base + p) / up;  // exact
  }

  // Outputs n .. n + count - 1 (count <= kLanes * up) into out[0 .. count).
  void tile(long long n, long long count, float* out) {
    long long p = 0, x0 = 0, p_last = 0, x_last = 0;
    first_tap(n + up - 1, p_last, x_last);
    first_tap(n, p, x0);
    const long long width = x_last - x0 + phase_len;  // the stretch each lane reads
    xt.resize(static_cast<std::size_t>(width * kLanes));
    if (x0 >= 0 && x0 + (kLanes - 1) * down + width <= n_in) {
      // Inside x (all but the first and last tiles): lane l reads the contiguous stretch
      // x[x0 + l * down ...], so xt is the transpose of kLanes such rows, taken in blocks of
      // kWidth x kWidth floats transposed in registers and converted to double, the last
      // width % kWidth rows one by one.
      const float* src = &x[static_cast<std::size_t>(x0)];
      long long j0 = 0;
      for (; j0 + lanes::kWidth <= width; j0 += lanes::kWidth) {
        for (int l0 = 0; l0 < kLanes; l0 += lanes::kWidth) {
          double* dst = &xt[static_cast<std::size_t>(j0 * kLanes + l0)];
          lanes::transpose<Lanes>(
              [&](int l) { return lanes::load_widened(src + (l0 + l) * down + j0); },
              [&](int i, const Lanes& v) { std::memcpy(dst + static_cast<std::ptrdiff_t>(i) * kLanes, &v, sizeof v); });
        }
      }
      for (long long j = j0; j < width; ++j) {
        double* row = &xt[static_cast<std::size_t>(j * kLanes)];
        for (int l = 0; l < kLanes; ++l) row[l] = static_cast<double>(src[j + l * down]);
      }
    } else {
      for (long long j = 0; j < width; ++j) {
        for (int l = 0; l < kLanes; ++l) {
          const long long i = x0 + l * down + j;
          xt[static_cast<std::size_t>(j * kLanes + l)] =
              (i >= 0 && i < n_in) ? static_cast<double>(x[static_cast<std::size_t>(i)]) : 0.0;
        }
      }
    }
    // Output n + j's phase and first x index, stepped from output n's (one output further moves
    // the filter by `down` input-rate samples) instead of divided out for each.
    const long long step_phase = down % up, step_x = down / up;
    const auto step = [&](long long& pj, long long& ij) {
      pj -= step_phase;
      ij += step_x;
      if (pj < 0) {
        pj += up;
        ++ij;
      }
    };
    // Output n + j + l * up goes to yt[j][l] (kLanes floats per phase, kVectors vector stores),
    // and the tile is transposed into y at the end, where lane l's outputs are contiguous.
    yt.resize(static_cast<std::size_t>(up * kLanes));
    const auto store = [&](long long j, const Lanes(&acc)[kVectors]) {
      for (int v = 0; v < kVectors; ++v) {
        const LanesF f = __builtin_convertvector(acc[v], LanesF);
        std::memcpy(&yt[static_cast<std::size_t>(j * kLanes + static_cast<long long>(v) * lanes::kWidth)], &f,
                    sizeof f);
      }
    };
    long long pa = p, ia = x0;
    for (long long j = 0; j < up; j += 2) {
      if (j > 0) step(pa, ia);
      long long pb = pa, ib = ia;
      const bool two = j + 1 < up;
      if (two) step(pb, ib);
      const double* ha = &phases[static_cast<std::size_t>(pa * phase_len)];
      const double* hb = &phases[static_cast<std::size_t>((two ? pb : pa) * phase_len)];
      const double* xa = &xt[static_cast<std::size_t>((ia - x0) * kLanes)];
      const double* xb = &xt[static_cast<std::size_t>(((two ? ib : ia) - x0) * kLanes)];
      // Phase p has (taps - p + up - 1) / up real taps (the longest phase_len): the padding taps
      // after them are left out.
      const long long len = (taps - std::min(pa, two ? pb : pa) + up - 1) / up;
      Lanes a[kVectors] = {}, b[kVectors] = {};
      for (long long t = 0; t < len; ++t) {
        for (int v = 0; v < kVectors; ++v) {
          Lanes va, vb;
          std::memcpy(&va, xa + t * kLanes + static_cast<long long>(v) * lanes::kWidth, sizeof va);
          std::memcpy(&vb, xb + t * kLanes + static_cast<long long>(v) * lanes::kWidth, sizeof vb);
          a[v] += ha[t] * va;
          b[v] += hb[t] * vb;
        }
      }
      store(j, a);
      if (two) store(j + 1, b);
      pa = two ? pb : pa;
      ia = two ? ib : ia;
    }
    if (count == kLanes * up) {
      // Blocks of kRowFloats phases x kRowFloats lanes transposed in registers, the rest one by one.
      float* dst = out;
      long long j0 = 0;
      for (; j0 + kRowFloats <= up; j0 += kRowFloats) {
        for (int l0 = 0; l0 < kLanes; l0 += kRowFloats) {
          lanes::transpose_block<RowF>(&yt[static_cast<std::size_t>(j0 * kLanes + l0)], kLanes, dst + l0 * up + j0, up);
        }
      }
      for (int l = 0; l < kLanes; ++l)
        for (long long j = j0; j < up; ++j) dst[l * up + j] = yt[static_cast<std::size_t>(j * kLanes + l)];
    } else {
      for (int l = 0; l < kLanes; ++l)
        for (long long j = 0; j < up && l * up + j < count; ++j)
          out[l * up + j] = yt[static_cast<std::size_t>(j * kLanes + l)];
    }
  }
};

}  // namespace

// Power series; the arguments here are at most the Kaiser beta, 5, where it converges in ~20 terms.
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

std::vector<double> firwin_kaiser(int numtaps, double cutoff, double beta) {
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

struct PolyphaseResampler::Impl {
  std::shared_ptr<const std::vector<double>> filter;
  Polyphase polyphase;
  long long n_out;
};

PolyphaseResampler::PolyphaseResampler(const std::vector<float>& x, int from_rate, int to_rate) {
  if (from_rate <= 0 || to_rate <= 0) {
    throw Error("resample_poly: sample rates must be positive (from " + std::to_string(from_rate) + " to " +
                std::to_string(to_rate) + ")");
  }
  const long long g = std::gcd(from_rate, to_rate);
  const long long up = to_rate / g, down = from_rate / g;
  const long long n_in = static_cast<long long>(x.size());
  const long long n_out = (n_in * up + down - 1) / down;  // ceil(n_in * up / down)

  // The filter scipy designs: firwin(2 * half_len + 1, 1 / max_rate,
  // ('kaiser', 5.0)) times up.
  const long long max_rate = std::max(up, down);
  // The filter has 20 taps per unit of the larger reduced rate: rates that share no factor make
  // it huge (10 MHz to 22050 Hz would need 2 * 10^8 taps), so it is bounded (the WAV reader's
  // rate limits stay far below).
  if (max_rate > kMaxReducedRate)
    throw Error("resample_poly: resampling from " + std::to_string(from_rate) + " Hz to " + std::to_string(to_rate) +
                " Hz needs a filter of " + std::to_string(20 * max_rate + 1) + " taps (at most " +
                std::to_string(20 * kMaxReducedRate + 1) + ")");
  std::shared_ptr<const std::vector<double>> filter = polyphase_filter(up, down);
  const std::vector<double>& phases = *filter;
  impl_.reset(new Impl{std::move(filter), Polyphase{x, phases, up, down}, n_out});
}

PolyphaseResampler::~PolyphaseResampler() = default;

long long PolyphaseResampler::size() const { return impl_->n_out; }

long long PolyphaseResampler::block() const { return Polyphase::kLanes * impl_->polyphase.up; }

void PolyphaseResampler::compute(long long n, long long count, float* out) {
  const long long tile = block();
  for (long long i = 0; i < count; i += tile) impl_->polyphase.tile(n + i, std::min(tile, count - i), out + i);
}

std::vector<float> resample_poly(const std::vector<float>& x, int from_rate, int to_rate) {
  if (from_rate > 0 && from_rate == to_rate) return x;
  PolyphaseResampler r(x, from_rate, to_rate);
  std::vector<float> y(static_cast<std::size_t>(r.size()));
  r.compute(0, r.size(), y.data());
  return y;
}

}  // namespace gmg::audio
