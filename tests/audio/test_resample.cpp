// Tests of audio/resample: scipy.signal.resample_poly's filter, lengths and phase.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "audio/resample.h"
#include "engine/core/error.h"
#include "engine/core/math.h"

namespace {

using gmg::kPi;

// ---------------------------------------------------------------------------
// The filter design.

TEST(Resample, BesselI0KnownValues) {
  // I0(x) = sum_k ((x/2)^k / k!)^2; I0(1) and I0(5) from Abramowitz & Stegun, table 9.8
  // (e^-x I0(x) = 0.4657596077 at 1, 0.1835408126 at 5).
  EXPECT_EQ(gmg::audio::bessel_i0(0.0), 1.0);
  EXPECT_NEAR(gmg::audio::bessel_i0(1.0), 0.4657596077 * std::exp(1.0), 1e-9);
  EXPECT_NEAR(gmg::audio::bessel_i0(5.0), 0.1835408126 * std::exp(5.0), 1e-8);
  // The first terms by hand at x = 0.5, ((1/4)^k / k!)^2: 1 + 1/16 + 1/1024 + 1/147456 +
  // 1/37748736; the next is 6.6e-11.
  EXPECT_NEAR(gmg::audio::bessel_i0(0.5), 1.0 + 1.0 / 16 + 1.0 / 1024 + 1.0 / 147456 + 1.0 / 37748736, 1e-10);
  EXPECT_EQ(gmg::audio::bessel_i0(-2.0), gmg::audio::bessel_i0(2.0));  // even
}

TEST(Resample, FirwinByHand) {
  // beta 0 is a rectangular window: 3 taps at cutoff 0.5 are 0.5 sinc(0.5 m), m = -1, 0, 1,
  // i.e. 1/pi, 1/2, 1/pi, then scaled to sum 1.
  const std::vector<double> h = gmg::audio::firwin_kaiser(3, 0.5, 0.0);
  const double sum = 0.5 + 2.0 / kPi;
  ASSERT_EQ(h.size(), 3u);
  EXPECT_NEAR(h[0], (1.0 / kPi) / sum, 1e-15);
  EXPECT_NEAR(h[1], 0.5 / sum, 1e-15);
  EXPECT_NEAR(h[2], (1.0 / kPi) / sum, 1e-15);
  // One tap is the identity filter.
  EXPECT_EQ(gmg::audio::firwin_kaiser(1, 0.3, 5.0), std::vector<double>{1.0});
  // Any design: symmetric, unit gain at DC, the Kaiser window tapering the ends.
  const std::vector<double> g = gmg::audio::firwin_kaiser(41, 0.1, 5.0);
  EXPECT_NEAR(std::accumulate(g.begin(), g.end(), 0.0), 1.0, 1e-12);
  for (std::size_t i = 0; i < g.size(); ++i) EXPECT_EQ(g[i], g[g.size() - 1 - i]) << i;
  EXPECT_EQ(std::max_element(g.begin(), g.end()) - g.begin(), 20);
  // Tap 1 against the centre tap (the normalisation cancels): m = -19, so the sinc is
  // sin(1.9 pi) / (1.9 pi) and the window I0(5 sqrt(1 - 0.95^2)) / I0(5); both are 1 at the centre.
  const double sinc = std::sin(1.9 * kPi) / (1.9 * kPi);
  const double window = gmg::audio::bessel_i0(5.0 * std::sqrt(1.0 - 0.95 * 0.95)) / gmg::audio::bessel_i0(5.0);
  EXPECT_NEAR(g[1] / g[20], sinc * window, 1e-12);
}

// ---------------------------------------------------------------------------
// Resampling.

TEST(Resample, SineKeepsFrequencyAndAmplitude) {
  std::vector<float> x(16000);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = static_cast<float>(0.5 * std::sin(2 * kPi * 440.0 * i / 16000.0));
  const std::vector<float> y = gmg::audio::resample_poly(x, 16000, 22050);
  ASSERT_EQ(y.size(), 22050u);
  double max_err = 0.0;
  for (std::size_t n = 1000; n + 1000 < y.size(); ++n) {
    const double expect = 0.5 * std::sin(2 * kPi * 440.0 * n / 22050.0);
    max_err = std::max(max_err, std::fabs(y[n] - expect));
  }
  EXPECT_LT(max_err, 1e-3);

  // Downsampling 44100 -> 22050 (up 1, down 2) too.
  std::vector<float> x2(44100);
  for (std::size_t i = 0; i < x2.size(); ++i)
    x2[i] = static_cast<float>(0.5 * std::sin(2 * kPi * 1000.0 * i / 44100.0));
  const std::vector<float> y2 = gmg::audio::resample_poly(x2, 44100, 22050);
  ASSERT_EQ(y2.size(), 22050u);
  max_err = 0.0;
  for (std::size_t n = 100; n + 100 < y2.size(); ++n) {
    max_err = std::max(max_err, std::fabs(y2[n] - 0.5 * std::sin(2 * kPi * 1000.0 * n / 22050.0)));
  }
  EXPECT_LT(max_err, 1e-3);
}

TEST(Resample, OutputLength) {
  struct Case {
    int from, to;
  };
  for (Case c : {Case{16000, 22050}, Case{44100, 22050}, Case{48000, 22050}, Case{8000, 22050}, Case{22050, 16000}}) {
    const long long g = std::gcd(c.from, c.to), up = c.to / g, down = c.from / g;
    for (std::size_t n : {1u, 2u, 7u, 320u, 321u, 1000u, 12345u}) {
      std::vector<float> x(n, 0.1f);
      const std::size_t expect = static_cast<std::size_t>((static_cast<long long>(n) * up + down - 1) / down);
      EXPECT_EQ(gmg::audio::resample_poly(x, c.from, c.to).size(), expect) << c.from << "->" << c.to << " n=" << n;
    }
  }
  std::vector<float> x{0.1f, 0.2f, 0.3f};
  EXPECT_EQ(gmg::audio::resample_poly(x, 22050, 22050), x);
  EXPECT_TRUE(gmg::audio::resample_poly({}, 16000, 22050).empty());
  EXPECT_THROW(gmg::audio::resample_poly(x, 0, 22050), gmg::Error);
  EXPECT_THROW(gmg::audio::resample_poly(x, 16000, -1), gmg::Error);
}

TEST(Resample, ConstantStaysConstant) {
  for (int from : {16000, 48000, 44100}) {
    std::vector<float> x(static_cast<std::size_t>(from), 0.3f);
    const std::vector<float> y = gmg::audio::resample_poly(x, from, 22050);
    double max_err = 0.0;
    for (std::size_t n = 2000; n + 2000 < y.size(); ++n) max_err = std::max(max_err, std::fabs(y[n] - 0.3));
    EXPECT_LT(max_err, 1e-3) << from;
  }
}

TEST(Resample, ZeroPhaseImpulse) {
  // An impulse at input sample 800 (time 0.05 s at 16 kHz) comes out as a
  // symmetric pulse whose peak is at output sample 0.05 * 22050 = 1102.5:
  // samples 1102 and 1103 carry the same weight.
  std::vector<float> x(1600, 0.0f);
  x[800] = 1.0f;
  const std::vector<float> y = gmg::audio::resample_poly(x, 16000, 22050);
  std::size_t arg = 0;
  for (std::size_t n = 0; n < y.size(); ++n)
    if (y[n] > y[arg]) arg = n;
  EXPECT_TRUE(arg == 1102 || arg == 1103) << arg;
  EXPECT_NEAR(y[1102], y[1103], 1e-3);
  EXPECT_NEAR(y[1100], y[1105], 1e-3);
  // 16000 -> 32000: the impulse lands exactly on output sample 1600 with the
  // filter's centre tap (up * cutoff = 1, times the DC normalisation).
  const std::vector<float> z = gmg::audio::resample_poly(x, 16000, 32000);
  EXPECT_NEAR(z[1600], 1.0, 2e-3);
  EXPECT_NEAR(z[1601], z[1599], 1e-6);
}

// The formula the resampler evaluates, one output at a time, its products summed in ascending
// tap order (the order the tiled, vectorised resampler keeps):
//   y[n] = sum_k h[k] * xu[n * down + k - half_len],  xu = x with up - 1 zeros after each sample.
std::vector<float> resample_by_formula(const std::vector<float>& x, int from, int to) {
  const long long g = std::gcd(from, to), up = to / g, down = from / g;
  const long long half_len = 10 * std::max(up, down), taps = 2 * half_len + 1;
  std::vector<double> h = gmg::audio::firwin_kaiser(static_cast<int>(taps), 1.0 / std::max(up, down), 5.0);
  for (double& v : h) v *= static_cast<double>(up);
  const long long n_in = static_cast<long long>(x.size()), n_out = (n_in * up + down - 1) / down;
  std::vector<float> y(static_cast<std::size_t>(n_out));
  for (long long n = 0; n < n_out; ++n) {
    double acc = 0.0;
    for (long long k = 0; k < taps; ++k) {
      const long long u = n * down + k - half_len;
      if (u < 0 || u % up != 0 || u / up >= n_in) continue;
      acc += h[static_cast<std::size_t>(k)] * x[static_cast<std::size_t>(u / up)];
    }
    y[static_cast<std::size_t>(n)] = static_cast<float>(acc);
  }
  return y;
}

TEST(Resample, EveryOutputIsTheFormulasBitForBit) {
  std::vector<float> x(9000);
  unsigned state = 12345;
  for (float& v : x) {
    state = state * 1103515245u + 12345u;
    v = static_cast<float>(static_cast<int>(state >> 16 & 0x7fff) - 16384) / 16384.0f;
  }
  // Rates whose reduced ratios give a tile of 8 outputs (44100 -> 22050) up to 3528 (16000 ->
  // 22050), downsampling and upsampling, and signals too short for any tile.
  for (const auto& [from, to] : {std::pair{16000, 22050}, std::pair{44100, 22050}, std::pair{48000, 22050},
                                 std::pair{8000, 22050}, std::pair{22050, 16000}, std::pair{11025, 22050}})
    for (std::size_t n : {std::size_t{7}, std::size_t{700}, x.size()}) {
      const std::vector<float> part(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(n));
      const std::vector<float> got = gmg::audio::resample_poly(part, from, to);
      const std::vector<float> want = resample_by_formula(part, from, to);
      ASSERT_EQ(got.size(), want.size());
      std::size_t differ = 0;
      for (std::size_t i = 0; i < got.size(); ++i) differ += got[i] == want[i] ? 0 : 1;
      EXPECT_EQ(differ, 0u) << from << " -> " << to << ", " << n << " samples";
    }
}

}  // namespace
