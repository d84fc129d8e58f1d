// Mathematical constants, the angle helpers and the smoothing every module shares.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace gmg {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;
inline constexpr double kDegToRad = kPi / 180.0;

// angle + k * 2 pi for the whole k that brings it nearest `reference` (radians). Unwrapping a
// sequence of angles applies this with the previous (unwrapped) angle as reference.
inline double wrap_near(double angle, double reference) {
  return angle + kTwoPi * std::round((reference - angle) / kTwoPi);
}

// Centred moving average over 2 * half + 1 samples, shrunk at the ends (each value the mean of the
// samples of its window that exist, summed in order).
inline std::vector<double> moving_average(const std::vector<double>& x, int half) {
  const int n = static_cast<int>(x.size());
  std::vector<double> y(x.size());
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    int count = 0;
    for (int k = std::max(0, i - half); k <= std::min(n - 1, i + half); ++k, ++count)
      sum += x[static_cast<std::size_t>(k)];
    y[static_cast<std::size_t>(i)] = sum / count;
  }
  return y;
}

}  // namespace gmg
