// Polyphase resampling, after scipy.signal.resample_poly (scipy 1.x).
#include "audio/resample.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <numeric>
#include <string>

#include "engine/core/error.h"
#include "engine/core/math.h"

namespace gmg::audio {
namespace {

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
  const long long half_len = 10 * max_rate;
  const long long taps = 2 * half_len + 1;
  const long long phase_len = (taps + up - 1) / up;
  const std::shared_ptr<const std::vector<double>> filter = polyphase_filter(up, down);
  const std::vector<double>& phases = *filter;

  std::vector<float> y(static_cast<std::size_t>(n_out));
  // Output n's first tap: phase p = k0 % up, taps from t0 = k0 / up on, reading x from i0.
  const auto first_tap = [&](long long n, long long& p, long long& t0, long long& i0) {
    const long long base = n * down - half_len;  // xu index of tap k = 0
    long long k0 = ((-base) % up + up) % up;     // first tap with (base + k) divisible by up
    i0 = (base + k0) / up;                       // x index of tap k0 (may be negative)
    if (i0 < 0) {
      k0 += (-i0) * up;
      i0 = 0;
    }
    p = k0 % up;
    t0 = k0 / up;
  };
  const auto one = [&](long long n) {
    long long p = 0, t0 = 0, i0 = 0;
    first_tap(n, p, t0, i0);
    const double* hp = &phases[static_cast<std::size_t>(p * phase_len)];
    double acc = 0.0;
    for (long long t = t0, i = i0; p + t * up < taps && i < n_in; ++t, ++i) acc += hp[t] * x[static_cast<std::size_t>(i)];
    y[static_cast<std::size_t>(n)] = static_cast<float>(acc);
  };
  constexpr int kLanes = 8;
  long long n = 0;
  while (n < n_out) {
    // A block of outputs whose taps all start at t0 = 0 and lie inside x takes the fast path.
    long long p[kLanes], t0[kLanes], i0[kLanes];
    bool interior = n + kLanes <= n_out;
    for (int l = 0; l < kLanes && interior; ++l) {
      first_tap(n + l, p[l], t0[l], i0[l]);
      interior = t0[l] == 0 && i0[l] + phase_len <= n_in;
    }
    if (!interior) {
      one(n++);
      continue;
    }
    double acc[kLanes] = {};
    const double* hp[kLanes];
    const float* xp[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      hp[l] = &phases[static_cast<std::size_t>(p[l] * phase_len)];
      xp[l] = &x[static_cast<std::size_t>(i0[l])];
    }
    for (long long t = 0; t < phase_len; ++t)
      for (int l = 0; l < kLanes; ++l) acc[l] += hp[l][t] * static_cast<double>(xp[l][t]);
    for (int l = 0; l < kLanes; ++l) y[static_cast<std::size_t>(n + l)] = static_cast<float>(acc[l]);
    n += kLanes;
  }
  return y;
}

}  // namespace gmg::audio
