#include "engine/motion/rotation.h"

#include <cctype>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/math.h"

namespace gmg {
namespace {

glm::dvec3 unit_axis(int axis) {
  glm::dvec3 a(0.0);
  a[axis] = 1.0;
  return a;
}

// Rotation matrix element R[row][col] (row-major meaning) of a unit quaternion.
double matrix_element(const glm::dmat3& m, int row, int col) { return m[col][row]; }

// True for the cyclic orders XYZ, YZX, ZXY.
bool is_cyclic(const EulerOrder& o) { return (o[0] + 1) % 3 == o[1] && (o[1] + 1) % 3 == o[2]; }

}  // namespace

EulerOrder euler_order_from_string(const std::string& text) {
  if (text.size() != 3) throw Error("invalid rotation order '" + text + "': expected three of X, Y, Z");
  EulerOrder order{};
  bool seen[3] = {false, false, false};
  for (int i = 0; i < 3; ++i) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(text[i])));
    if (c < 'X' || c > 'Z' || seen[c - 'X'])
      throw Error("invalid rotation order '" + text + "': expected a permutation of X, Y, Z");
    seen[c - 'X'] = true;
    order[i] = c - 'X';
  }
  return order;
}

std::string euler_order_to_string(const EulerOrder& order) {
  std::string s;
  for (int axis : order) s.push_back(static_cast<char>('X' + axis));
  return s;
}

glm::dquat euler_to_quat(const glm::dvec3& angles, const EulerOrder& order) {
  glm::dquat q(1.0, 0.0, 0.0, 0.0);
  for (int i = 0; i < 3; ++i) q = q * glm::angleAxis(angles[i], unit_axis(order[i]));
  return glm::normalize(q);
}

glm::dvec3 quat_to_euler(const glm::dquat& q, const EulerOrder& order) {
  // R = R_i(a) R_j(b) R_k(c). For a cyclic order R[i][k] = sin(b); for the others -sin(b).
  // The remaining angles follow from the row i and column k of R (Shoemake's scheme).
  const glm::dmat3 m = glm::mat3_cast(glm::normalize(q));
  const int i = order[0], j = order[1], k = order[2];
  const double s = is_cyclic(order) ? 1.0 : -1.0;
  const double sin_b = glm::clamp(s * matrix_element(m, i, k), -1.0, 1.0);
  glm::dvec3 out;
  out[1] = std::asin(sin_b);
  if (std::abs(sin_b) < 1.0 - 1e-12) {
    out[0] = std::atan2(-s * matrix_element(m, j, k), matrix_element(m, k, k));
    out[2] = std::atan2(-s * matrix_element(m, i, j), matrix_element(m, i, i));
  } else {
    // Gimbal lock: only a +/- c is determined; put it all in a.
    out[2] = 0.0;
    out[0] = std::atan2(s * matrix_element(m, k, j), matrix_element(m, j, j));
  }
  return out;
}

glm::dvec3 quat_to_euler_near(const glm::dquat& q, const EulerOrder& order, const glm::dvec3& previous) {
  const glm::dvec3 first = quat_to_euler(q, order);
  // The other solution of the same rotation: (a + pi, pi - b, c + pi), wrapped to (-pi, pi].
  glm::dvec3 second(first[0] + kPi, kPi - first[1], first[2] + kPi);
  for (int a = 0; a < 3; ++a) second[a] = wrap_near(second[a], 0.0);
  // Choose by angular distance (2*pi wraps are free), so a curve passing +/-180 degrees keeps
  // its solution branch; the values themselves stay in (-pi, pi] as most tools write them.
  auto distance = [&](const glm::dvec3& e) {
    double d = 0.0;
    for (int a = 0; a < 3; ++a) d += std::abs(wrap_near(e[a], previous[a]) - previous[a]);
    return d;
  };
  return distance(second) < distance(first) ? second : first;
}

glm::dvec3 quat_to_euler_matching(const glm::dquat& q, const EulerOrder& order, const glm::dvec3& reference) {
  const glm::dvec3 first = quat_to_euler(q, order);
  const glm::dvec3 second(first[0] + kPi, kPi - first[1], first[2] + kPi);
  glm::dvec3 best(0.0);
  double best_distance = -1.0;
  for (const glm::dvec3& candidate : {first, second}) {
    glm::dvec3 wrapped;
    double d = 0.0;
    for (int a = 0; a < 3; ++a) {
      wrapped[a] = wrap_near(candidate[a], reference[a]);
      d += std::abs(wrapped[a] - reference[a]);
    }
    if (best_distance < 0.0 || d < best_distance) {
      best = wrapped;
      best_distance = d;
    }
  }
  return best;
}

glm::dquat expmap_to_quat(const glm::dvec3& v) {
  const double angle = glm::length(v);
  if (angle < 1e-8) {
    // Taylor expansion keeps the result smooth and exactly unit length near zero.
    return glm::normalize(glm::dquat(1.0 - angle * angle / 8.0, 0.5 * v.x, 0.5 * v.y, 0.5 * v.z));
  }
  const glm::dvec3 axis = v / angle;
  const double s = std::sin(0.5 * angle);
  return glm::dquat(std::cos(0.5 * angle), s * axis.x, s * axis.y, s * axis.z);
}

glm::dvec3 quat_to_expmap(const glm::dquat& q_in) {
  glm::dquat q = glm::normalize(q_in);
  if (q.w < 0.0) q = -q;  // same rotation; keeps the angle in [0, pi]
  const glm::dvec3 xyz(q.x, q.y, q.z);
  const double s = glm::length(xyz);
  if (s < 1e-12) return 2.0 * xyz;  // angle ~ 2*s, axis ~ xyz/s
  const double angle = 2.0 * std::atan2(s, q.w);
  return xyz * (angle / s);
}

glm::dquat slerp_shortest(const glm::dquat& a, const glm::dquat& b_in, double t) {
  glm::dquat b = b_in;
  double cos_theta = glm::dot(a, b);
  if (cos_theta < 0.0) {
    b = -b;
    cos_theta = -cos_theta;
  }
  if (cos_theta > 1.0 - 1e-9) return glm::normalize(a * (1.0 - t) + b * t);
  const double theta = std::acos(glm::clamp(cos_theta, -1.0, 1.0));
  const double sin_theta = std::sin(theta);
  const double wa = std::sin((1.0 - t) * theta) / sin_theta;
  const double wb = std::sin(t * theta) / sin_theta;
  return glm::normalize(a * wa + b * wb);
}

double rotation_angle(const glm::dquat& q) {
  return 2.0 * std::atan2(std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z), std::abs(q.w));
}

double rotation_angle_between(const glm::dquat& a, const glm::dquat& b) {
  const double d = std::abs(glm::dot(glm::normalize(a), glm::normalize(b)));
  return 2.0 * std::acos(glm::clamp(d, 0.0, 1.0));
}

}  // namespace gmg
