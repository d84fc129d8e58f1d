// Polyphase resampling, after scipy.signal.resample_poly (scipy 1.x).
#include "audio/resample.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "engine/core/error.h"
#include "engine/core/math.h"

namespace gmg::audio {
namespace {

// 192 kHz against a coprime target rate: the WAV reader's highest rate.
constexpr long long kMaxReducedRate = 192000;

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

}  // namespace gmg::audio
