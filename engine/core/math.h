// Mathematical constants and the angle helpers every module shares.
#pragma once

#include <cmath>

namespace gmg {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;
inline constexpr double kDegToRad = kPi / 180.0;

// angle + k * 2 pi for the whole k that brings it nearest `reference` (radians). Unwrapping a
// sequence of angles applies this with the previous (unwrapped) angle as reference.
inline double wrap_near(double angle, double reference) {
  return angle + kTwoPi * std::round((reference - angle) / kTwoPi);
}

}  // namespace gmg
