// Polyphase resampling, after scipy.signal.resample_poly (scipy 1.x).
#include "audio/resample.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <numeric>
#include <string>

#include "engine/core/error.h"
#include "engine/core/math.h"

namespace gmg::audio {
namespace {

// Eight doubles (and floats) as one vector (GCC and Clang vector extensions): lane-wise IEEE
// arithmetic, so each lane rounds exactly as the scalar code would (contraction is off).
using Lanes = double __attribute__((vector_size(64)));
using LanesF = float __attribute__((vector_size(32)));

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
struct Polyphase {
  static constexpr int kLanes = 8;
  const std::vector<float>& x;
  const std::vector<double>& phases;  // polyphase_filter(up, down)
  long long up, down;
  long long half_len = 10 * std::max(up, down);
  long long taps = 2 * half_len + 1;
  long long phase_len = (taps + up - 1) / up;
  long long n_in = static_cast<long long>(x.size());
  std::vector<float> xt{};  // a tile's stretch of x, transposed

  // Output n's first tap: phase p = k0 % up, taps from t0 = k0 / up on, reading x from i0.
  void first_tap(long long n, long long& p, long long& t0, long long& i0) const {
    const long long base = n * down - half_len;  // xu index of tap k = 0
    long long k0 = ((-base) % up + up) % up;     // first tap with (base + k) divisible by up
    i0 = (base + k0) / up;                       // x index of tap k0 (may be negative)
    if (i0 < 0) {
      k0 += (-i0) * up;
      i0 = 0;
    }
    p = k0 % up;
    t0 = k0 / up;
  }

  // Output n, its products summed in ascending tap order.
  float one(long long n) const {
    long long p = 0, t0 = 0, i0 = 0;
    first_tap(n, p, t0, i0);
    const double* hp = &phases[static_cast<std::size_t>(p * phase_len)];
    double acc = 0.0;
    for (long long t = t0, i = i0; p + t * up < taps && i < n_in; ++t, ++i)
      acc += hp[t] * x[static_cast<std::size_t>(i)];
    return static_cast<float>(acc);
  }

  // Whether every tap of outputs n .. n + 8 up - 1 lies inside x.
  bool tile_inside(long long n) const {
    long long p0 = 0, t0 = 0, x0 = 0, p1 = 0, t1 = 0, i1 = 0;
    first_tap(n, p0, t0, x0);
    first_tap(n + kLanes * up - 1, p1, t1, i1);
    return t0 == 0 && i1 + phase_len <= n_in;
  }

  // Outputs n + l * up (l = 0..7) share a phase and read x at i0 + l * down: a tile of 8 * up
  // outputs whose taps all lie inside x is computed phase by phase, eight outputs at once, from a
  // transposed copy of its stretch of x (xt[j][l] = x[x0 + l * down + j]), so the eight products
  // of a tap are one vector operation. Each output still sums its products in ascending tap order,
  // from 0.0, as one() does (a padding tap adds 0 * x, which leaves a nonzero sum as it is and can
  // only turn a sum of -0 into +0).
  void tile(long long n, std::vector<float>& y) {
    long long pj = 0, tj = 0, ij = 0, x0 = 0;
    first_tap(n + up - 1, pj, tj, ij);
    const long long last = ij;
    first_tap(n, pj, tj, x0);
    const long long width = last - x0 + phase_len;  // the stretch each lane reads
    xt.resize(static_cast<std::size_t>(width * kLanes));
    for (int l = 0; l < kLanes; ++l) {
      const float* src = &x[static_cast<std::size_t>(x0 + l * down)];
      for (long long j = 0; j < width; ++j) xt[static_cast<std::size_t>(j * kLanes + l)] = src[j];
    }
    // Output n + j's phase and first x index, stepped from output n's (one output further moves
    // the filter by `down` input-rate samples) instead of divided out for each.
    const long long step_phase = down % up, step_x = down / up;
    ij = x0;
    for (long long j = 0; j < up; ++j) {
      if (j > 0) {
        pj -= step_phase;
        ij += step_x;
        if (pj < 0) {
          pj += up;
          ++ij;
        }
      }
      const double* hp = &phases[static_cast<std::size_t>(pj * phase_len)];
      const float* xp = &xt[static_cast<std::size_t>((ij - x0) * kLanes)];
      Lanes acc = {};
      for (long long t = 0; t < phase_len; ++t) {
        LanesF xf;
        std::memcpy(&xf, xp + t * kLanes, sizeof xf);
        acc += hp[t] * __builtin_convertvector(xf, Lanes);
      }
      for (int l = 0; l < kLanes; ++l) y[static_cast<std::size_t>(n + j + l * up)] = static_cast<float>(acc[l]);
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
  // The filter has 20 taps per unit of the larger reduced rate: rates that share no factor make
  // it huge (10 MHz to 22050 Hz would need 2 * 10^8 taps), so it is bounded (the WAV reader's
  // rate limits stay far below).
  if (max_rate > kMaxReducedRate)
    throw Error("resample_poly: resampling from " + std::to_string(from_rate) + " Hz to " + std::to_string(to_rate) +
                " Hz needs a filter of " + std::to_string(20 * max_rate + 1) + " taps (at most " +
                std::to_string(20 * kMaxReducedRate + 1) + ")");
  const std::shared_ptr<const std::vector<double>> filter = polyphase_filter(up, down);
  Polyphase r{x, *filter, up, down};
  std::vector<float> y(static_cast<std::size_t>(n_out));
  const long long tile = Polyphase::kLanes * up;
  long long n = 0;
  while (n < n_out) {
    if (n + tile <= n_out && r.tile_inside(n)) {
      r.tile(n, y);
      n += tile;
    } else {
      y[static_cast<std::size_t>(n)] = r.one(n);
      ++n;
    }
  }
  return y;
}

}  // namespace gmg::audio
