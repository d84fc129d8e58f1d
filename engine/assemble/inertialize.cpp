#include "engine/assemble/inertialize.h"

#include <cmath>

namespace gmg {

double spring_damping(double halflife_frames) { return 2.0 * std::log(2.0) / std::max(1e-6, halflife_frames); }

void spring_decay(glm::dvec3& x, glm::dvec3& v, double y, double dt) {
  const glm::dvec3 j1 = v + x * y;
  const double eydt = std::exp(-y * dt);
  x = eydt * (x + j1 * dt);
  v = eydt * (v - j1 * y * dt);
}

double spring_settle_frames(double y, double fraction) {
  // (1 + u) e^(-u) is decreasing for u > 0: bisect on u = y t.
  double lo = 0.0, hi = 1.0;
  while ((1.0 + hi) * std::exp(-hi) > fraction) hi *= 2.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((1.0 + mid) * std::exp(-mid) > fraction ? lo : hi) = mid;
  }
  return hi / y;
}

}  // namespace gmg
