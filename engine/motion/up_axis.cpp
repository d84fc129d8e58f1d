#include "engine/motion/up_axis.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/motion/motion_file.h"

namespace gmg {
namespace {

// The quarter turn about X that takes Z-up to Y-up: (x, y, z) -> (x, z, -y).
glm::dquat z_to_y() { return glm::dquat(std::sqrt(0.5), -std::sqrt(0.5), 0.0, 0.0); }

void turn_root(Motion& m, const glm::dquat& turn, glm::dvec3 (*map)(const glm::dvec3&)) {
  for (int f = 0; f < m.frame_count; ++f) {
    const std::size_t i = m.index(f, 0);
    m.rotations[i] = glm::normalize(turn * m.rotations[i]);
    m.translations[i] = map(m.translations[i]);
  }
  if (!m.euler_hints.empty())
    for (int f = 0; f < m.frame_count; ++f) m.euler_hints[m.index(f, 0)] = glm::dvec3(0.0);
}

glm::dvec3 z_up_to_y_up(const glm::dvec3& v) { return {v.x, v.z, -v.y}; }
glm::dvec3 y_up_to_z_up(const glm::dvec3& v) { return {v.x, -v.z, v.y}; }

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

UpAxis detect_up_axis(const Motion& m) {
  if (m.frame_count <= 0 || m.joint_count() < 2) return UpAxis::Y;
  const int samples = std::min(64, m.frame_count);
  const int joints = m.joint_count();
  std::vector<glm::dquat> rot(static_cast<std::size_t>(joints));
  std::vector<glm::dvec3> pos(static_cast<std::size_t>(joints));
  std::vector<double> extent_y, extent_z;
  for (int s = 0; s < samples; ++s) {
    const int f = static_cast<int>(static_cast<long long>(s) * (m.frame_count - 1) / std::max(1, samples - 1));
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    motion_world_pose(m, f, rot, pos);
    for (const glm::dvec3& p : pos) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    extent_y.push_back(hi.y - lo.y);
    extent_z.push_back(hi.z - lo.z);
  }
  motion_release_pages(m);
  return median(extent_z) > median(extent_y) ? UpAxis::Z : UpAxis::Y;
}

UpAxis resolve_up_axis(const Motion& m, UpChoice choice) {
  switch (choice) {
    case UpChoice::Y:
      return UpAxis::Y;
    case UpChoice::Z:
      return UpAxis::Z;
    case UpChoice::Auto:
      break;
  }
  return detect_up_axis(m);
}

Motion motion_read_y_up(const std::string& path, const std::string& skeleton) {
  Motion m = motion_read(path, skeleton);
  motion_to_y_up(m, detect_up_axis(m));
  return m;
}

void motion_to_y_up(Motion& m, UpAxis from) {
  if (from == UpAxis::Z) turn_root(m, z_to_y(), z_up_to_y_up);
}

void motion_from_y_up(Motion& m, UpAxis to) {
  if (to == UpAxis::Z) turn_root(m, glm::conjugate(z_to_y()), y_up_to_z_up);
}

glm::dvec3 to_y_up(const glm::dvec3& v, UpAxis from) { return from == UpAxis::Z ? z_up_to_y_up(v) : v; }
glm::dvec3 from_y_up(const glm::dvec3& v, UpAxis to) { return to == UpAxis::Z ? y_up_to_z_up(v) : v; }

}  // namespace gmg
